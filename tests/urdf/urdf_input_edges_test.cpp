// What real URDF files bring to the import's door: file names in any case (`robot.URDF`), numbers
// written every way urdfdom reads them (and no way it does not), unexpanded xacro templates, `package://`
// meshes whose package is nowhere, and `--check` findings placed at the URDF element they concern.
#include <console_bridge/console.h>
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <urdf_parser/urdf_parser.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>

#include "openplx/runtime/simulation.h"
#include "tests/support/scoped_env.h"
#include "tests/support/scratch_dir.h"
#include "tests/support/tetrahedron_stl.h"
#include "tools/cli/cli.h"

namespace {

namespace fs = std::filesystem;
namespace rt = openplx::runtime;

int cli(const std::vector<std::string>& args, std::string* err) {
  std::ostringstream out, errors;
  const int status = openplx::cli::run(args, out, errors);
  *err = errors.str();
  return status;
}

std::string read(const fs::path& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

using openplx::testing::ScopedEnv;

// A base and an arm on a hinge. Line 6 holds the joint's <origin> (xyz), line 7 its <limit> (upper).
std::string hinge_robot(const std::string& xyz, const std::string& upper) {
  return "<?xml version=\"1.0\"?>\n"  // 1
         "<robot name=\"hinge\">\n"   // 2
         "  <link name=\"base\"><inertial><mass value=\"1\"/><inertia ixx=\"1\" iyy=\"1\" izz=\"1\" "
         "ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial></link>\n"  // 3
         "  <link name=\"arm\"><inertial><mass value=\"1\"/><inertia ixx=\"1\" iyy=\"1\" izz=\"1\" "
         "ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial></link>\n"                                   // 4
         "  <joint name=\"j\" type=\"revolute\"><parent link=\"base\"/><child link=\"arm\"/>\n"  // 5
         "    <origin xyz=\"" +
         xyz +
         "\"/><axis xyz=\"0 0 1\"/>\n"  // 6
         "    <limit lower=\"-1\" upper=\"" +
         upper +
         "\" effort=\"10\" velocity=\"1\"/></joint>\n"  // 7
         "</robot>\n";
}

// A file named robot.URDF (Windows exporters, SolidWorks' sw_urdf_exporter) is a URDF, given directly and
// imported from OpenPLX.
TEST(UrdfInputEdges, ExtensionsAreCaseInsensitive) {
  const openplx::testing::ScratchDir dir;
  std::string err;
  for (const std::string name : {"arm.URDF", "arm2.Urdf"}) {
    std::ofstream(dir / name) << hinge_robot("0 0 1", "1");
    EXPECT_EQ(cli({(dir / name).string(), "-o", (dir / "direct.xml").string(), "--check"}, &err), 0)
        << name << "\n"
        << err;
    EXPECT_NE(read(dir / "direct.xml").find("<joint name=\"j\""), std::string::npos) << name;
  }
  std::ofstream(dir / "scene.openplx") << "import @\"arm.URDF\"\nScene is arm\n";
  EXPECT_EQ(cli({(dir / "scene.openplx").string(), "-o", (dir / "scene.xml").string()}, &err), 0) << err;
  EXPECT_NE(read(dir / "scene.xml").find("<joint name=\"j\""), std::string::npos);
  rt::Simulation sim = rt::Simulation::load((dir / "arm.URDF").string());
  EXPECT_GE(mj_name2id(sim.model(), mjOBJ_JOINT, "j"), 0);
}

// What urdfdom itself makes of `text`: the joint's origin and upper limit, or nullopt when it rejects it.
struct UrdfdomReading {
  double x = 0, y = 0, z = 0, upper = 0;
};
std::optional<UrdfdomReading> urdfdom_reading(const std::string& text) {
  console_bridge::noOutputHandler();  // its messages for the numbers it refuses are not this test's output
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(text);
  console_bridge::restorePreviousOutputHandler();
  if (!model) return std::nullopt;
  const urdf::JointConstSharedPtr joint = model->getJoint("j");
  if (!joint || !joint->limits) return std::nullopt;
  const urdf::Vector3& p = joint->parent_to_joint_origin_transform.position;
  return UrdfdomReading{p.x, p.y, p.z, joint->limits->upper};
}

// Every way of writing a number is taken or refused exactly as urdfdom 3.0.1 (urdf::parseURDF, run here)
// takes or refuses it, and taken with urdfdom's value; refused, it is an error at the line of the element
// holding it, quoting the word. A list splits at spaces only (urdfdom's split_string), each word read as
// `stringstream >> double` that must reach the end: a tab or line break between numbers, or a space after
// a single number, is refused by urdfdom and by us.
TEST(UrdfInputEdges, NumbersAreReadExactlyAsUrdfdomReadsThem) {
  const openplx::testing::ScratchDir dir;
  const std::vector<std::string> scalars = {
      "1e-3",  "1E+2", ".5",   "5.",  "+2",  " 2",   "\t2", "2.5e+0", "-.5",  "007", "1e-400", "1e-310",
      "2 ",    "2\n",  "1..2", "abc", "1 2", "",     "1e",  "1e+",    ".",    "-",   "+-1",    "--1",
      "1e400", "0x10", "inf",  "nan", "1,5", "1.5.", "e5",  "1e5.0",  "1.e3", "\t"};
  const std::vector<std::string> lists = {"1e-3 0 0", "1E+2 .5 5.", "  0 0 0  ", "\t0 0 0", "+1 -1 +.5",
                                          "0  0   0", "0 0 0\n",    "0\t0 0",    "0 0\n0",  "1..2 0 0",
                                          "abc 0 0",  "0 0",        "0 0 0 0",   "\n0 0 0", "0 0 1e400",
                                          "0 0 inf",  "1,0 0 0",    "0 0 0 \t"};
  auto check = [&](const std::string& xyz, const std::string& upper, int line) {
    SCOPED_TRACE("xyz=\"" + xyz + "\" upper=\"" + upper + "\"");
    const std::string text = hinge_robot(xyz, upper);
    const fs::path urdf = dir / "numbers.urdf";
    std::ofstream(urdf) << text;
    const std::optional<UrdfdomReading> expected = urdfdom_reading(text);
    std::string err;
    const int status = cli({urdf.string(), "-o", (dir / "numbers.xml").string()}, &err);
    if (!expected) {
      EXPECT_EQ(status, openplx::cli::kExitInputError) << err;
      EXPECT_EQ(err.find(urdf.string() + ":" + std::to_string(line) + ":"), 0u) << err;
      EXPECT_NE(err.find("error: <"), std::string::npos) << err;
      EXPECT_NE(err.find("is not"), std::string::npos) << err;
      return;
    }
    ASSERT_EQ(status, 0) << err;
    rt::Simulation sim = rt::Simulation::load(urdf.string());
    const mjModel* m = sim.model();
    const int arm = mj_name2id(m, mjOBJ_BODY, "arm"), j = mj_name2id(m, mjOBJ_JOINT, "j");
    ASSERT_GE(arm, 0);
    ASSERT_GE(j, 0);
    EXPECT_EQ(m->body_pos[3 * arm], expected->x);
    EXPECT_EQ(m->body_pos[3 * arm + 1], expected->y);
    EXPECT_EQ(m->body_pos[3 * arm + 2], expected->z);
    if (expected->upper > -1) {
      EXPECT_EQ(m->jnt_range[2 * j + 1], expected->upper);
    }
  };
  for (const std::string& upper : scalars) check("0 0 1", upper, 7);
  for (const std::string& xyz : lists) check(xyz, "1", 6);
}

// An unexpanded xacro template is an error at its first xacro construct (an element or a ${...}
// placeholder) that says to expand it first, whatever its name; a URDF that declares xacro and fails for
// another reason gets that hint as a note.
TEST(UrdfInputEdges, XacroTemplatesAskToBeExpandedFirst) {
  const openplx::testing::ScratchDir dir;
  std::string err;
  std::ofstream(dir / "arm.urdf.xacro")
      << "<?xml version=\"1.0\"?>\n"
         "<robot name=\"arm\" xmlns:xacro=\"http://www.ros.org/wiki/xacro\">\n"
         "  <xacro:include filename=\"$(find arm)/urdf/parts.xacro\"/>\n"
         "  <xacro:arm_link name=\"base\"/>\n"
         "</robot>\n";
  const fs::path xacro = dir / "arm.urdf.xacro";
  EXPECT_EQ(cli({xacro.string(), "-o", (dir / "arm.xml").string()}, &err), openplx::cli::kExitInputError);
  EXPECT_EQ(err.find(xacro.string() +
                     ":3:3: error: this is an unexpanded xacro template (<xacro:include> here), not a URDF"),
            0u)
      << err;
  EXPECT_NE(err.find("Expand it first: `xacro arm.urdf.xacro > arm.urdf`"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir / "arm.xml"));
  // Placeholders alone, in a file named .urdf: at the element holding the first one.
  std::ofstream(dir / "box.urdf")
      << "<robot name=\"box\">\n"
         "  <link name=\"base\">\n"
         "    <collision><geometry><box size=\"${width} 1 1\"/></geometry></collision>\n"
         "  </link>\n"
         "</robot>\n";
  EXPECT_EQ(cli({(dir / "box.urdf").string(), "-o", (dir / "box.xml").string()}, &err),
            openplx::cli::kExitInputError);
  EXPECT_EQ(err.find((dir / "box.urdf").string() + ":3:26: error: this is an unexpanded xacro template (a " +
                     "${...} or $(...) placeholder here)"),
            0u)
      << err;
  EXPECT_NE(err.find("`xacro box.urdf > box.expanded.urdf`"), std::string::npos) << err;
  // xacro's output keeps the namespace: urdfdom's own failure, with the hint as a note.
  std::ofstream(dir / "empty.urdf") << "<?xml version=\"1.0\"?>\n"
                                       "<robot name=\"e\" xmlns:xacro=\"http://www.ros.org/wiki/xacro\">\n"
                                       "</robot>\n";
  EXPECT_EQ(cli({(dir / "empty.urdf").string()}, &err), openplx::cli::kExitInputError);
  EXPECT_EQ(err.find((dir / "empty.urdf").string() + ":2:1: error: No link elements found"), 0u) << err;
  EXPECT_NE(err.find("note: the file declares the xacro namespace (line 2): if it is a template, expand it "
                     "first: `xacro empty.urdf > empty.expanded.urdf`"),
            std::string::npos)
      << err;
  // An expanded file that keeps the namespace converts.
  std::ofstream(dir / "kept.urdf")
      << "<robot name=\"k\" xmlns:xacro=\"http://www.ros.org/wiki/xacro\">\n"
         "  <link name=\"base\"><inertial><mass value=\"1\"/><inertia ixx=\"1\" "
         "iyy=\"1\" izz=\"1\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial></link>\n"
         "</robot>\n";
  EXPECT_EQ(cli({(dir / "kept.urdf").string(), "-o", (dir / "kept.xml").string(), "--check"}, &err), 0)
      << err;
}

// A <robot> without a name (or with an empty one), which urdfdom refuses and MuJoCo's importer loads: it
// loads, named after its file (a URDF given directly is the model `<name>_robot`), with a warning at the
// <robot>; --strict makes that an error.
TEST(UrdfInputEdges, NamelessRobotIsNamedAfterItsFile) {
  const openplx::testing::ScratchDir dir;
  std::string err;
  for (const char* robot : {"<robot>", "<robot name=\"\">"}) {
    SCOPED_TRACE(robot);
    std::ofstream(dir / "wheel_cart.urdf")
        << "<?xml version=\"1.0\"?>\n"
        << robot
        << "\n  <link name=\"base\"><inertial><mass value=\"1\"/><inertia ixx=\"1\" iyy=\"1\" izz=\"1\" "
           "ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial></link>\n"
           "</robot>\n";
    const fs::path xml = dir / "wheel_cart.xml";
    ASSERT_EQ(cli({(dir / "wheel_cart.urdf").string(), "-o", xml.string(), "--check"}, &err), 0) << err;
    EXPECT_EQ(err.find((dir / "wheel_cart.urdf").string() + ":2:1: warning: the <robot> has "), 0u) << err;
    EXPECT_NE(err.find("it was named `wheel_cart` after its file"), std::string::npos) << err;
    EXPECT_NE(read(xml).find("<mujoco model=\"wheel_cart_robot\""), std::string::npos) << read(xml);
    fs::remove(xml);
    EXPECT_NE(cli({(dir / "wheel_cart.urdf").string(), "-o", xml.string(), "--strict"}, &err), 0) << err;
    EXPECT_FALSE(fs::exists(xml));
  }
}

// A robot whose meshes name `package://robot_pkg/...`, with a collision mesh on line 4 and a visual one on
// line 5.
std::string packaged_robot(const std::string& package) {
  return "<?xml version=\"1.0\"?>\n"
         "<robot name=\"pk\">\n"
         "  <link name=\"base\"><inertial><mass value=\"1\"/><inertia ixx=\"1\" iyy=\"1\" izz=\"1\" "
         "ixy=\"0\" "
         "ixz=\"0\" iyz=\"0\"/></inertial>\n"
         "    <collision><geometry><mesh filename=\"package://" +
         package +
         "/meshes/hull.stl\"/></geometry></collision>\n"
         "    <visual><geometry><mesh filename=\"package://" +
         package +
         "/meshes/look.stl\"/></geometry></visual>\n"
         "  </link>\n"
         "</robot>\n";
}

// A package found nowhere is said at the <mesh> naming it: the package, where it was looked for (the
// variables' folders, the URDF's folder and those above it) and what to set. A collision mesh is an error; a
// visual one a warning, and the robot converts without it.
TEST(UrdfInputEdges, PackageFoundNowhereIsSaidWithWhereItWasLookedFor) {
  const openplx::testing::ScratchDir dir;
  const ScopedEnv ros("ROS_PACKAGE_PATH", (dir / "ws" / "src").string());
  const ScopedEnv ament("AMENT_PREFIX_PATH", (dir / "install").string());
  fs::create_directories(dir / "robot" / "urdf");
  const fs::path urdf = dir / "robot" / "urdf" / "pk.urdf";
  std::ofstream(urdf) << packaged_robot("robot_pkg");
  std::string err;
  EXPECT_EQ(cli({urdf.string(), "-o", (dir / "pk.xml").string()}, &err), openplx::cli::kExitInputError);
  EXPECT_EQ(err.find(urdf.string() +
                     ":4:26: error: mesh package://robot_pkg/meshes/hull.stl: package `robot_pkg` not found "
                     "[urdf-invalid]"),
            0u)
      << err;
  EXPECT_NE(err.find("note: looked in ROS_PACKAGE_PATH (" + (dir / "ws" / "src").string() +
                     "), AMENT_PREFIX_PATH (" + (dir / "install" / "share").string() + "), and " +
                     (dir / "robot" / "urdf").string() +
                     " and the folders above it (for a folder named robot_pkg or holding meshes/hull.stl)"),
            std::string::npos)
      << err;
  EXPECT_NE(err.find("note: set ROS_PACKAGE_PATH (ROS 1) or AMENT_PREFIX_PATH (ROS 2) so that `robot_pkg` is "
                     "found, or import this URDF from an OpenPLX file that declares a Urdf.PackagePath with "
                     "name \"robot_pkg\""),
            std::string::npos)
      << err;
  EXPECT_NE(
      err.find(urdf.string() +
               ":5:23: warning: mesh package://robot_pkg/meshes/look.stl: package `robot_pkg` not found; "
               "this visual was left out [urdf-warning]"),
      std::string::npos)
      << err;
  EXPECT_EQ(err.find("mjcf-missing-asset"), std::string::npos) << err;  // not said again when emitted
  // The collision mesh found beside the robot (a checkout under another name than its package): it loads,
  // the visual still warned and left out.
  openplx::testing::write_tetrahedron(dir / "robot" / "meshes" / "hull.stl");
  EXPECT_EQ(cli({urdf.string(), "-o", (dir / "pk.xml").string(), "--check"}, &err), 0) << err;
  EXPECT_NE(err.find(urdf.string() + ":5:23: warning: mesh package://robot_pkg/meshes/look.stl"),
            std::string::npos)
      << err;
  rt::Simulation sim = rt::Simulation::load(urdf.string());
  EXPECT_EQ(sim.model()->nmesh, 1);
  EXPECT_EQ(sim.model()->ngeom, 1);
  // Imported from OpenPLX, a Urdf.PackagePath can still name the package: nothing is said at the import.
  openplx::testing::write_tetrahedron(dir / "elsewhere" / "meshes" / "look.stl");
  std::ofstream(dir / "scene.openplx") << "import @\"robot/urdf/pk.urdf\"\nScene is pk:\n"
                                          "    pkg is Urdf.PackagePath:\n        name: \"robot_pkg\"\n"
                                          "        path: @\"elsewhere\"\n";
  openplx::testing::write_tetrahedron(dir / "elsewhere" / "meshes" / "hull.stl");
  EXPECT_EQ(cli({(dir / "scene.openplx").string(), "-o", (dir / "scene.xml").string(), "--check"}, &err), 0)
      << err;
  EXPECT_EQ(err.find("not found"), std::string::npos) << err;
}

// Findings about a URDF's parts are placed at the URDF element they concern, as the import's own are. MuJoCo
// refuses a moving body lighter than mjMINVAL (1e-15 kg): the emitter applies its rule, and the error lands
// on the <link> (line 6), not on the generated document.
TEST(UrdfInputEdges, CheckFindingsAreAtTheUrdfElement) {
  const openplx::testing::ScratchDir dir;
  const fs::path urdf = dir / "tiny.urdf";
  std::ofstream(urdf)
      << "<?xml version=\"1.0\"?>\n"
         "<robot name=\"tiny\">\n"
         "  <link name=\"base\"><inertial><mass value=\"1\"/><inertia ixx=\"1\" iyy=\"1\" "
         "izz=\"1\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial></link>\n"
         "  <joint name=\"j\" type=\"continuous\"><parent link=\"base\"/><child link=\"arm\"/>"
         "<axis xyz=\"0 0 1\"/></joint>\n"
         "\n"
         "  <link name=\"arm\"><inertial><mass value=\"1e-20\"/><inertia ixx=\"1e-20\" "
         "iyy=\"1e-20\" izz=\"1e-20\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial></link>\n"
         "</robot>\n";
  std::string err;
  EXPECT_EQ(cli({urdf.string(), "-o", (dir / "tiny.xml").string(), "--check"}, &err),
            openplx::cli::kExitInputError);
  EXPECT_NE(
      err.find(urdf.string() + ":6:3: error: `arm` moves but its mass (1e-20 kg with the bodies fixed to "
                               "it) is below MuJoCo's smallest, 1e-15 kg"),
      std::string::npos)
      << err;
  EXPECT_EQ(err.find(".urdf.openplx:"), std::string::npos) << err;
}

}  // namespace
