// What real robot files do, taken as they come: mimic joints with offsets start where the mimic puts them and
// stay coupled; joints named like links keep their URDF names in MuJoCo and get a usable OpenPLX name;
// planar joints' ignored limits are said; malformed numbers urdfdom would swallow are located errors;
// `package://` resolves through ROS_PACKAGE_PATH and AMENT_PREFIX_PATH; URDF 1.1 capsules and quaternion
// origins are read; blocks for other tools are reported. Parity with MuJoCo's importer for the robots of
// tests/urdf/robots is in urdf_parity_test.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "openplx/runtime/simulation.h"
#include "tests/support/scoped_env.h"
#include "tests/support/scratch_dir.h"
#include "tests/support/tetrahedron_stl.h"
#include "tools/cli/cli.h"

namespace {

namespace fs = std::filesystem;
namespace rt = openplx::runtime;

const fs::path kRobots = fs::path(OPENPLX_TEST_DATA_DIR) / "urdf" / "robots";

int cli(const std::vector<std::string>& args, std::string* err) {
  std::ostringstream out, errors;
  const int status = openplx::cli::run(args, out, errors);
  *err = errors.str();
  return status;
}

double joint_value(rt::Simulation& sim, const char* joint) {
  const mjModel* m = sim.model();
  const int j = mj_name2id(m, mjOBJ_JOINT, joint);
  EXPECT_GE(j, 0) << joint;
  return j < 0 ? 0.0 : sim.data()->qpos[m->jnt_qposadr[j]];
}

// The gripper's inner knuckle follows the driving one with multiplier 1.0585 and offset 0.7235, the fingertip
// follows the inner knuckle with -1 and 0.1. Both start where their mimic puts them (`--check` finds no
// violated coupling) and stay on it while the fingers fall under gravity: the couplings are rigid
// (solref 2h), so a few 1e-4 rad of lag at most.
TEST(UrdfMimic, OffsetFollowersStartOnTheirMimicAndStayOnIt) {
  const std::string urdf = (kRobots / "mimic_offset_hand.urdf").string();
  std::string err;
  EXPECT_EQ(cli({urdf, "--check", "-o", "-"}, &err), openplx::cli::kExitOk) << err;
  rt::Simulation sim = rt::Simulation::load(urdf);
  EXPECT_DOUBLE_EQ(joint_value(sim, "inner_knuckle_joint"), 0.7235);
  EXPECT_DOUBLE_EQ(joint_value(sim, "fingertip_joint"), 0.1 - 0.7235);
  double moved = 0;
  for (int k = 0; k < 5; ++k) {
    sim.advance(0.1);
    const double leader = joint_value(sim, "finger_joint");
    const double inner = joint_value(sim, "inner_knuckle_joint");
    moved = std::max(moved, std::abs(leader));
    EXPECT_NEAR(inner, 0.7235 + 1.0585 * leader, 5e-4);
    EXPECT_NEAR(joint_value(sim, "fingertip_joint"), 0.1 - inner, 5e-4);
  }
  EXPECT_GT(moved, 0.05);  // the coupling was exercised, not only the start
}

// URDF joints and links live in separate namespaces: joint `shoulder` moves link `shoulder`. In MuJoCo the
// joint keeps its name; in OpenPLX it is `shoulder_joint` (and `shoulder_limits`, a link, pushes the range
// of joint `shoulder` to `shoulder_joint_limits`), both usable from an extending model.
TEST(UrdfNames, JointsNamedLikeLinksKeepTheirNamesInMuJoCo) {
  const openplx::testing::ScratchDir dir;
  fs::copy_file(kRobots / "shared_names.urdf", dir / "shared_names.urdf");
  std::ofstream(dir / "arm.openplx") << "import @\"shared_names.urdf\"\n"
                                        "Arm is shared_names:\n"
                                        "    angle is Physics.Signals.AngleOutput:\n"
                                        "        source: shoulder_joint\n"
                                        "    shoulder_joint_limits.end: 1.5\n";
  rt::Simulation sim = rt::Simulation::load((dir / "arm.openplx").string());
  const mjModel* m = sim.model();
  for (const char* joint : {"shoulder", "elbow", "wrist"}) EXPECT_GE(mj_name2id(m, mjOBJ_JOINT, joint), 0);
  for (const char* body : {"shoulder", "elbow", "shoulder_limits"})
    EXPECT_GE(mj_name2id(m, mjOBJ_BODY, body), 0);
  const int shoulder = mj_name2id(m, mjOBJ_JOINT, "shoulder");
  EXPECT_EQ(m->jnt_limited[shoulder], 1);
  EXPECT_EQ(m->jnt_range[2 * shoulder + 1], 1.5);  // the extension's, through the renamed range
  sim.data()->qpos[m->jnt_qposadr[shoulder]] = 0.3;
  mj_forward(sim.model(), sim.data());
  EXPECT_DOUBLE_EQ(sim.output("angle").real(), 0.3);
}

// A planar joint is MuJoCo's three joints (their axes are checked against MuJoCo's importer in
// urdf_parity_test); its <limit>, which URDF applies to revolute and prismatic joints only, is a warning at
// the <limit>, an error under --strict.
TEST(UrdfPlanar, LimitIsIgnoredWithALocatedWarning) {
  const openplx::testing::ScratchDir dir;
  std::ifstream in(kRobots / "planar_puck.urdf");
  std::stringstream text;
  text << in.rdbuf();
  std::string urdf = text.str();
  const std::string dynamics = "    <dynamics damping=\"0.3\" friction=\"0.05\"/>\n";
  const size_t at = urdf.find(dynamics);
  ASSERT_NE(at, std::string::npos);
  urdf.insert(at, "    <limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/>\n");
  const int line = 1 + static_cast<int>(std::count(urdf.begin(), urdf.begin() + at, '\n'));
  std::ofstream(dir / "puck.urdf") << urdf;
  std::string err;
  EXPECT_EQ(cli({(dir / "puck.urdf").string(), "--check", "-o", (dir / "puck.xml").string()}, &err),
            openplx::cli::kExitOk);
  EXPECT_NE(err.find((dir / "puck.urdf").string() + ":" + std::to_string(line) +
                     ":5: warning: joint `puck_plane` is planar: URDF limits only revolute and prismatic "
                     "joints, so its <limit> was ignored"),
            std::string::npos)
      << err;
  std::ifstream xml(dir / "puck.xml");
  std::stringstream mjcf;
  mjcf << xml.rdbuf();
  for (const char* joint :
       {"puck_plane_TX\" type=\"slide", "puck_plane_TY\" type=\"slide", "puck_plane_RZ\" type=\"hinge"}) {
    EXPECT_NE(mjcf.str().find(joint), std::string::npos) << joint;
  }
  EXPECT_EQ(mjcf.str().find(" range="), mjcf.str().find(" range=\"-1.5 1.5\""));  // the arm's only
  EXPECT_EQ(cli({(dir / "puck.urdf").string(), "--strict", "-o", (dir / "strict.xml").string()}, &err),
            openplx::cli::kExitInputError);
  EXPECT_FALSE(fs::exists(dir / "strict.xml"));
}

// A one-link robot with the given visual origin attributes, mass and visual shape.
std::string robot_with(const std::string& visual_origin, const std::string& mass = "1",
                       const std::string& shape = "<box size=\"0.1 0.1 0.1\"/>") {
  return "<?xml version=\"1.0\"?>\n"
         "<robot name=\"bad\">\n"
         "  <link name=\"base\">\n"
         "    <inertial><mass value=\"" +
         mass +
         "\"/><inertia ixx=\"0.1\" iyy=\"0.1\" izz=\"0.1\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial>\n"
         "    <visual><origin " +
         visual_origin + "/><geometry>" + shape +
         "</geometry></visual>\n"
         "  </link>\n"
         "</robot>\n";
}

// urdfdom drops a <visual> whose origin does not parse, or whose shape lacks what it needs, with exit 0 and
// no word. Every malformed number and every incomplete shape is an error at its element; nothing is written.
TEST(UrdfValues, MalformedValuesAreLocatedErrors) {
  const openplx::testing::ScratchDir dir;
  const std::vector<std::tuple<std::string, std::string, std::string>> cases = {
      {"xyz=\"abc 1 2\"", "1", ":5:13: error: <origin> xyz=\"abc 1 2\" is not 3 numbers (`abc`)"},
      {"xyz=\"1 2\"", "1", ":5:13: error: <origin> xyz=\"1 2\" is not 3 numbers"},
      {"rpy=\"0 0 nan\"", "1", ":5:13: error: <origin> rpy=\"0 0 nan\" is not 3 numbers (`nan`)"},
      {"xyz=\"0 0 0\"", "1,5", ":4:15: error: <mass> value=\"1,5\" is not a number (`1,5`)"},
  };
  for (const auto& [origin, mass, expected] : cases) {
    SCOPED_TRACE(origin + " " + mass);
    std::ofstream(dir / "bad.urdf") << robot_with(origin, mass);
    std::string err;
    EXPECT_EQ(cli({(dir / "bad.urdf").string(), "-o", (dir / "bad.xml").string()}, &err),
              openplx::cli::kExitInputError);
    EXPECT_EQ(err.rfind((dir / "bad.urdf").string() + expected, 0), 0u) << err;
    EXPECT_FALSE(fs::exists(dir / "bad.xml"));
  }
  const std::vector<std::pair<std::string, std::string>> shapes = {
      {"<sphere/>", ":5:44: error: <sphere> has no radius attribute"},
      {"<mesh/>", ":5:44: error: <mesh> has no filename attribute"},
      {"<cone radius=\"1\"/>", ":5:44: error: <cone> is not a URDF shape"},
  };
  for (const auto& [shape, expected] : shapes) {
    SCOPED_TRACE(shape);
    std::ofstream(dir / "bad.urdf") << robot_with("xyz=\"0 0 0\"", "1", shape);
    std::string err;
    EXPECT_EQ(cli({(dir / "bad.urdf").string(), "-o", (dir / "bad.xml").string()}, &err),
              openplx::cli::kExitInputError);
    EXPECT_EQ(err.rfind((dir / "bad.urdf").string() + expected, 0), 0u) << err;
    EXPECT_FALSE(fs::exists(dir / "bad.xml"));
  }
}

using openplx::testing::write_tetrahedron;

using openplx::testing::ScopedEnv;

// A robot whose mesh package is not above its file: found as ROS finds it, through ROS_PACKAGE_PATH (a
// workspace's src folder, packages below it) or AMENT_PREFIX_PATH (<prefix>/share/<package>).
TEST(UrdfPackages, RosPackagePathsResolvePackageUris) {
  const openplx::testing::ScratchDir dir;
  fs::create_directories(dir / "robots");
  std::ofstream(dir / "robots" / "arm.urdf")
      << "<?xml version=\"1.0\"?>\n<robot name=\"arm\">\n  <link name=\"base\">\n"
         "    <inertial><mass value=\"1\"/><inertia ixx=\"0.1\" iyy=\"0.1\" izz=\"0.1\" ixy=\"0\" ixz=\"0\" "
         "iyz=\"0\"/></inertial>\n"
         "    <visual><geometry><mesh filename=\"package://far_pkg/meshes/tetra.stl\"/></geometry></visual>\n"
         "  </link>\n</robot>\n";
  const std::string urdf = (dir / "robots" / "arm.urdf").string();
  std::string err;
  {
    const ScopedEnv ros("ROS_PACKAGE_PATH", "");
    const ScopedEnv ament("AMENT_PREFIX_PATH", "");
    // Nowhere to be found: a visual never sinks a robot, so it is left out with a warning naming the package.
    EXPECT_EQ(cli({urdf, "--check", "-o", "-"}, &err), openplx::cli::kExitOk) << err;
    EXPECT_NE(err.find("package `far_pkg` not found; this visual was left out"), std::string::npos) << err;
  }
  write_tetrahedron(dir / "ws" / "src" / "group" / "far_pkg" / "meshes" / "tetra.stl");
  {
    const ScopedEnv ros("ROS_PACKAGE_PATH", "/nonexistent:" + (dir / "ws" / "src").string());
    EXPECT_EQ(cli({urdf, "--check", "-o", "-"}, &err), openplx::cli::kExitOk) << err;
  }
  fs::rename(dir / "ws" / "src" / "group" / "far_pkg", dir / "far_pkg_moved");
  write_tetrahedron(dir / "install" / "share" / "far_pkg" / "meshes" / "tetra.stl");
  {
    const ScopedEnv ros("ROS_PACKAGE_PATH", "");
    const ScopedEnv ament("AMENT_PREFIX_PATH", (dir / "install").string());
    EXPECT_EQ(cli({urdf, "--check", "-o", "-"}, &err), openplx::cli::kExitOk) << err;
  }
}

// URDF 1.1: a capsule is a MuJoCo capsule (radius, half the cylindrical length); an origin given as
// quat_xyzw places the link exactly as the same rotation given as rpy; both at once is an error.
TEST(UrdfVersion11, CapsulesAndQuaternionOriginsAreRead) {
  const openplx::testing::ScratchDir dir;
  auto robot = [](const std::string& joint_rotation) {
    return "<?xml version=\"1.0\"?>\n<robot name=\"r\">\n"
           "  <link name=\"base\"><inertial><mass value=\"1\"/><inertia ixx=\"1\" iyy=\"1\" izz=\"1\" "
           "ixy=\"0\" "
           "ixz=\"0\" iyz=\"0\"/></inertial></link>\n"
           "  <link name=\"arm\"><inertial><mass value=\"2\"/><inertia ixx=\"1\" iyy=\"2\" izz=\"2\" "
           "ixy=\"0\" "
           "ixz=\"0\" iyz=\"0\"/></inertial>\n"
           "    <collision><geometry><capsule radius=\"0.05\" "
           "length=\"0.3\"/></geometry></collision></link>\n"
           "  <joint name=\"j\" type=\"revolute\"><parent link=\"base\"/><child link=\"arm\"/>\n"
           "    <origin xyz=\"0 0 1\" " +
           joint_rotation +
           "/><axis xyz=\"0 1 0\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>\n"
           "</robot>\n";
  };
  // The same rotation: 0.5 rad about (1, 2, 3)/|(1, 2, 3)|.
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 2, 3).normalized()));
  const Eigen::Matrix3d r = q.toRotationMatrix();
  const double roll = std::atan2(r(2, 1), r(2, 2)), pitch = std::asin(-r(2, 0)),
               yaw = std::atan2(r(1, 0), r(0, 0));
  std::ostringstream with_rpy, with_quat;
  with_rpy.precision(17);
  with_quat.precision(17);
  with_rpy << "rpy=\"" << roll << " " << pitch << " " << yaw << "\"";
  with_quat << "quat_xyzw=\"" << q.x() << " " << q.y() << " " << q.z() << " " << q.w() << "\"";
  std::ofstream(dir / "rpy.urdf") << robot(with_rpy.str());
  std::ofstream(dir / "quat.urdf") << robot(with_quat.str());
  rt::Simulation a = rt::Simulation::load((dir / "rpy.urdf").string());
  rt::Simulation b = rt::Simulation::load((dir / "quat.urdf").string());
  const int arm = mj_name2id(a.model(), mjOBJ_BODY, "arm");
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(a.data()->xquat[4 * arm + k], b.data()->xquat[4 * arm + k], 1e-15);
  EXPECT_NEAR(b.data()->xquat[4 * arm + 1], q.x(), 1e-15);
  const mjModel* m = b.model();
  int capsules = 0;
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->geom_type[g] != mjGEOM_CAPSULE) continue;
    ++capsules;
    EXPECT_DOUBLE_EQ(m->geom_size[3 * g], 0.05);
    EXPECT_DOUBLE_EQ(m->geom_size[3 * g + 1], 0.15);
  }
  EXPECT_EQ(capsules, 1);
  std::ofstream(dir / "both.urdf") << robot(with_rpy.str() + " " + with_quat.str());
  std::string err;
  EXPECT_EQ(cli({(dir / "both.urdf").string(), "-o", "-"}, &err), openplx::cli::kExitInputError);
  EXPECT_NE(err.find(":7:5: error: <origin> has both rpy and quat_xyzw; URDF allows one"), std::string::npos)
      << err;
}

// <transmission> (ros_control), <mujoco> and <gazebo> blocks are read by nobody here: each is a warning at
// its line saying what it holds and what was (not) done.
TEST(UrdfOtherTools, BlocksForOtherToolsAreReported) {
  const openplx::testing::ScratchDir dir;
  std::ofstream(dir / "r.urdf")
      << "<?xml version=\"1.0\"?>\n<robot name=\"r\">\n"
         "  <link name=\"base\"><inertial><mass value=\"1\"/><inertia ixx=\"1\" iyy=\"1\" izz=\"1\" "
         "ixy=\"0\" "
         "ixz=\"0\" iyz=\"0\"/></inertial></link>\n"
         "  <transmission name=\"t\"><type>transmission_interface/SimpleTransmission</type></transmission>\n"
         "  <mujoco><compiler discardvisual=\"true\"/></mujoco>\n"
         "  <gazebo reference=\"base\"><material>Gazebo/Grey</material></gazebo>\n"
         "</robot>\n";
  std::string err;
  EXPECT_EQ(cli({(dir / "r.urdf").string(), "-o", "-"}, &err), openplx::cli::kExitOk) << err;
  const std::string file = (dir / "r.urdf").string();
  EXPECT_NE(
      err.find(file + ":4:3: warning: <transmission> was not read: it holds a ros_control transmission: "
                      "no actuator was made from it"),
      std::string::npos)
      << err;
  EXPECT_NE(err.find(file + ":5:3: warning: <mujoco> was not read"), std::string::npos) << err;
  EXPECT_NE(err.find(file + ":6:3: warning: <gazebo> was not read"), std::string::npos) << err;
}

}  // namespace
