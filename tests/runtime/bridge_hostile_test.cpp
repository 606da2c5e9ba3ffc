// SignalBridge against manifests that do not fit: inconsistent manifests are LoadErrors naming the
// manifest and the signal (they crashed the bridge), a manifest of another model is refused by its
// fingerprint or by the elements it names, a second bridge on the same data and prefix is refused, and
// after_step() throws SimulationError when MuJoCo had to reset the data.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>

#include "contract/manifest_reader.h"
#include "frontend/diagnostics/diagnostics.h"
#include "frontend/pipeline.h"
#include "mjcf_emitter/document_fingerprint.h"
#include "mjcf_emitter/emitter.h"
#include "openplx/runtime/signal_bridge.h"
#include "openplx/runtime/simulation.h"
#include "snap/resolve_system.h"
#include "snap/snap.h"
#include "tests/support/light_rod.h"
#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace {

namespace rt = openplx::runtime;
namespace fs = std::filesystem;
namespace mj = openplx::mjcf;
using nlohmann::json;
using openplx::testing::ScratchDir;

std::string sample(const std::string& name) {
  return std::string(OPENPLX_SAMPLES_DIR) + "/" + name;
}

// The converter's MJCF and manifest for `model` at `out` (.xml; the manifest beside it).
void emit(const std::string& model, const fs::path& out, const std::string& prefix, bool keyframe = false) {
  std::ostringstream text, errors;
  std::vector<std::string> args = {model, "-o", out.string(), "--prefix", prefix};
  if (!keyframe) args.push_back("--no-keyframe");
  ASSERT_EQ(openplx::cli::run(args, text, errors), 0) << errors.str();
}

fs::path manifest_of(const fs::path& xml) {
  return fs::path(xml).replace_extension(".signals.json");
}

// The emitted document of `model`, as the emitter builds it (for its fingerprint).
mj::Emitted emitted(const std::string& model, const std::string& prefix) {
  namespace fe = openplx::frontend;
  fe::SourceManager sources;
  fe::DiagnosticSink sink;
  fe::LoadRequest request;
  request.path = model;
  fe::Evaluation evaluation = fe::evaluate_file(request, sources, sink);
  EXPECT_FALSE(sink.has_errors());
  openplx::snap::ResolvedSystem system =
      openplx::snap::resolve_system(*evaluation.evaluator, evaluation.root, sink);
  openplx::snap::run_snap(system, sink);
  mj::EmitOptions options;
  options.model_name = evaluation.evaluator->root_name();
  options.prefix = prefix;
  return mj::emit_mjcf(system, options, sink);
}

json read_json(const fs::path& path) {
  std::ifstream in(path);
  return json::parse(in);
}
void write_json(const fs::path& path, const json& j) {
  std::ofstream(path) << j.dump(1);
}

// What the converter writes once the fingerprint and time step are passed to write_manifest_json.
void add_fingerprint(const fs::path& manifest, const std::string& model, const std::string& prefix) {
  json j = read_json(manifest);
  j["fingerprint"] = mj::model_fingerprint(emitted(model, prefix).document, prefix).text();
  j["timestep"] = 0.002;
  write_json(manifest, j);
}

// A manifest as written before the fingerprint existed.
void remove_fingerprint(const fs::path& manifest) {
  json j = read_json(manifest);
  j.erase("fingerprint");
  j.erase("timestep");
  write_json(manifest, j);
}

struct Compiled {
  mjModel* m = nullptr;
  mjData* d = nullptr;
  explicit Compiled(const fs::path& xml) {
    char error[1000] = "";
    m = mj_loadXML(xml.c_str(), nullptr, error, sizeof(error));
    EXPECT_NE(m, nullptr) << error;
    if (m) d = mj_makeData(m);
  }
  ~Compiled() {
    if (d) mj_deleteData(d);
    if (m) mj_deleteModel(m);
  }
};

std::string load_error(const fs::path& manifest, mjModel* m, mjData* d, const std::string& prefix = "") {
  try {
    rt::SignalBridge::attach(manifest.string(), m, d, prefix);
  } catch (const rt::LoadError& e) {
    return e.what();
  }
  return "";
}

const char* const kLightRod = openplx::testing::kLightRodPendulum;

TEST(ModelFingerprint, TheDocumentsIsTheCompiledModels) {
  const ScratchDir dir;
  for (const char* name : {"pendulum.openplx", "cart_pole.openplx", "drivetrain_machine.openplx",
                           "four_bar.openplx", "two_joint_arm.openplx", "vehicle_circle.openplx"}) {
    for (const std::string prefix : {"", "p/"}) {
      const mj::Emitted out = emitted(sample(name), prefix);
      const fs::path xml = dir / "model.xml";
      std::ofstream(xml) << out.document.to_string();
      Compiled model(xml);
      ASSERT_NE(model.m, nullptr) << name;
      const mj::Fingerprint expected = mj::model_fingerprint(out.document, prefix);
      EXPECT_EQ(expected.text(), mj::model_fingerprint(model.m, prefix).text()) << name << " " << prefix;
      EXPECT_GT(expected.bodies, 0) << name;
      mj::Fingerprint parsed;
      ASSERT_TRUE(mj::Fingerprint::parse(expected.text(), parsed));
      EXPECT_EQ(parsed.text(), expected.text());
    }
  }
  mj::Fingerprint parsed;
  EXPECT_FALSE(mj::Fingerprint::parse("v2 bodies=1 joints=1 hash=0123456789abcdef", parsed));
  EXPECT_FALSE(mj::Fingerprint::parse("v1 bodies=1 joints=1 hash=0123", parsed));
  EXPECT_FALSE(mj::Fingerprint::parse("v1 bodies=-1 joints=1 hash=0123456789abcdef", parsed));
}

// The case: a manifest of another model attached because one name (`hinge`) happened to match.
TEST(BridgeMismatch, ManifestOfAnotherModelIsRefused) {
  const ScratchDir dir;
  emit(sample("pendulum.openplx"), dir / "pendulum.xml", "");
  emit(sample("cart_pole.openplx"), dir / "cart_pole.xml", "");
  Compiled cart_pole(dir / "cart_pole.xml");
  ASSERT_NE(cart_pole.m, nullptr);
  // The converter writes the fingerprint the emitted document gives.
  const json written = read_json(manifest_of(dir / "pendulum.xml"));
  EXPECT_EQ(written.at("fingerprint").get<std::string>(),
            mj::model_fingerprint(emitted(sample("pendulum.openplx"), "").document, "").text());
  EXPECT_EQ(written.at("timestep").get<double>(), 0.002);
  // Without a fingerprint (manifests written before it): every element it names must be there.
  remove_fingerprint(manifest_of(dir / "pendulum.xml"));
  std::string error = load_error(manifest_of(dir / "pendulum.xml"), cart_pole.m, cart_pole.d);
  EXPECT_NE(
      error.find("pendulum.signals.json: error: the model lacks 3 of the 4 MuJoCo elements this manifest "
                 "names (body `ground`, body `rod`, site `rod.top`)"),
      std::string::npos)
      << error;
  add_fingerprint(manifest_of(dir / "pendulum.xml"), sample("pendulum.openplx"), "");
  error = load_error(manifest_of(dir / "pendulum.xml"), cart_pole.m, cart_pole.d);
  EXPECT_NE(
      error.find("pendulum.signals.json: error: the manifest was written for another model: it describes 2 "
                 "bodies and 1 joints"),
      std::string::npos)
      << error;
  // Its own model takes it.
  Compiled pendulum(dir / "pendulum.xml");
  EXPECT_NO_THROW(
      rt::SignalBridge::attach(manifest_of(dir / "pendulum.xml").string(), pendulum.m, pendulum.d));
  // A fingerprint this runtime cannot read is refused, not skipped.
  json j = read_json(manifest_of(dir / "pendulum.xml"));
  j["fingerprint"] = "v9 something";
  write_json(dir / "future.signals.json", j);
  error = load_error(dir / "future.signals.json", pendulum.m, pendulum.d);
  EXPECT_NE(error.find("is not one this runtime reads"), std::string::npos) << error;
}

// The fingerprint holds in a scene with other models and under another prefix than the one emitted.
TEST(BridgeMismatch, SceneAndRenamedPrefixStillMatch) {
  const ScratchDir dir;
  emit(sample("cart_pole.openplx"), dir / "left_cart_pole.xml", "left/");
  emit(sample("cart_pole.openplx"), dir / "right_cart_pole.xml", "right/");
  emit(sample("pendulum.openplx"), dir / "pendulum.xml", "");
  add_fingerprint(manifest_of(dir / "left_cart_pole.xml"), sample("cart_pole.openplx"), "left/");
  add_fingerprint(manifest_of(dir / "pendulum.xml"), sample("pendulum.openplx"), "");
  std::ofstream(dir / "scene.xml") << "<mujoco><include file=\"left_cart_pole.xml\"/><include "
                                      "file=\"right_cart_pole.xml\"/><include file=\"pendulum.xml\"/>"
                                      "<option><flag contact=\"disable\"/></option></mujoco>";
  Compiled scene(dir / "scene.xml");
  ASSERT_NE(scene.m, nullptr);
  rt::SignalBridge left =
      rt::SignalBridge::attach(manifest_of(dir / "left_cart_pole.xml").string(), scene.m, scene.d);
  // The left manifest drives the right copy under its prefix.
  rt::SignalBridge right =
      rt::SignalBridge::attach(manifest_of(dir / "left_cart_pole.xml").string(), scene.m, scene.d, "right/");
  // No prefix: the scene's other models' bodies are in the count too; the names it uses are checked.
  rt::SignalBridge pendulum =
      rt::SignalBridge::attach(manifest_of(dir / "pendulum.xml").string(), scene.m, scene.d);
  left.input("push").set(5.0);
  right.input("push").set(-5.0);
  for (int k = 0; k < 100; ++k) {
    left.before_step();
    right.before_step();
    pendulum.before_step();
    mj_step(scene.m, scene.d);
    left.after_step();
    right.after_step();
    pendulum.after_step();
  }
  EXPECT_GT(left.output("cart_position").real(), 0.01);
  EXPECT_LT(right.output("cart_position").real(), -0.01);
  // A prefix under which the model has other elements is refused.
  const std::string error = load_error(manifest_of(dir / "left_cart_pole.xml"), scene.m, scene.d, "nobody/");
  EXPECT_NE(error.find("written for another model"), std::string::npos) << error;
}

TEST(BridgeMismatch, SecondBridgeOnTheSameDataIsRefused) {
  const ScratchDir dir;
  emit(sample("cart_pole.openplx"), dir / "cart_pole.xml", "cp/");
  Compiled model(dir / "cart_pole.xml");
  ASSERT_NE(model.m, nullptr);
  const fs::path manifest = manifest_of(dir / "cart_pole.xml");
  {
    rt::SignalBridge first = rt::SignalBridge::attach(manifest.string(), model.m, model.d);
    std::string error = load_error(manifest, model.m, model.d);
    EXPECT_NE(error.find("a bridge for the names with prefix `cp/` is already attached to this mjData"),
              std::string::npos)
        << error;
    rt::SignalBridge moved = std::move(first);  // the registration moves along
    EXPECT_NE(load_error(manifest, model.m, model.d), "");
  }
  EXPECT_EQ(load_error(manifest, model.m, model.d), "");  // free again once it is gone
  // Another data of the same model takes its own bridge.
  mjData* other = mj_makeData(model.m);
  rt::SignalBridge first = rt::SignalBridge::attach(manifest.string(), model.m, model.d);
  EXPECT_EQ(load_error(manifest, model.m, other), "");
  mj_deleteData(other);
}

// Valid JSON that does not hold together crashed the bridge (heap overflows, null dereferences).
TEST(BridgeMismatch, InconsistentManifestsAreLoadErrorsNamingTheSignal) {
  const ScratchDir dir;
  emit(sample("cart_pole.openplx"), dir / "cart_pole.xml", "");
  Compiled model(dir / "cart_pole.xml");
  ASSERT_NE(model.m, nullptr);
  const json good = read_json(manifest_of(dir / "cart_pole.xml"));
  auto find = [&](const json& j, const std::string& path) -> size_t {
    for (size_t k = 0; k < j["signals"].size(); ++k) {
      if (j["signals"][k]["path"] == path) return k;
    }
    ADD_FAILURE() << "no signal " << path;
    return 0;
  };
  const size_t enable = find(good, "rail_limits.enable_interaction_input");
  const size_t push = find(good, "drive.force_input");
  json template_binding = good["signals"][push];
  auto binding = [&](const std::string& quantity, const std::string& object, json names, json initial_vector,
                     const std::string& value = "real") {
    json b = template_binding;
    b["path"] = "made." + quantity;
    b["quantity"] = quantity;
    b["object"] = object;
    b["names"] = std::move(names);
    b["initial_vector"] = std::move(initial_vector);
    b["value"] = value;
    return b;
  };
  auto law = [](const std::string& kind, json actuators) {
    return json{{"kind", kind},
                {"path", "power.part"},
                {"actuators", std::move(actuators)},
                {"curve_x", {0, 1}},
                {"curve_y", {1, 2}},
                {"curve2_x", json::array()},
                {"curve2_y", json::array()},
                {"parameter", 1}};
  };
  struct Case {
    const char* what;
    std::function<void(json&)> change;
    const char* expected;
  };
  const std::vector<Case> cases = {
      {"interaction_enabled without names", [&](json& j) { j["signals"][enable]["names"] = json::array(); },
       "signal `rail_limits.enable_interaction_input`: it names no MuJoCo element"},
      {"motor_force without names",
       [&](json& j) {
         j["signals"].push_back(binding("motor_force", "tendon", json::array(), json::array()));
       },
       "signal `made.motor_force`: it names no MuJoCo element"},
      {"engine law without actuators", [&](json& j) { j["laws"].push_back(law("engine", json::array())); },
       "law of `power.part`: an engine law needs one actuator, not 0"},
      {"torque converter with one actuator",
       [&](json& j) { j["laws"].push_back(law("torque_converter", {"drive"})); },
       "law of `power.part`: a torque-converter law needs two actuators (pump, turbine), not 1"},
      {"lidar without field indices",
       [&](json& j) {
         j["signals"].push_back(
             binding("sensor_fields", "sensor", {"ray0", "ray1"}, json::array(), "vector"));
       },
       "signal `made.sensor_fields`: it needs one field index per sensor"},
      {"control on a joint", [&](json& j) { j["signals"][push]["object"] = "joint"; },
       "signal `drive.force_input`: quantity `ctrl` does not act on a `joint`"},
      {"NaN initial control", [&](json& j) { j["signals"][push]["initial"] = "nan"; },
       "signal `drive.force_input`: its initial value is not a finite number"},
      {"range as one number",
       [&](json& j) { j["signals"].push_back(binding("force_range", "actuator", {"drive"}, json::array())); },
       "signal `made.force_range`: a range takes two numbers"},
      {"gear INT_MIN",
       [&](json& j) {
         json b = binding("gear_select", "equality", {"x"}, {1.0, 2.0}, "int");
         b["initial"] = -2147483648.0;
         j["signals"].push_back(b);
       },
       "signal `made.gear_select`: its initial gear is not a whole number of a gearbox"},
      {"unsorted curve",
       [&](json& j) {
         json l = law("engine", {"drive"});
         l["curve_x"] = {2, 1};
         j["laws"].push_back(l);
       },
       "a curve's x values are not in ascending order"},
      {"engaged without capacity",
       [&](json& j) { j["signals"].push_back(binding("engaged", "tendon", {"t"}, json::array(), "bool")); },
       "its initial_vector must hold the clutch's torque capacity"},
      {"kinematic velocity of two numbers",
       [&](json& j) {
         j["signals"].push_back(binding("kinematic_linear_velocity", "body", {"cart"}, {1, 2}, "vec3"));
       },
       "its initial_vector must hold a velocity's three numbers"},
  };
  for (const Case& c : cases) {
    json j = good;
    c.change(j);
    const fs::path manifest = dir / "broken.signals.json";
    write_json(manifest, j);
    const std::string error = load_error(manifest, model.m, model.d);
    EXPECT_NE(error.find(manifest.string() + ": error: "), std::string::npos) << c.what << ": " << error;
    EXPECT_NE(error.find(c.expected), std::string::npos) << c.what << ": " << error;
  }
}

// Elements of the wrong kind for what the binding does (found only against the model) are refused too.
TEST(BridgeMismatch, ElementsOfTheWrongKindAreRefused) {
  const ScratchDir dir;
  emit(sample("cart_pole.openplx"), dir / "cart_pole.xml", "");
  Compiled model(dir / "cart_pole.xml");
  ASSERT_NE(model.m, nullptr);
  json j = read_json(manifest_of(dir / "cart_pole.xml"));
  json b = j["signals"][0];
  b["path"] = "made.velocity";
  b["direction"] = "input";
  b["quantity"] = "kinematic_linear_velocity";  // on a body that is not a mocap body
  b["object"] = "body";
  b["names"] = {"cart"};
  b["value"] = "vec3";
  j["signals"].push_back(b);
  write_json(dir / "kinematic.signals.json", j);
  const std::string error = load_error(dir / "kinematic.signals.json", model.m, model.d);
  EXPECT_NE(error.find("`made.velocity`: body `cart` is not a mocap body"), std::string::npos) << error;
}

TEST(BridgeInstability, AfterStepThrowsNamingTheJoint) {
  const ScratchDir dir;
  std::ofstream(dir / "light_rod.openplx")
      << kLightRod
      << "    motor is Physics3D.Interactions.TorqueMotor:\n        connectors: [rod.top, pivot]\n";
  emit((dir / "light_rod.openplx").string(), dir / "light_rod.xml", "rod/");
  Compiled model(dir / "light_rod.xml");
  ASSERT_NE(model.m, nullptr);
  rt::SignalBridge bridge =
      rt::SignalBridge::attach(manifest_of(dir / "light_rod.xml").string(), model.m, model.d);
  bridge.input("motor.torque_input").set(1e8);
  bridge.before_step();
  mj_step(model.m, model.d);
  try {
    bridge.after_step();
    FAIL() << "the step blew up without a word";
  } catch (const rt::SimulationError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("light_rod.signals.json: error: at t = 0 s"), std::string::npos) << what;
    EXPECT_NE(what.find("hinge joint `hinge` in body `rod`"), std::string::npos) << what;  // prefix stripped
  }
  // Opted out: MuJoCo's reset stands and the bridge says so in its warnings. (The step that reset the data
  // went on from time 0: this one starts at 0.002 s.)
  bridge.set_on_instability(rt::OnInstability::Continue);
  bridge.input("motor.torque_input").set(1e8);
  bridge.before_step();
  mj_step(model.m, model.d);
  EXPECT_NO_THROW(bridge.after_step());
  ASSERT_FALSE(bridge.warnings().empty());
  EXPECT_NE(bridge.warnings().back().find("warning: at t = 0.002 s"), std::string::npos)
      << bridge.warnings().back();
}

// A model emitted for 0.002 s run in a scene at a larger step is said at attach. Its stiff spring (1e9 N
// m/rad on a light rod: the MJCF's stand-in, damped for 0.002 s, blows up at 0.05 s) is the runtime's spring
// row, computed for the step the scene takes, so it stays where its stiffness holds the rod. An instability
// that does happen names both time steps (the hint is instability.cpp's, tested with it).
TEST(BridgeInstability, SceneAtAnotherTimeStepIsSaidAndTheSpringRowFollowsIt) {
  const ScratchDir dir;
  std::ofstream(dir / "stiff.openplx") << kLightRod
                                       << "    spring is Physics3D.Interactions.TorsionSpring:\n"
                                          "        connectors: [rod.top, pivot]\n"
                                          "        flexibility.stiffness: 1e9\n";
  emit((dir / "stiff.openplx").string(), dir / "stiff.xml", "");
  Compiled model(dir / "stiff.xml");
  ASSERT_NE(model.m, nullptr);
  model.m->opt.timestep = 0.05;
  rt::SignalBridge bridge =
      rt::SignalBridge::attach(manifest_of(dir / "stiff.xml").string(), model.m, model.d);
  // Said at attach, before anything has gone wrong.
  ASSERT_EQ(bridge.warnings().size(), 1u);
  EXPECT_NE(
      bridge.warnings()[0].find("stiff.signals.json: warning: the scene steps at 0.05 s but the model was "
                                "emitted for 0.002 s"),
      std::string::npos)
      << bridge.warnings()[0];
  const int hinge = mj_name2id(model.m, mjOBJ_JOINT, "hinge");
  ASSERT_GE(hinge, 0);
  for (int k = 0; k < 200; ++k) {
    bridge.before_step();
    mj_step(model.m, model.d);
    ASSERT_NO_THROW(bridge.after_step()) << "step " << k;
  }
  EXPECT_LT(std::abs(model.d->qpos[model.m->jnt_qposadr[hinge]]), 1e-6);
}

// The validation refuses none of the manifests the emitter writes.
TEST(BridgeMismatch, EveryGoldenManifestReads) {
  size_t read = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(OPENPLX_TEST_DATA_DIR) / "golden" / "mjcf")) {
    if (entry.path().string().ends_with(".signals.json")) {
      EXPECT_NO_THROW(mj::read_manifest(entry.path().string())) << entry.path();
      ++read;
    }
  }
  EXPECT_GE(read, 5u);
}

}  // namespace
