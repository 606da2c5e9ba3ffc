// SignalBridge on models the runtime did not load: two prefixed copies of the cart-pole merged into one
// scene with <include>, loaded by plain mj_loadXML, each driven through its own bridge, move exactly as the
// same model does in a Simulation of its own; a wrong prefix or a broken manifest is a LoadError.
#include "openplx/runtime/signal_bridge.h"
#include "openplx/runtime/simulation.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace {

namespace rt = openplx::runtime;
namespace fs = std::filesystem;

const std::string kCartPole = std::string(OPENPLX_SAMPLES_DIR) + "/cart_pole.openplx";

void emit(const fs::path& out, const std::string& prefix) {
  std::ostringstream text, errors;
  ASSERT_EQ(
      openplx::cli::run({kCartPole, "-o", out.string(), "--prefix", prefix, "--no-keyframe"}, text, errors),
      0)
      << errors.str();
}

struct Scene {
  mjModel* m = nullptr;
  mjData* d = nullptr;
  explicit Scene(const fs::path& dir) {
    fs::copy_file(fs::path(OPENPLX_SAMPLES_DIR) / "merged_scene.xml", dir / "merged_scene.xml");
    emit(dir / "left_cart_pole.xml", "left/");
    emit(dir / "right_cart_pole.xml", "right/");
    char error[1000] = "";
    m = mj_loadXML((dir / "merged_scene.xml").c_str(), nullptr, error, sizeof(error));
    EXPECT_NE(m, nullptr) << error;
    if (m) d = mj_makeData(m);
  }
  ~Scene() {
    if (d) mj_deleteData(d);
    if (m) mj_deleteModel(m);
  }
};

TEST(SignalBridge, TwoCopiesInOneSceneMoveAsTheModelDoesAlone) {
  const openplx::testing::ScratchDir dir;
  Scene scene(dir.path());
  ASSERT_NE(scene.m, nullptr);
  rt::SignalBridge left =
      rt::SignalBridge::attach((dir / "left_cart_pole.signals.json").string(), scene.m, scene.d);
  rt::SignalBridge right =
      rt::SignalBridge::attach((dir / "right_cart_pole.signals.json").string(), scene.m, scene.d);
  rt::Simulation alone = rt::Simulation::load(kCartPole);
  left.input("push").set(5.0);
  right.input("push").set(-5.0);
  alone.input("push").set(5.0);
  for (int k = 0; k < 500; ++k) {
    left.before_step();
    right.before_step();
    mj_step(scene.m, scene.d);
    left.after_step();
    right.after_step();
    alone.step();
  }
  // The scene has contacts off and the copies never touch each other's joints: the left copy is the model.
  EXPECT_NEAR(left.output("cart_position").real(), alone.output("cart_position").real(), 1e-12);
  EXPECT_NEAR(left.output("pole_angle").real(), alone.output("pole_angle").real(), 1e-12);
  EXPECT_GT(left.output("cart_position").real(), 0.5);
  EXPECT_LT(right.output("cart_position").real(), -0.5);
  EXPECT_EQ(left.inputs().size(), alone.inputs().size());
  EXPECT_THROW(left.input("no_such_input"), rt::SignalError);
}

TEST(SignalBridge, WrongPrefixOrBrokenManifestIsALoadError) {
  const openplx::testing::ScratchDir dir;
  Scene scene(dir.path());
  ASSERT_NE(scene.m, nullptr);
  const std::string manifest = (dir / "left_cart_pole.signals.json").string();
  EXPECT_THROW(rt::SignalBridge::attach(manifest, scene.m, scene.d, "middle/"), rt::LoadError);
  // The right prefix given explicitly, or the other copy's: both name elements the scene has.
  EXPECT_NO_THROW(rt::SignalBridge::attach(manifest, scene.m, scene.d, "left/"));
  rt::SignalBridge renamed = rt::SignalBridge::attach(manifest, scene.m, scene.d, "right/");
  renamed.input("push").set(2.0);
  EXPECT_EQ(scene.d->ctrl[mj_name2id(scene.m, mjOBJ_ACTUATOR, "right/drive")], 2.0);
  std::ofstream(dir / "broken.json") << "{\"model\": \"x\", \"signals\": [{\"path\": 1}]}";
  try {
    rt::SignalBridge::attach((dir / "broken.json").string(), scene.m, scene.d);
    FAIL() << "no LoadError";
  } catch (const rt::LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("broken.json: error: not a signal manifest"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(rt::SignalBridge::attach((dir / "missing.json").string(), scene.m, scene.d), rt::LoadError);
}

}  // namespace
