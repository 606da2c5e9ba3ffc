// The manifest's format_version and time-step record as a SignalBridge reads them: a newer format is refused
// naming both versions; a scene stepping at another time step than the model was emitted for is warned about,
// with both numbers and the choices that follow it, only when the manifest says the model has such choices.
#include <mujoco/mujoco.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "openplx/runtime/signal_bridge.h"
#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace {

namespace fs = std::filesystem;
namespace rt = openplx::runtime;
using nlohmann::json;

struct Loaded {
  mjModel* m = nullptr;
  mjData* d = nullptr;
  explicit Loaded(const fs::path& xml) {
    char error[1000] = "";
    m = mj_loadXML(xml.c_str(), nullptr, error, sizeof(error));
    EXPECT_NE(m, nullptr) << error;
    if (m) d = mj_makeData(m);
  }
  ~Loaded() {
    if (d) mj_deleteData(d);
    if (m) mj_deleteModel(m);
  }
};

fs::path convert(const std::string& sample, const fs::path& dir) {
  const fs::path xml = dir / (sample + ".xml");
  std::ostringstream text, errors;
  EXPECT_EQ(
      openplx::cli::run({std::string(OPENPLX_SAMPLES_DIR) + "/" + sample + ".openplx", "-o", xml.string()},
                        text, errors),
      0)
      << errors.str();
  return xml;
}

fs::path manifest_of(const fs::path& xml) {
  return fs::path(xml).replace_extension(".signals.json");
}

TEST(ManifestVersion, ANewerFormatIsRefusedNamingBothVersions) {
  const openplx::testing::ScratchDir dir;
  const fs::path xml = convert("pendulum", dir.path());
  json j = json::parse(std::ifstream(manifest_of(xml)));
  EXPECT_EQ(j.at("format_version"), 1);
  EXPECT_EQ(j.at("mujoco"), "2.2.2");
  j["format_version"] = 2;
  j["signals"][0]["renamed_in_version_2"] = true;
  std::ofstream(dir / "future.signals.json") << j.dump();
  Loaded model(xml);
  try {
    rt::SignalBridge::attach((dir / "future.signals.json").string(), model.m, model.d);
    ADD_FAILURE() << "a format_version 2 manifest was read";
  } catch (const rt::LoadError& e) {
    EXPECT_NE(
        std::string(e.what()).find("future.signals.json: error: the manifest's format_version is 2 but this "
                                   "runtime reads up to 1"),
        std::string::npos)
        << e.what();
  }
}

TEST(ManifestVersion, AnotherTimeStepIsWarnedAboutOnlyWhenTheModelsChoicesFollowIt) {
  const openplx::testing::ScratchDir dir;
  // pendulum: a hinge and nothing else; its MJCF means the same at any step.
  const fs::path pendulum = convert("pendulum", dir.path());
  EXPECT_FALSE(json::parse(std::ifstream(manifest_of(pendulum))).at("timestep_dependent").get<bool>());
  Loaded free_of_it(pendulum);
  free_of_it.m->opt.timestep = 0.005;
  rt::SignalBridge quiet =
      rt::SignalBridge::attach(manifest_of(pendulum).string(), free_of_it.m, free_of_it.d);
  EXPECT_TRUE(quiet.warnings().empty()) << quiet.warnings().front();
  // cart_pole: its rail's hard limit is set for 2 h.
  const fs::path cart_pole = convert("cart_pole", dir.path());
  const json j = json::parse(std::ifstream(manifest_of(cart_pole)));
  EXPECT_TRUE(j.at("timestep_dependent").get<bool>());
  EXPECT_EQ(j.at("timestep_choices"), json::array({"hard limits (1, solreflimit 2h)"}));
  Loaded following(cart_pole);
  following.m->opt.timestep = 0.005;
  rt::SignalBridge warned =
      rt::SignalBridge::attach(manifest_of(cart_pole).string(), following.m, following.d);
  ASSERT_EQ(warned.warnings().size(), 1u);
  EXPECT_NE(warned.warnings()[0].find(
                "cart_pole.signals.json: warning: the scene steps at 0.005 s but the model "
                "was emitted for 0.002 s; its hard limits (1, solreflimit 2h) follow the time "
                "step it was emitted for: emit it with --timestep 0.005"),
            std::string::npos)
      << warned.warnings()[0];
  // At its own step: nothing to say.
  Loaded same(cart_pole);
  rt::SignalBridge silent = rt::SignalBridge::attach(manifest_of(cart_pole).string(), same.m, same.d);
  EXPECT_TRUE(silent.warnings().empty());
}

}  // namespace
