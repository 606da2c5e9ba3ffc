// Hostile values: numbers nothing can simulate (a negative mass, 1 / 0, an infinite position, a zero
// quaternion or axis, a negative stiffness or shaft inertia, an infinite gear ratio or brake capacity, a mass
// whose weight overflows, a lidar of no rays, an engine without a curve), tracks MuJoCo cannot allocate,
// broken or giant mesh and image files and an absurd time step. Each is an error at the user's line
// (or a warning saying what was done, for what is only visual), exit 1 or 2, and no output file: never a
// crash, never a number MuJoCo cannot use.
#include <mujoco/mujoco.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "mjcf_emitter/xml.h"
#include "tests/support/car_model.h"
#include "tests/support/scratch_dir.h"
#include "tests/support/tetrahedron_stl.h"
#include "tools/cli/cli.h"

namespace {

namespace fs = std::filesystem;

struct Converted {
  int status = -1;
  std::string errors;  // the diagnostics, as printed
  std::string xml;     // the output file's text; empty when none was written
};

class Hostile : public ::testing::Test {
 public:
  // Writes `text` as scene.openplx and converts it to scene.xml.
  Converted convert(const std::string& text, std::vector<std::string> extra = {}) {
    std::ofstream(dir_ / "scene.openplx") << text;
    const fs::path xml = dir_ / "scene.xml";
    fs::remove(xml);  // an earlier conversion's
    std::vector<std::string> args{(dir_ / "scene.openplx").string(), "-o", xml.string()};
    args.insert(args.end(), extra.begin(), extra.end());
    std::ostringstream out, errors;
    Converted c;
    c.status = openplx::cli::run(args, out, errors);
    c.errors = errors.str();
    if (fs::exists(xml)) {
      std::ifstream in(xml);
      std::ostringstream read;
      read << in.rdbuf();
      c.xml = read.str();
    }
    return c;
  }
  // The conversion fails with an error at scene.openplx:line:column that contains `words`, and writes
  // nothing.
  void expect_error_at(const Converted& c, int line, int column, const std::string& words,
                       const std::string& code = "invalid-value") {
    EXPECT_EQ(c.status, 1) << c.errors;
    const std::string at =
        "scene.openplx:" + std::to_string(line) + ":" + std::to_string(column) + ": error: ";
    const size_t found = c.errors.find(at);
    ASSERT_NE(found, std::string::npos) << c.errors;
    const std::string message = c.errors.substr(found, c.errors.find('\n', found) - found);
    EXPECT_NE(message.find(words), std::string::npos) << message;
    EXPECT_NE(message.find("[" + code + "]"), std::string::npos) << message;
    EXPECT_EQ(c.xml, "") << "an output file was written";
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  openplx::testing::ScratchDir scratch_;
  fs::path dir_ = scratch_.path();
};

// A rod whose mass line (line 2) is `mass`.
std::string rod(const std::string& mass, const std::string& more = "") {
  return "Rod is Physics3D.Bodies.RigidBody:\n"
         "    inertia.mass: " +
         mass +
         "\n"
         "    geometry is Physics3D.Geometries.Box:\n"
         "        size: {0.05, 0.05, 1.0}\n" +
         more +
         "Scene is Physics3D.System:\n"
         "    rod is Rod\n";
}

TEST_F(Hostile, NegativeMassIsAnErrorAtItsLine) {
  expect_error_at(convert(rod("-1.0")), 2, 5, "`Rod.inertia.mass` is -1.0; a mass is 0");
}

TEST_F(Hostile, DivisionByZeroIsAnErrorAtTheExpression) {
  expect_error_at(convert(rod("1 / 0")), 2, 19, "division by zero");
  expect_error_at(convert(rod("2.0 / 0.0")), 2, 19, "division by zero");
}

TEST_F(Hostile, NaNAndOverflowAreErrorsAtTheExpression) {
  expect_error_at(convert(rod("Math.INF - Math.INF")), 2, 19, "no number (NaN)");
  expect_error_at(convert(rod("1e300 * 1e300")), 2, 19, "overflows");
  expect_error_at(convert(rod("Math.Functions.sqrt(-1.0)")), 2, 19, "`Math.Functions.sqrt` gives no number");
  expect_error_at(convert(rod("Math.INF")), 2, 5, "`Rod.inertia.mass` is inf");
}

TEST_F(Hostile, InfinityStaysAValueWhereItMeansNoLimit) {
  // Math.INF is how OpenPLX says "unlimited" (efforts, viscosity): arithmetic on it is no error.
  const Converted c = convert(rod("1.0", "    limit is Real: -Math.INF * 2\n"));
  EXPECT_EQ(c.status, 0) << c.errors;
  EXPECT_EQ(c.xml.find("inf"), std::string::npos) << c.xml;
}

TEST_F(Hostile, NonPhysicalInertiaTensorsAreErrors) {
  expect_error_at(
      convert(
          rod("1.0",
              "    inertia.tensor: Physics3D.Bodies.Inertia.symmetric_tensor({-1.0, 1.0, 1.0}, 0, 0, 0)\n")),
      5, 5, "`Rod.inertia.tensor` is -1.0; its principal moments must be 0 or positive");
  expect_error_at(
      convert(
          rod("1.0",
              "    inertia.tensor: Physics3D.Bodies.Inertia.symmetric_tensor({1.0, 1.0, 3.0}, 0, 0, 0)\n")),
      5, 5, "exceeds the sum of the other two");
}

TEST_F(Hostile, InfinitePositionAndZeroQuaternionAreErrors) {
  expect_error_at(convert(rod("1.0", "    kinematics.local_transform.position: {0.0, Math.INF, 0.0}\n")), 5,
                  5, "`Rod.kinematics.local_transform.position.y` is inf; a position is finite");
  expect_error_at(convert(rod("1.0", "    kinematics.local_transform.position.z: -Math.INF\n")), 5, 5,
                  "position.z` is -inf");
  // No rotation is not the identity: taking it for one would be silently wrong.
  expect_error_at(convert(rod("1.0", "    kinematics.local_transform.rotation: {0.0, 0.0, 0.0, 0.0}\n")), 5,
                  5, "a rotation quaternion has a length");
  expect_error_at(convert(rod("1.0", "    kinematics.initial_local_linear_velocity: {Math.INF, 0, 0}\n")), 5,
                  5, "an initial velocity is finite");
}

TEST_F(Hostile, NegativeSizesDensitiesAndInfiniteConnectorsAreErrors) {
  std::string negative = rod("1.0");
  negative.replace(negative.find("{0.05, 0.05"), 5, "{-0.05");
  expect_error_at(convert(negative), 4, 9, "`Rod.geometry.size.x` is -0.05; a box's size is finite");
  expect_error_at(convert("const Light is Physics.Geometries.Material:\n"
                          "    density: -5.0\n" +
                          rod("1.0", "    geometry.material: Light\n")),
                  2, 5, "a density is a finite number");
  expect_error_at(convert(rod("1.0",
                              "    top is Physics3D.Interactions.MateConnector:\n"
                              "        position: {0, 0, Math.INF}\n")),
                  6, 9, "`Rod.top.position.z` is inf; a connector's position and axes are finite");
}

TEST_F(Hostile, ARotationAboutTheZeroAxisIsAnErrorAtTheCall) {
  const std::string turned = "    kinematics.local_transform.rotation: Math.Quat.angle_axis(";
  expect_error_at(convert(rod("1.0", turned + "1, {0, 0, 0})\n")), 5, 42,
                  "`Math.Quat.angle_axis` turns 1.0 rad about the zero vector; an axis has a length");
  // No turn is the identity whatever the axis.
  const Converted none = convert(rod("1.0", turned + "0, {0, 0, 0})\n"));
  EXPECT_EQ(none.status, 0) << none.errors;
}

// MuJoCo loads a body of 1e308 kg, but its weight overflows to NaN at the first step (2e307 kg does too,
// 1.8e307 kg not); below 1e-15 kg it refuses a moving body, also when its inertia tensor is written.
TEST_F(Hostile, MassesMuJoCoCannotSimulateAreErrors) {
  expect_error_at(convert(rod("1e308")), 2, 5, "`Rod.inertia.mass` is 1e+308; a mass is 0");
  EXPECT_EQ(convert(rod("1e307")).status, 0);
  expect_error_at(
      convert(rod("1e-308",
                  "    inertia.tensor: Physics3D.Bodies.Inertia.symmetric_tensor({1.0, 1.0, 1.0}, 0, "
                  "0, 0)\n")),
      7, 5, "mass (1e-308 kg with the bodies fixed to it) is below MuJoCo's smallest", "mjcf-bad-asset");
}

// A lidar whose resolutions are `horizontal` (line 10) and `vertical` (line 11) rays.
std::string lidar(const std::string& horizontal, const std::string& vertical) {
  return "Scene is Physics3D.System:\n"
         "    mount is Physics3D.Interactions.MateConnector:\n"
         "        main_axis: {0, 0, 1}\n"
         "        normal: {1, 0, 0}\n"
         "    lidar is Sensors.PulsedLidarLogic:\n"
         "        mate_connector_attachment: mount\n"
         "        wavelength: 865\n"
         "        ray_source becomes Sensors.Optics.HorizontalSweepRaySource:\n"
         "            frequency: 10\n"
         "            horizontal_resolution: " +
         horizontal +
         "\n"
         "            vertical_resolution: " +
         vertical +
         "\n"
         "            horizontal_fov: {-0.4, 0.4}\n"
         "            vertical_fov: {-0.1, 0.1}\n";
}

TEST_F(Hostile, LidarResolutionsOfNoRayAreErrors) {
  ASSERT_EQ(convert(lidar("5", "2")).status, 0);
  const Converted c = convert(lidar("-3", "0"));
  expect_error_at(c, 10, 13,
                  "`lidar.ray_source.horizontal_resolution` is -3.0; a lidar's resolution is a ray count");
  expect_error_at(c, 11, 13, "`lidar.ray_source.vertical_resolution` is 0.0; a lidar's resolution");
  // Reported once, not once per row of rays.
  const Converted wide = convert(lidar("0", "7"));
  EXPECT_EQ(wide.errors.find("horizontal_resolution"), wide.errors.rfind("horizontal_resolution` is"))
      << wide.errors;
}

// A bench with a shaft and `engine` (its lines from line 5) on it.
std::string engine_bench(const std::string& engine) {
  return "Bench is Physics3D.System:\n"
         "    crank is DriveTrain.Shaft:\n"
         "        inertia.inertia: 1\n"
         "    engine is " +
         engine + "        connectors: [crank.input]\n";
}

TEST_F(Hostile, EnginesWithoutATorqueCurveAreErrors) {
  ASSERT_EQ(convert(engine_bench("DriveTrain.EmpiricalEngine:\n")).status, 0);
  expect_error_at(convert(engine_bench("DriveTrain.EmpiricalEngine:\n        rpm_torque_list: []\n")), 5, 9,
                  "`engine.rpm_torque_list` is empty; an engine's torque table has at least one point");
  ASSERT_EQ(convert(engine_bench("DriveTrain.MeanValueEngine:\n")).status, 0);
  const Converted zero =
      convert(engine_bench("DriveTrain.MeanValueEngine:\n        max_torque_RPM: 0\n        max_power_RPM: "
                           "0\n        max_RPM: 0\n"));
  expect_error_at(zero, 5, 9, "`engine.max_torque_RPM` is 0.0; an engine's rated speed is a positive RPM");
  expect_error_at(zero, 6, 9, "`engine.max_power_RPM` is 0.0");
  expect_error_at(zero, 7, 9, "`engine.max_RPM` is 0.0");
}

// openplx::testing::car() with its suspension line `from` replaced by `to`, and that line's number.
std::pair<std::string, int> car_with(const std::string& from, const std::string& to) {
  std::string model = openplx::testing::car(openplx::testing::Car{});
  const size_t at = model.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at == std::string::npos) return {model, 0};
  model.replace(at, from.size(), to);
  return {model,
          1 + static_cast<int>(std::count(model.begin(), model.begin() + static_cast<long>(at), '\n'))};
}

TEST_F(Hostile, NegativeSuspensionStiffnessAndDampingAreErrors) {
  const auto [stiff, stiff_line] = car_with("stiffness: 40000", "stiffness: -20000");
  expect_error_at(
      convert(stiff), stiff_line, 5,
      "`Corner.mate.spring_constant.stiffness` is -20000.0; a suspension's stiffness is a finite number");
  const auto [damped, damped_line] = car_with("damping_constant: 1500", "damping_constant: -1");
  expect_error_at(convert(damped), damped_line, 5,
                  "a suspension's damping is a finite number, 0 or positive");
}

// A hinged arm with a torsion spring whose stiffness line (line 14) is `stiffness`.
std::string sprung_arm(const std::string& stiffness) {
  return "Scene is Physics3D.System:\n"
         "    anchor is Physics3D.Interactions.MateConnector:\n"
         "        main_axis: {0, 0, 1}\n"
         "    arm is Physics3D.Bodies.RigidBody:\n"
         "        inertia.mass: 1\n"
         "        shape is Physics3D.Geometries.Box:\n"
         "            size: {0.5, 0.1, 0.1}\n"
         "        axle is Physics3D.Interactions.MateConnector:\n"
         "            main_axis: {0, 0, 1}\n"
         "    hinge is Physics3D.Interactions.Hinge:\n"
         "        connectors: [anchor, arm.axle]\n"
         "    spring is Physics3D.Interactions.TorsionSpring:\n"
         "        connectors: [anchor, arm.axle]\n"
         "        flexibility.stiffness: " +
         stiffness + "\n";
}

TEST_F(Hostile, NegativeStiffnessIsAnError) {
  const Converted fine = convert(sprung_arm("50"));
  ASSERT_EQ(fine.status, 0) << fine.errors;
  expect_error_at(convert(sprung_arm("-50")), 14, 9, "a stiffness is 0 or positive");
}

// samples/drivetrain_machine.openplx with its line `from` (in its PowerTrain) replaced by `to`, and that
// line's number.
std::pair<std::string, int> machine_with(const std::string& from, const std::string& to) {
  std::ifstream in(std::string(OPENPLX_SAMPLES_DIR) + "/drivetrain_machine.openplx");
  std::ostringstream text;
  text << in.rdbuf();
  std::string model = text.str();
  const size_t at = model.find("    " + from + "\n");
  EXPECT_NE(at, std::string::npos) << from;
  if (at == std::string::npos) return {model, 0};
  model.replace(at + 4, from.size(), to);
  return {model,
          1 + static_cast<int>(std::count(model.begin(), model.begin() + static_cast<long>(at), '\n'))};
}

void expect_machine_error(Hostile& test, const std::string& from, const std::string& to,
                          const std::string& words) {
  const auto [model, line] = machine_with(from, to);
  test.expect_error_at(test.convert(model), line, 5, words);
}

TEST_F(Hostile, DrivetrainNumbersOutOfRangeAreErrorsAtTheirLines) {
  const std::string capacity = "clutch.torque_capacity: 300";
  const Converted fine = convert(machine_with(capacity, capacity).first);
  ASSERT_EQ(fine.status, 0) << fine.errors;
  expect_machine_error(*this, capacity, "engine_shaft.inertia.inertia: -0.2", "a shaft's moment of inertia");
  expect_machine_error(*this, capacity, "differential.gear_ratio: Math.INF",
                       "a gear ratio is a finite number other than 0");
  expect_machine_error(*this, capacity, "gear_box.forward_gears: [3.5, 0.0, 1.2]",
                       "`PowerTrain.gear_box.forward_gears` is 0.0");
  expect_machine_error(*this, capacity, "clutch.torque_capacity: -300",
                       "`PowerTrain.clutch.torque_capacity` is -300.0; a torque capacity is a finite number");
  expect_machine_error(*this, "left_brake.torque_capacity: 1500", "left_brake.torque_capacity: Math.INF",
                       "a torque capacity is a finite number");
}

// A gear of 2^31 once overflowed an int: now it is a gear the lists lack, warned, and the gearbox starts in
// neutral.
TEST_F(Hostile, AnInitialGearBeyondIntIsWarnedAndNeutral) {
  for (const char* gear : {"2147483648", "-2147483648", "9000000000000000000"}) {
    const std::string capacity = "clutch.torque_capacity: 300";
    const Converted c =
        convert(machine_with(capacity, capacity + "\n    gear_box.initial_gear: " + gear).first);
    EXPECT_EQ(c.status, 0) << c.errors;
    EXPECT_NE(c.errors.find("selects no gear of its lists; it starts in neutral"), std::string::npos)
        << c.errors;
  }
}

// A tracked vehicle (the runtime's vehicle test) with `links` links per track and `tracks` tracks.
std::string tank(const std::string& links, int tracks = 1) {
  std::string text =
      "Sprocket is Vehicles.TrackSystem.Components.TrackWheels.Sprocket:\n"
      "    with Vehicles.TrackSystem.Components.TrackWheels.Traits.CylindricalShape\n"
      "    radius: 0.2\n"
      "    width: 0.3\n"
      "    body.inertia.mass: 10\n"
      "Idler is Vehicles.TrackSystem.Components.TrackWheels.Idler:\n"
      "    with Vehicles.TrackSystem.Components.TrackWheels.Traits.CylindricalShape\n"
      "    radius: 0.2\n"
      "    width: 0.3\n"
      "    body.inertia.mass: 10\n"
      "Tank is Physics3D.System:\n"
      "    chassis is Physics3D.Bodies.RigidBody:\n"
      "        inertia.mass: 100\n"
      "        geometry is Physics3D.Geometries.Box:\n"
      "            size: {2, 0.2, 0.2}\n";
  for (int t = 0; t < tracks; ++t) {
    const std::string side = std::to_string(t), y = t == 0 ? "0.3" : "-0.3";
    text += "        sprocket_" + side +
            " is Physics3D.Interactions.MateConnector:\n"
            "            main_axis: Math.Vec3.Y_AXIS()\n"
            "            normal: Math.Vec3.Z_AXIS()\n"
            "            position: {-1, " +
            y +
            ", -0.2}\n"
            "        idler_" +
            side +
            " is Physics3D.Interactions.MateConnector:\n"
            "            main_axis: Math.Vec3.Y_AXIS()\n"
            "            normal: Math.Vec3.Z_AXIS()\n"
            "            position: {1, " +
            y + ", -0.2}\n";
  }
  for (int t = 0; t < tracks; ++t) {
    const std::string side = std::to_string(t);
    text += "    track_" + side +
            " is Vehicles.TrackSystem.Base:\n"
            "        tracks.link_count: " +
            links +
            "\n"
            "        tracks.link_description becomes "
            "Vehicles.TrackSystem.Components.Tracks.LinkDescription.Box:\n"
            "            width: 0.3\n"
            "            height: 0.05\n"
            "        track_wheels: [track_" +
            side + ".sprocket, track_" + side +
            ".idler]\n"
            "        sprocket is Sprocket\n"
            "        idler is Idler\n"
            "        chassis_body: chassis\n"
            "    connection_" +
            side +
            " is Vehicles.TrackSystem.Connections.Base with "
            "Vehicles.TrackSystem.Connections.Traits.TwoWheels:\n"
            "        track_system: track_" +
            side + "\n        connectors: [chassis.sprocket_" + side + ", chassis.idler_" + side + "]\n";
  }
  return text;
}

// The line of track `t`'s link_count in tank(links, tracks).
int link_count_line(int tracks, int t) {
  return 15 + 8 * tracks + 2 + 12 * t;
}

TEST_F(Hostile, TrackLinkCountsBeyondWhatMuJoCoAllocatesAreErrors) {
  // Release once wrote njmax="-424508940" for this one.
  expect_error_at(convert(tank("1000000000")), link_count_line(1, 0), 9,
                  "`track_0.tracks.link_count` is 1e+09; a track has 3 to 300 links");
  expect_error_at(convert(tank("301")), link_count_line(1, 0), 9, "a track has 3 to 300 links");
  expect_error_at(convert(tank("2")), link_count_line(1, 0), 9, "a track has 3 to 300 links");
  // Two tracks within the bound each, beyond it together: an error at the second track system.
  const Converted both = convert(tank("200", 2));
  EXPECT_EQ(both.status, 1);
  EXPECT_NE(both.errors.find("brings the model's track links to 400"), std::string::npos) << both.errors;
  EXPECT_NE(both.errors.find("[mjcf-too-large]"), std::string::npos) << both.errors;
  EXPECT_EQ(both.xml, "");
}

// The documented maximum is true: a model with 300 track links loads in MuJoCo 2.2.2 and gets its data.
TEST_F(Hostile, TrackOfTheDocumentedMaximumLoadsInMuJoCo) {
  const Converted c = convert(tank("150", 2));
  ASSERT_EQ(c.status, 0) << c.errors;
  EXPECT_NE(c.xml.find("<size njmax=\"5300\" nconmax=\"1300\"/>"), std::string::npos);
  char error[1000] = "";
  mjModel* m = mj_loadXML(path("scene.xml").c_str(), nullptr, error, sizeof(error));
  ASSERT_NE(m, nullptr) << error;
  mjData* d = mj_makeData(m);
  EXPECT_NE(d, nullptr);
  if (d) {
    mj_step(m, d);
    EXPECT_EQ(d->warning[mjWARN_CNSTRFULL].number, 0);
    mj_deleteData(d);
  }
  mj_deleteModel(m);
}

TEST_F(Hostile, TimestepOutsideWhatMuJoCoCanStepIsAUsageError) {
  const std::string model = rod("1.0");
  for (const char* bad : {"1e308", "1e-320", "2", "1e-7", "nan", "inf"}) {
    const Converted c = convert(model, {"--timestep", bad});
    EXPECT_EQ(c.status, 2) << bad;
    EXPECT_NE(c.errors.find("from 1e-06 to 1"), std::string::npos) << c.errors;
    EXPECT_EQ(c.xml, "");
  }
  EXPECT_EQ(convert(model, {"--timestep", "1"}).status, 0);
  EXPECT_EQ(convert(model, {"--timestep", "1e-6"}).status, 0);
}

// ------------------------------------------------------------------------------------------- files

// A body with a collision mesh (line 4) and a visual mesh (line 6) read from `file`.
std::string meshes(const std::string& file) {
  return "Scene is Physics3D.System:\n"
         "    body is Physics3D.Bodies.RigidBody:\n"
         "        inertia.mass: 1.0\n"
         "        shape is Physics3D.Geometries.ExternalTriMeshGeometry:\n"
         "            path: @\"" +
         file +
         "\"\n"
         "        look is Visuals.Geometries.ExternalTriMeshGeometry:\n"
         "            path: @\"" +
         file + "\"\n";
}

// The same body with only the visual mesh (line 4), and a box to collide with.
std::string visual_mesh(const std::string& file) {
  return "Scene is Physics3D.System:\n"
         "    body is Physics3D.Bodies.RigidBody:\n"
         "        inertia.mass: 1.0\n"
         "        look is Visuals.Geometries.ExternalTriMeshGeometry:\n"
         "            path: @\"" +
         file +
         "\"\n"
         "        shape is Physics3D.Geometries.Box:\n"
         "            size: {0.1, 0.1, 0.1}\n";
}

void write_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

std::string stl_of(uint32_t claimed, const std::vector<std::array<float, 9>>& triangles) {
  std::string bytes(80, '\0');
  bytes.append(reinterpret_cast<const char*>(&claimed), 4);
  for (const auto& t : triangles) {
    bytes.append(12, '\0');  // normal
    bytes.append(reinterpret_cast<const char*>(t.data()), 36);
    bytes.append(2, '\0');
  }
  return bytes;
}

TEST_F(Hostile, BrokenMeshFilesAreErrorsWhereTheyCollideAndWarningsWhereOnlySeen) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::string tetra_obj =
      "v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nv 0 0 0.1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  struct Case {
    const char* file;
    std::string bytes;
    const char* problem;
  };
  const Case cases[] = {
      {"garbage.stl", std::string(700, '\x5a'), "triangles"},
      {"truncated.stl", stl_of(4, {{0, 0, 0, 1, 0, 0, 0, 1, 0}}), "truncated"},
      {"nan.stl", stl_of(1, {{nan, 0, 0, 1, 0, 0, 0, 1, 0}}), "vertex 1 is nan"},
      {"flat.stl", stl_of(2, {{0, 0, 0, 1, 0, 0, 0, 1, 0}, {1, 0, 0, 1, 1, 0, 0, 1, 0}}), "on one plane"},
      {"garbage.obj", "this is not\nan obj file\n", "0 vertices"},
      {"truncated.obj", "v 0 0 0\nv 0.1 0 0\nv 0 0.1", "line 3: a vertex of 2 numbers"},  // crashed MuJoCo
      {"nan.obj", "v nan 0 0\n" + tetra_obj.substr(8), "vertex 1 is nan"},
      {"badface.obj", tetra_obj + "f 1 2 9\n", "face corner '9' names no vertex"},
  };
  for (const Case& k : cases) {
    SCOPED_TRACE(k.file);
    write_bytes(dir_ / k.file, k.bytes);
    const Converted c = convert(meshes(k.file));
    expect_error_at(c, 4, 9, "`body.shape.path` cannot be a MuJoCo mesh", "mjcf-bad-asset");
    EXPECT_NE(c.errors.find(k.problem), std::string::npos) << c.errors;
    EXPECT_NE(c.errors.find("scene.openplx:6:9: warning: mesh file " + path(k.file) + " of `body.look.path`"),
              std::string::npos)
        << c.errors;
    EXPECT_EQ(c.errors.find("QH6"), std::string::npos) << "qhull's text: " << c.errors;
    // Only visual: the model converts, without the visual geometry, and says so.
    const Converted seen = convert(visual_mesh(k.file));
    EXPECT_EQ(seen.status, 0) << seen.errors;
    EXPECT_NE(seen.errors.find("scene.openplx:4:9: warning: "), std::string::npos) << seen.errors;
    EXPECT_NE(seen.errors.find("this visual geometry was left out"), std::string::npos) << seen.errors;
    EXPECT_EQ(seen.xml.find("<mesh"), std::string::npos) << seen.xml;
  }
  // The same meshes whole are fine.
  write_bytes(dir_ / "good.obj", tetra_obj);
  const Converted obj = convert(meshes("good.obj"));
  EXPECT_EQ(obj.status, 0) << obj.errors;
  openplx::testing::write_tetrahedron(dir_ / "good.stl");
  const Converted stl = convert(meshes("good.stl"));
  EXPECT_EQ(stl.status, 0) << stl.errors;
  EXPECT_EQ(stl.errors, "");
}

TEST_F(Hostile, FlatVertexMeshesAreErrorsWhereTheyCollideAndWarningsWhereOnlySeen) {
  const std::string flat = "[{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}]";
  expect_error_at(convert("Scene is Physics3D.System:\n"
                          "    body is Physics3D.Bodies.RigidBody:\n"
                          "        inertia.mass: 1.0\n"
                          "        hull is Physics3D.Geometries.ConvexMesh:\n"
                          "            vertices: " +
                          flat + "\n"),
                  4, 9, "`body.hull.vertices` cannot be a MuJoCo mesh: its vertices lie on one plane",
                  "mjcf-bad-asset");
  const Converted seen = convert(
      "Scene is Physics3D.System:\n"
      "    body is Physics3D.Bodies.RigidBody:\n"
      "        inertia.mass: 1.0\n"
      "        look is Visuals.Geometries.ConvexMesh:\n"
      "            vertices: " +
      flat +
      "\n"
      "        shape is Physics3D.Geometries.Box:\n"
      "            size: {0.1, 0.1, 0.1}\n");
  EXPECT_EQ(seen.status, 0) << seen.errors;
  EXPECT_NE(seen.errors.find("scene.openplx:4:9: warning: `body.look.vertices` cannot be a MuJoCo mesh"),
            std::string::npos)
      << seen.errors;
  EXPECT_EQ(seen.xml.find("<mesh"), std::string::npos) << seen.xml;
}

TEST_F(Hostile, ATextureThatIsNoPngIsLeftOutWithAWarning) {
  write_bytes(dir_ / "fake.png", "GIF89a, not a PNG at all");
  const Converted c = convert(
      "import @\"fake.png\" as Fake\n"
      "const Shown is Fake\n"
      "Scene is Physics3D.System:\n"
      "    paint is Visuals.Materials.Material with Visuals.Materials.SurfaceFeatures.BaseColor:\n"
      "        base_color_map: Shown\n"
      "    body is Physics3D.Bodies.RigidBody:\n"
      "        inertia.mass: 1\n"
      "        shape is Physics3D.Geometries.Box:\n"
      "            size: {1, 1, 1}\n"
      "        look is Visuals.Geometries.Box:\n"
      "            size: {1, 1, 1}\n"
      "            material: paint\n");
  EXPECT_EQ(c.status, 0) << c.errors;
  EXPECT_NE(
      c.errors.find("is no PNG image MuJoCo can read (it does not start as a PNG file does); the texture "
                    "was left out"),
      std::string::npos)
      << c.errors;
  EXPECT_NE(c.errors.find("scene.openplx:"), std::string::npos) << c.errors;
  EXPECT_EQ(c.xml.find("<texture"), std::string::npos) << c.xml;
  char error[1000] = "";
  mjModel* m = mj_loadXML(path("scene.xml").c_str(), nullptr, error, sizeof(error));
  EXPECT_NE(m, nullptr) << error;
  if (m) mj_deleteModel(m);
}

// A PNG chunk: length, type, data and its CRC-32 (the PNG specification's, bit by bit).
std::string png_chunk(const std::string& type, const std::string& data) {
  auto be32 = [](uint32_t v) {
    return std::string{static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8),
                       static_cast<char>(v)};
  };
  uint32_t crc = 0xffffffffu;
  for (const char byte : type + data) {
    crc ^= static_cast<unsigned char>(byte);
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return be32(static_cast<uint32_t>(data.size())) + type + data + be32(~crc);
}

// MuJoCo would decode the image whole before anything else: a header claiming 10^6 x 10^6 pixels is left
// out with a warning before it tries (checksums right; the pixel data itself is one zlib block of nothing).
TEST_F(Hostile, ATextureClaimingMorePixelsThanMuJoCoHoldsIsLeftOut) {
  const std::string million("\x00\x0f\x42\x40", 4);  // 1000000, big-endian
  const std::string header = million + million + std::string("\x08\x06\x00\x00\x00", 5);  // 8-bit RGBA
  write_bytes(dir_ / "huge.png", "\x89PNG\r\n\x1a\n" + png_chunk("IHDR", header) +
                                     png_chunk("IDAT", std::string("\x78\x9c\x03\x00\x00\x00\x00\x01", 8)) +
                                     png_chunk("IEND", ""));
  const Converted c = convert(
      "import @\"huge.png\" as Huge\n"
      "const Shown is Huge\n"
      "Scene is Physics3D.System:\n"
      "    paint is Visuals.Materials.Material with Visuals.Materials.SurfaceFeatures.BaseColor:\n"
      "        base_color_map: Shown\n"
      "    body is Physics3D.Bodies.RigidBody:\n"
      "        inertia.mass: 1\n"
      "        shape is Physics3D.Geometries.Box:\n"
      "            size: {1, 1, 1}\n"
      "        look is Visuals.Geometries.Box:\n"
      "            size: {1, 1, 1}\n"
      "            material: paint\n");
  EXPECT_EQ(c.status, 0) << c.errors;
  EXPECT_NE(c.errors.find("its header claims 1000000 x 1000000 pixels, more than MuJoCo keeps in a texture"),
            std::string::npos)
      << c.errors;
  EXPECT_NE(c.errors.find("the texture was left out"), std::string::npos) << c.errors;
  EXPECT_EQ(c.xml.find("<texture"), std::string::npos) << c.xml;
}

// ------------------------------------------------------------------------------------------ backstop

TEST(NonFiniteBackstop, WrittenNumbersAreCountedAndFound) {
  namespace mj = openplx::mjcf;
  mj::Element root("mujoco");
  root.add("body").set("name", "inf").set("pos", "0 0 0");  // a name is no number
  EXPECT_EQ(root.first_non_finite(), "");
  const size_t before = mj::non_finite_numbers_written();
  root.add("body").set("pos", Eigen::Vector3d(0, std::numeric_limits<double>::quiet_NaN(), 0));
  EXPECT_EQ(mj::non_finite_numbers_written(), before + 1);
  EXPECT_EQ(root.first_non_finite(), "<body pos=\"0 nan 0\">");
  root.children().pop_back();
  root.add("geom").set("mass", std::numeric_limits<double>::infinity());
  EXPECT_EQ(root.first_non_finite(), "<geom mass=\"inf\">");
  EXPECT_EQ(mj::non_finite_numbers_written(), before + 2);
}

}  // namespace
