// docs/signals.schema.json against the manifests openplx2mjcf writes, checked by ajv at its defaults (a
// standard validator, run under Node: tests/support/schema_validators.h): every sample, corpus model (OpenPLX
// and URDF), seed snippet and three models written here to reach the remaining quantities validates, together
// they use every quantity kind, and the schema documents exactly the kinds the emitter has. Broken manifests
// are in manifest_schema_errors_test.cpp. Also the time-step record: a model whose manifest says its
// stability choices do not follow the time step emits the same MJCF at another one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "contract/signal_binding.h"
#include "tests/support/schema_validators.h"
#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace {

namespace fs = std::filesystem;
namespace mj = openplx::mjcf;
using nlohmann::json;

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

const fs::path kSchema = fs::path(OPENPLX_TEST_DATA_DIR).parent_path() / "docs" / "signals.schema.json";

const json& schema() {
  static const json s = read_json(kSchema);
  return s;
}

// ajv's verdict on every file: each valid, and nothing logged compiling the schema (strict mode is quiet).
void expect_all_valid(const std::vector<std::string>& files) {
  const openplx::testing::Validation v = openplx::testing::ajv_validate(kSchema, files);
  ASSERT_EQ(v.failure, "");
  for (const std::string& w : v.warnings) ADD_FAILURE() << "ajv logged: " << w;
  for (const std::string& f : files) {
    const auto found = v.by_file.find(f);
    ASSERT_NE(found, v.by_file.end()) << f;
    EXPECT_TRUE(found->second.valid) << f << ": " << found->second.details.substr(0, 2000);
  }
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

// The kinds an enum of the schema allows, checked to be exactly those its `definitions` describe.
std::set<std::string> documented_kinds(const json& property) {
  std::set<std::string> kinds, described;
  for (const json& kind : property.at("enum")) kinds.insert(kind.get<std::string>());
  for (const auto& [kind, text] : property.at("definitions").items()) described.insert(kind);
  EXPECT_EQ(kinds, described);
  EXPECT_EQ(kinds.size(), property.at("enum").size()) << "a kind listed twice";
  return kinds;
}

std::set<std::string> schema_quantities() {
  return documented_kinds(schema().at("definitions").at("quantity"));
}

TEST(ManifestSchema, DocumentsExactlyTheEmittersQuantitiesEachWithMeaningAndHowToApplyIt) {
  std::set<std::string> emitter;
  for (int q = static_cast<int>(mj::Quantity::None); q <= static_cast<int>(mj::Quantity::Constant); ++q)
    emitter.insert(std::string(mj::to_string(static_cast<mj::Quantity>(q))));
  EXPECT_EQ(schema_quantities(), emitter);
  EXPECT_EQ(emitter.size(), 55u);
  for (const auto& [kind, doc] : schema().at("definitions").at("quantity").at("definitions").items()) {
    SCOPED_TRACE(kind);
    const std::string text = doc.at("description");
    const size_t apply = text.find(" Apply: ");
    ASSERT_NE(apply, std::string::npos) << text;
    EXPECT_GT(apply, 20u) << "its meaning, before how to apply it";
    EXPECT_GT(text.size() - apply, 20u) << "how to apply it";
  }
  const json& laws = schema().at("definitions").at("law").at("properties").at("kind");
  EXPECT_EQ(documented_kinds(laws).size(), 6u);
  for (const auto& [kind, doc] : laws.at("definitions").items())
    EXPECT_GT(doc.at("description").get<std::string>().size(), 50u) << kind;
  EXPECT_EQ(schema().at("properties").at("format_version").at("const"), mj::kManifestFormatVersion);
  // The draft every validator takes at its defaults (ajv-cli's default spec is draft-07).
  EXPECT_EQ(schema().at("$schema"), "http://json-schema.org/draft-07/schema#");
}

// Every kind, written by the manifest writer itself, whatever the models reach.
TEST(ManifestSchema, EveryQuantityTheWriterCanWriteValidates) {
  const openplx::testing::ScratchDir dir;
  std::vector<mj::SignalBinding> bindings;
  for (int q = static_cast<int>(mj::Quantity::None); q <= static_cast<int>(mj::Quantity::Constant); ++q) {
    mj::SignalBinding b;
    b.path = "signal" + std::to_string(q);
    b.type = "Physics.Signals.Force1DInput";
    b.unit = "N";
    b.quantity = static_cast<mj::Quantity>(q);
    b.names = {"x"};
    b.low = -INFINITY;
    b.high = NAN;
    if (b.quantity == mj::Quantity::SensorFields) b.noise = {{0.0}, {0.01}, {0.001}};  // optional: once
    bindings.push_back(b);
  }
  mj::RuntimeLaw spring;
  spring.kind = mj::RuntimeLaw::Kind::Spring;
  const std::string file = (dir / "every_quantity.signals.json").string();
  std::ofstream(file) << mj::manifest_json("m", "p/", bindings, {spring, mj::RuntimeLaw{}},
                                           {"v1 bodies=1 joints=0 hash=0", 0.002, "3", {"1 x"}});
  // The writer spells what JSON cannot hold as strings, which the schema's `number` allows.
  ASSERT_NE(read_text(file).find("\"-inf\""), std::string::npos);
  ASSERT_NE(read_text(file).find("\"nan\""), std::string::npos);
  ASSERT_NE(read_text(file).find("\"deviation_per_metre\""), std::string::npos);
  expect_all_valid({file});
}

TEST(ManifestSchema, EveryManifestTheConverterWritesValidatesAndTogetherTheyUseEveryQuantity) {
  const openplx::testing::ScratchDir dir;
  std::vector<std::string> manifests;
  std::map<std::string, size_t> quantities, laws;
  size_t runtime_signals = 0, dependent = 0, same_at_another_step = 0;
  const std::vector<fs::path> models = sources(dir.path());
  for (size_t k = 0; k < models.size(); ++k) {
    const fs::path& source = models[k];
    SCOPED_TRACE(source.string());
    const std::string name = std::to_string(k) + "_" + source.stem().string();
    const std::string xml = convert(source, dir / "at_0.002", name);
    if (xml.empty()) continue;  // refused by design (other tests check why)
    manifests.push_back((dir / "at_0.002" / (name + ".signals.json")).string());
    const json manifest = read_json(manifests.back());
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
  expect_all_valid(manifests);
  const size_t validated = manifests.size();
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
  std::cout << validated << " manifests checked by ajv (" << models.size() << " sources), " << used.size()
            << " quantity kinds used, " << runtime_signals << " signals marked runtime, laws:";
  for (const auto& [kind, n] : laws) std::cout << " " << kind << " " << n;
  std::cout << "; " << dependent << " with time-step-dependent choices, " << same_at_another_step
            << " emit the same MJCF at 0.001 s\n";
}

}  // namespace
