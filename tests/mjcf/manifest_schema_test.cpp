// docs/signals.schema.json against the manifests openplx2mjcf writes: every sample, corpus model (OpenPLX and
// URDF), seed snippet and three models written here to reach the remaining quantities validates, together
// they use every quantity kind, and the schema documents exactly the kinds the emitter has. The validator
// (tests/support/json_schema_subset.h) is itself shown to refuse manifests with a missing field, a wrong
// type, an unknown quantity or field, and a newer format. Also the time-step record: a model whose manifest
// says its stability choices do not follow the time step emits the same MJCF at another one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>

#include "contract/signal_binding.h"
#include "tests/support/json_schema_subset.h"
#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace {

namespace fs = std::filesystem;
namespace mj = openplx::mjcf;
using nlohmann::json;
using openplx::testing::SchemaSubset;

json read_json(const fs::path& path) {
  std::ifstream in(path);
  return json::parse(in);
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

const json& schema() {
  static const json s = read_json(fs::path(OPENPLX_TEST_DATA_DIR) / ".." / "docs" / "signals.schema.json");
  return s;
}

std::string joined(const std::vector<std::string>& errors) {
  std::string text;
  for (size_t k = 0; k < errors.size() && k < 8; ++k) text += errors[k] + "\n";
  return text;
}

// Models that reach what no sample or corpus model does: mate connector outputs (relative_to another
// connector too), a body's acceleration, forces in a transform's axes, a body's torque input, an
// IMU, a virtual affine input; a Distance mate, a DistanceRange and a force motor with an effort-range
// input; a torque converter (a runtime law) and a viscous gear.
const char kConnectorsAndSensors[] = R"(Acceleration3DOutput is Physics.Signals.Output:
    type: Physics.Signals.InputOutputType.Acceleration3D
    source is Physics3D.Bodies.RigidBody
Puck is Physics3D.Bodies.RigidBody:
    with Physics3D.Signals.Torque3DInputTrait
    inertia.mass: 1
    disc is Physics3D.Geometries.Box:
        size: {0.2, 0.2, 0.05}
    axle is Physics3D.Interactions.MateConnector:
        main_axis: Math.Vec3.Z_AXIS()
        normal: Math.Vec3.X_AXIS()
    mount is Physics3D.Interactions.MateConnector:
        main_axis: Math.Vec3.Z_AXIS()
        normal: Math.Vec3.X_AXIS()
Scene is Physics3D.System:
    ground is Physics3D.Interactions.MateConnector:
        main_axis: Math.Vec3.Z_AXIS()
        normal: Math.Vec3.X_AXIS()
    puck is Puck
    hinge is Physics3D.Interactions.Hinge:
        connectors: [ground, puck.axle]
    spin is Physics3D.Interactions.RotationalVelocityMotor:
        connectors: [ground, puck.axle]
        target_speed: 2
    imu is Sensors.IMULogic:
        mate_connector_attachment: puck.mount
        accelerometer is Sensors.AccelerometerLogic:
            mate_connector_attachment: puck.mount
    readings is Sensors.Signals.IMUOutput:
        source: imu
        fields: [{Sensors.Signals.TriaxialOutputField.Z_F64, imu.accelerometer}]
    mount_position is Physics3D.Signals.MateConnector.PositionOutput:
        source: puck.mount
    mount_rpy is Physics3D.Signals.MateConnector.RPYOutput:
        source: puck.mount
    mount_velocity is Physics3D.Signals.MateConnector.LinearVelocity3DOutput:
        source: puck.mount
    mount_rate is Physics3D.Signals.MateConnector.AngularVelocity3DOutput:
        source: puck.mount
    puck_acceleration is Acceleration3DOutput:
        source: puck
    mount_acceleration is Physics3D.Signals.MateConnector.Acceleration3DOutput:
        source: puck.mount
    mount_angular_acceleration is Physics3D.Signals.MateConnector.AngularAcceleration3DOutput:
        source: puck.mount
    ground_from_mount is Physics3D.Signals.MateConnector.PositionOutput:
        source: ground
        relative_to: puck.mount
    ground_rpy_from_mount is Physics3D.Signals.MateConnector.RPYOutput:
        source: ground
        relative_to: puck.mount
    ground_velocity_from_mount is Physics3D.Signals.MateConnector.LinearVelocity3DOutput:
        source: ground
        relative_to: puck.mount
    ground_rate_from_mount is Physics3D.Signals.MateConnector.AngularVelocity3DOutput:
        source: ground
        relative_to: puck.mount
    ground_acceleration_from_mount is Physics3D.Signals.MateConnector.Acceleration3DOutput:
        source: ground
        relative_to: puck.mount
    ground_angular_acceleration_from_mount is Physics3D.Signals.MateConnector.AngularAcceleration3DOutput:
        source: ground
        relative_to: puck.mount
    turned_force is Physics3D.Signals.Force3DOutput:
        source: hinge
        relative_to: Math.AffineTransform.from({0, 0, 0}, Math.Quat.angle_axis(0.5, {0, 0, 1}))
    turned_torque is Physics3D.Signals.Torque3DOutput:
        source: hinge
        relative_to: Math.AffineTransform.from({0, 0, 0}, Math.Quat.angle_axis(0.5, {0, 0, 1}))
    push is Physics3D.Signals.Torque3DInput:
        source: puck
    doubled is Control.Virtual.AffineTransform1DInput:
        target: spin.target_angular_velocity_input
        scale: 2.0
)";

const char kDistances[] = R"(RangedPush is Physics3D.Interactions.ForceMotor:
    with Physics.Signals.ForceRangeInputTrait
    force_range_input is Physics.Signals.ForceRangeInput:
        source: this
Bob is Physics3D.Bodies.RigidBody:
    inertia.mass: 1
    ball is Physics3D.Geometries.Sphere:
        radius: 0.05
    c is Physics3D.Interactions.MateConnector:
        main_axis: Math.Vec3.X_AXIS()
        normal: Math.Vec3.Y_AXIS()
Scene is Physics3D.System:
    pivot is Physics3D.Interactions.MateConnector:
        main_axis: Math.Vec3.X_AXIS()
        normal: Math.Vec3.Y_AXIS()
    anchor is Physics3D.Interactions.MateConnector:
        position: {0, 2, 0}
        main_axis: Math.Vec3.X_AXIS()
        normal: Math.Vec3.Y_AXIS()
    rail is Physics3D.Interactions.MateConnector:
        position: {0.3, 2, 0}
        main_axis: Math.Vec3.X_AXIS()
        normal: Math.Vec3.Y_AXIS()
    bob is Bob
    rod is Physics3D.Interactions.Distance:
        connectors: [pivot, bob.c]
        initial_distance: 1.0
    slider is Bob
    slide is Physics3D.Interactions.Prismatic:
        connectors: [rail, slider.c]
    range is Physics3D.Interactions.DistanceRange:
        connectors: [anchor, slider.c]
        start: 0.1
        end: 0.5
    push is RangedPush:
        connectors: [rail, slider.c]
        min_effort: -10
        max_effort: 10
)";

const char kShafts[] = R"(Converter is Physics3D.System:
    pump is DriveTrain.Shaft:
        inertia.inertia: 1
    turbine is DriveTrain.Shaft:
        inertia.inertia: 1
    out is DriveTrain.Shaft:
        inertia.inertia: 1
    engine is Physics1D.Interactions.RotationalVelocityMotor:
        connectors: [pump.input]
        target_speed: 20
    converter is DriveTrain.EmpiricalTorqueConverter:
        connectors: [pump.output, turbine.input]
    gear is DriveTrain.ViscousGear:
        connectors: [turbine.output, out.input]
        ratio: 2
        dissipation.viscosity: 2
)";

// An elastic wheel on a static hub: its tire's six directions are compliance laws.
const char kElasticWheel[] = R"(Hub is Physics3D.Bodies.RigidBody:
    is_dynamic: false
    axle is Physics3D.Interactions.MateConnector:
        main_axis: {0, 1, 0}
        normal: {0, 0, 1}
Tyre is Vehicles.Wheels.ElasticWheel:
    rim becomes Vehicles.Wheels.Rim:
        radius: 0.3
        width: 0.2
        rotational_axis: {0, 1, 0}
        inertia.mass: 10
    tire becomes Vehicles.Wheels.Tire:
        outer_radius: 0.4
        inner_radius: 0.3
        width: 0.25
        rotational_axis: {0, 1, 0}
        inertia.mass: 30
Scene is Physics3D.System:
    hub is Hub
    wheel is Tyre
    axle is Physics3D.Interactions.Hinge:
        connectors: [hub.axle, wheel.connector]
)";

std::vector<fs::path> sources(const fs::path& dir) {
  std::vector<fs::path> found;
  for (const fs::path& folder : {fs::path(OPENPLX_SAMPLES_DIR), fs::path(OPENPLX_CORPUS_DIR) / "agxunity",
                                 fs::path(OPENPLX_VENDORED_CORPUS_DIR) / "agxunity",
                                 fs::path(OPENPLX_TEST_DATA_DIR) / "seed_snippets"}) {
    if (!fs::is_directory(folder)) continue;
    for (const auto& entry : fs::directory_iterator(folder))
      if (entry.path().extension() == ".openplx") found.push_back(entry.path());
  }
  for (const auto& entry : fs::recursive_directory_iterator(fs::path(OPENPLX_VENDORED_CORPUS_DIR) / "urdf"))
    if (entry.path().extension() == ".urdf") found.push_back(entry.path());
  std::sort(found.begin(), found.end());
  for (const auto& [name, text] :
       {std::pair{"connectors_and_sensors", kConnectorsAndSensors}, std::pair{"distances", kDistances},
        std::pair{"shafts", kShafts}, std::pair{"elastic_wheel", kElasticWheel}}) {
    found.push_back(dir / (std::string(name) + ".openplx"));
    std::ofstream(found.back()) << text;
  }
  return found;
}

// Converts `source` to DIR/OUT/NAME.xml with extra arguments; the MJCF path, or "" when refused.
std::string convert(const fs::path& source, const fs::path& dir, const std::string& name,
                    const std::vector<std::string>& extra = {}) {
  fs::create_directories(dir);
  const std::string out = (dir / (name + ".xml")).string();
  std::vector<std::string> args{source.string(), "-o", out};
  if (source.stem() == "simple_lidar") args.insert(args.end(), {"--model", "ValidLidar"});
  if (source.stem() == "use_test_bundle")
    args.insert(args.end(), {"-B", (source.parent_path() / "TestBundle").string()});
  args.insert(args.end(), extra.begin(), extra.end());
  std::ostringstream text, errors;
  return openplx::cli::run(args, text, errors) == 0 ? out : "";
}

std::set<std::string> schema_quantities() {
  std::set<std::string> kinds;
  for (const json& option : schema().at("$defs").at("quantity").at("oneOf")) kinds.insert(option.at("const"));
  return kinds;
}

TEST(ManifestSchema, DocumentsExactlyTheEmittersQuantitiesEachWithMeaningAndHowToApplyIt) {
  std::set<std::string> emitter;
  for (int q = static_cast<int>(mj::Quantity::None); q <= static_cast<int>(mj::Quantity::Constant); ++q)
    emitter.insert(std::string(mj::to_string(static_cast<mj::Quantity>(q))));
  EXPECT_EQ(schema_quantities(), emitter);
  EXPECT_EQ(emitter.size(), 55u);
  for (const json& option : schema().at("$defs").at("quantity").at("oneOf")) {
    SCOPED_TRACE(option.at("const").get<std::string>());
    EXPECT_GT(option.value("description", "").size(), 20u);
    EXPECT_GT(option.value("x-apply", "").size(), 10u);
  }
  EXPECT_EQ(schema().at("properties").at("format_version").at("const"), mj::kManifestFormatVersion);
}

// Every kind, written by the manifest writer itself, whatever the models reach.
TEST(ManifestSchema, EveryQuantityTheWriterCanWriteValidates) {
  const SchemaSubset validator(schema());
  std::vector<mj::SignalBinding> bindings;
  for (int q = static_cast<int>(mj::Quantity::None); q <= static_cast<int>(mj::Quantity::Constant); ++q) {
    mj::SignalBinding b;
    b.path = "signal" + std::to_string(q);
    b.type = "Physics.Signals.Force1DInput";
    b.unit = "N";
    b.quantity = static_cast<mj::Quantity>(q);
    b.names = {"x"};
    b.low = -INFINITY;
    bindings.push_back(b);
  }
  mj::RuntimeLaw spring;
  spring.kind = mj::RuntimeLaw::Kind::Spring;
  const json manifest = json::parse(mj::manifest_json("m", "p/", bindings, {spring, mj::RuntimeLaw{}},
                                                      {"v1 bodies=1 joints=0 hash=0", 0.002, "3", {"1 x"}}));
  EXPECT_TRUE(validator.validate(manifest).empty()) << joined(validator.validate(manifest));
}

TEST(ManifestSchema, TheValidatorRefusesBrokenManifests) {
  const openplx::testing::ScratchDir dir;
  const std::string xml =
      convert(fs::path(OPENPLX_SAMPLES_DIR) / "cart_pole.openplx", dir.path(), "cart_pole");
  ASSERT_FALSE(xml.empty());
  const json good = read_json(dir / "cart_pole.signals.json");
  const SchemaSubset validator(schema());
  ASSERT_TRUE(validator.validate(good).empty()) << joined(validator.validate(good));
  auto refused = [&](const std::string& what, const std::function<void(json&)>& spoil,
                     const std::string& says) {
    SCOPED_TRACE(what);
    json bad = good;
    spoil(bad);
    const std::string errors = joined(validator.validate(bad));
    EXPECT_NE(errors.find(says), std::string::npos) << errors;
  };
  refused(
      "a missing field", [](json& j) { j["signals"][3].erase("sign"); },
      "/signals/3: lacks the required field \"sign\"");
  refused(
      "a missing top-level field", [](json& j) { j.erase("format_version"); },
      "/: lacks the required field \"format_version\"");
  refused(
      "a wrong type", [](json& j) { j["signals"][0]["enabled"] = "yes"; }, "/signals/0/enabled: is string");
  refused(
      "a string for a number", [](json& j) { j["signals"][0]["sign"] = "one"; }, "/signals/0/sign:");
  refused(
      "an unknown quantity", [](json& j) { j["signals"][1]["quantity"] = "warp_drive"; },
      "/signals/1/quantity: \"warp_drive\" matches 0 of the oneOf alternatives");
  refused(
      "an unknown field", [](json& j) { j["signals"][2]["colour"] = "red"; },
      "/signals/2/colour: not allowed here");
  refused(
      "a newer format", [](json& j) { j["format_version"] = 2; }, "/format_version: is 2, not 1");
  refused(
      "a time step of zero", [](json& j) { j["timestep"] = 0; },
      "/timestep: 0 is below its exclusiveMinimum");
  refused(
      "an unknown law",
      [](json& j) {
        j["laws"] = json::array({{{"kind", "rocket"}}});
      },
      "/laws/0/kind: \"rocket\" matches 0");
  // A schema keyword the validator does not implement is an error, not a rule silently skipped.
  EXPECT_THROW(SchemaSubset(json{{"pattern", "^a"}}).validate(json("a")), std::invalid_argument);
}

TEST(ManifestSchema, EveryManifestTheConverterWritesValidatesAndTogetherTheyUseEveryQuantity) {
  const openplx::testing::ScratchDir dir;
  const SchemaSubset validator(schema());
  std::map<std::string, size_t> quantities, laws;
  size_t validated = 0, runtime_signals = 0, dependent = 0, same_at_another_step = 0;
  const std::vector<fs::path> models = sources(dir.path());
  for (size_t k = 0; k < models.size(); ++k) {
    const fs::path& source = models[k];
    SCOPED_TRACE(source.string());
    const std::string name = std::to_string(k) + "_" + source.stem().string();
    const std::string xml = convert(source, dir / "at_0.002", name);
    if (xml.empty()) continue;  // refused by design (other tests check why)
    const json manifest = read_json(dir / "at_0.002" / (name + ".signals.json"));
    const std::vector<std::string> errors = validator.validate(manifest);
    EXPECT_TRUE(errors.empty()) << joined(errors);
    ++validated;
    for (const json& s : manifest.at("signals")) {
      ++quantities[s.at("quantity")];
      runtime_signals += s.at("runtime").get<bool>();
    }
    for (const json& l : manifest.at("laws")) ++laws[l.at("kind")];
    // The time-step record: the same MJCF at another time step (but for <option timestep>) unless dependent.
    const std::string other = convert(source, dir / "at_0.001", name, {"--timestep", "0.001"});
    ASSERT_FALSE(other.empty());
    std::string text = read_text(other);
    const std::string step = "timestep=\"0.001\"";
    text.replace(text.find(step), step.size(), "timestep=\"0.002\"");
    const bool same = text == read_text(xml);
    same_at_another_step += same;
    if (manifest.at("timestep_dependent").get<bool>()) {
      ++dependent;
      EXPECT_FALSE(manifest.at("timestep_choices").empty());
    } else {
      EXPECT_TRUE(same) << "the manifest says the MJCF does not follow the time step, but it changed";
      EXPECT_TRUE(manifest.at("timestep_choices").empty());
    }
  }
  std::set<std::string> used;
  for (const auto& [q, n] : quantities) used.insert(q);
  const std::set<std::string> documented = schema_quantities();
  std::set<std::string> missing;
  std::set_difference(documented.begin(), documented.end(), used.begin(), used.end(),
                      std::inserter(missing, missing.end()));
  missing.erase("motor_force_range");  // written by converters before the runtime owned motors' rows
  EXPECT_TRUE(missing.empty()) << "no model uses " << *missing.begin();
  EXPECT_EQ(laws.size(), 6u);
  EXPECT_GE(validated, 70u);
  std::cout << validated << " manifests validated (" << models.size() << " sources), " << used.size()
            << " quantity kinds used, " << runtime_signals << " signals marked runtime, laws:";
  for (const auto& [kind, n] : laws) std::cout << " " << kind << " " << n;
  std::cout << "; " << dependent << " with time-step-dependent choices, " << same_at_another_step
            << " emit the same MJCF at 0.001 s\n";
}

}  // namespace
