// What real URDF files bring to the import's door (issue 31): file names in any case (`robot.URDF`), numbers
// written every way urdfdom reads them (and no way it does not), unexpanded xacro templates, `package://`
// meshes whose package is nowhere, and `--check` findings placed at the URDF element they concern.
#include <gtest/gtest.h>
#include <console_bridge/console.h>
#include <mujoco/mujoco.h>
#include <urdf_parser/urdf_parser.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>

#include "openplx/runtime/simulation.h"
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

// Sets an environment variable for one test's lifetime (each test runs in its own process under ctest).
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    ::setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() { old_ ? ::setenv(name_, old_->c_str(), 1) : ::unsetenv(name_); }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

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
    if (expected->upper > -1) EXPECT_EQ(m->jnt_range[2 * j + 1], expected->upper);
  };
  for (const std::string& upper : scalars) check("0 0 1", upper, 7);
  for (const std::string& xyz : lists) check(xyz, "1", 6);
}

}  // namespace
