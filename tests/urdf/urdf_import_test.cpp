// URDF through urdfdom: robots load directly and through `import`, can be extended in OpenPLX and driven by
// the runtime, and bad URDFs are errors, never crashes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "openplx/runtime/simulation.h"
#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace {

namespace fs = std::filesystem;
namespace rt = openplx::runtime;

const fs::path kUrdf = fs::path(OPENPLX_CORPUS_DIR) / "urdf";

int cli(const std::vector<std::string>& args, std::string* err = nullptr) {
  std::ostringstream out, errors;
  const int status = openplx::cli::run(args, out, errors);
  if (err) *err = errors.str();
  return status;
}

// Every fail_* URDF is an error at the URDF's own line and column: tinyxml2's position for malformed XML,
// the element urdfdom's message names otherwise (the second of a duplicate, the joint that closes a loop).
// Lines checked by reading each file.
TEST(UrdfImport, EveryFailUrdfIsRejectedAtItsOwnLine) {
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"fail_pr2_desc_bracket.urdf",
       ":9:7: error: <origin> rpy=\"0 0 1 }\" is not 3 numbers (`}`) [urdf-invalid]"},
      {"fail_pr2_desc_double.urdf",
       ":31:5: error: link 'fl_caster_rotation_link' is not unique. [urdf-invalid]"},
      {"fail_pr2_desc_double_joint.urdf",
       ":21:5: error: joint 'fl_caster_rotation_joint' is not unique. [urdf-invalid]"},
      {"fail_pr2_desc_loop.urdf",
       ":22:5: error: joint `fr_caster_rotation_joint` closes a loop (fl_caster_rotation_joint → "
       "fr_caster_rotation_joint → fl_caster_rotation_joint); a URDF must be a tree [urdf-invalid]"},
      {"fail_pr2_desc_no_joint2.urdf",
       ":10:5: error: malformed URDF: an element on this line is not well formed [urdf-invalid]"},
      {"fail_pr2_desc_parent_itself.urdf",
       ":4:5: error: joint `fl_caster_rotation_joint` has link `base_link` as parent and child "
       "[urdf-invalid]"},
      {"fail_pr2_desc_two_trees.urdf",
       ":4:5: error: Failed to build tree: parent link [base_link] of joint [fl_caster_rotation_joint] not "
       "found."},
      {"fail_three_links_one_joint.urdf",
       ":21:3: error: malformed URDF: an element opened here is not closed by a matching end tag "
       "[urdf-invalid]"},
  };
  size_t files = 0;
  for (const auto& entry : fs::directory_iterator(kUrdf / "urdfdom")) {
    files += entry.path().filename().string().rfind("fail_", 0) == 0;
  }
  EXPECT_EQ(files, expected.size());
  for (const auto& [file, diagnostic] : expected) {
    SCOPED_TRACE(file);
    const fs::path path = fs::absolute(kUrdf / "urdfdom" / file).lexically_normal();
    std::string err;
    EXPECT_EQ(cli({path.string()}, &err), openplx::cli::kExitInputError);
    EXPECT_EQ(err.rfind(path.string() + diagnostic, 0), 0u) << err;  // the first line of the output
  }
}

TEST(UrdfImport, UnknownJointTypeIsAnError) {
  std::string err;
  const fs::path path = fs::absolute(kUrdf / "bullet3" / "hinge.urdf").lexically_normal();
  EXPECT_EQ(cli({path.string()}, &err), openplx::cli::kExitInputError);
  EXPECT_EQ(
      err.rfind(
          path.string() +
              ":41:4: error: Joint [joint_baseLink_childA] has no known type [spherical] [urdf-invalid]",
          0),
      0u)
      << err;
}

// Meshes the URDF names but that are not there are located at their <mesh> elements (07-physics.urdf names
// PR2 gripper meshes through package:// and does not ship them): errors for collision meshes (they change the
// physics), warnings for visual ones, which are left out.
TEST(UrdfImport, MissingMeshesAreLocatedAtTheirMeshElements) {
  std::string err;
  const fs::path path =
      fs::absolute(kUrdf / "urdfdom" / "urdf_tutorial_2011" / "07-physics.urdf").lexically_normal();
  EXPECT_EQ(cli({path.string()}, &err), openplx::cli::kExitInputError);
  for (int line : {280, 304}) {
    EXPECT_NE(err.find(path.string() + ":" + std::to_string(line) + ":9: error: mesh "), std::string::npos)
        << line << "\n"
        << err;
  }
  for (int line : {275, 299}) {
    EXPECT_NE(err.find(path.string() + ":" + std::to_string(line) + ":9: warning: mesh "), std::string::npos)
        << line << "\n"
        << err;
  }
}

// Numbers as urdfdom and MuJoCo read them: a leading '+' (ROS-Industrial and OEM packages write
// `upper="+3"`, `xyz="0 +0.1 0"`) and exponents convert; a lone or doubled sign is still an error at its
// element.
TEST(UrdfImport, LeadingPlusSignsAreNumbers) {
  const openplx::testing::ScratchDir scratch;
  auto robot = [](const std::string& xyz, const std::string& upper) {
    return "<robot name=\"plus\">\n"
           "  <link name=\"base\"><inertial><mass value=\"1\"/>"
           "<inertia ixx=\"1\" iyy=\"1\" izz=\"1\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial></link>\n"
           "  <link name=\"arm\"><inertial><mass value=\"+1e0\"/>"
           "<inertia ixx=\"1\" iyy=\"1\" izz=\"1\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial></link>\n"
           "  <joint name=\"j\" type=\"revolute\"><parent link=\"base\"/><child link=\"arm\"/>\n"
           "    <origin xyz=\"" +
           xyz +
           "\"/><axis xyz=\"0 0 1\"/>\n"
           "    <limit lower=\"-1\" upper=\"" +
           upper +
           "\" effort=\"10\" velocity=\"1\"/></joint>\n"
           "</robot>\n";
  };
  const fs::path good = scratch / "good.urdf", out = scratch / "good.xml";
  std::ofstream(good) << robot("0 +0.1 0", "+3");
  std::string err;
  ASSERT_EQ(cli({good.string(), "-o", out.string(), "--check"}, &err), 0) << err;
  std::ifstream in(out);
  const std::string xml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(xml.find("range=\"-1 3\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("pos=\"0 0.1 0\""), std::string::npos) << xml;
  for (const std::string upper : {"+", "++3", "+-3", "3+"}) {
    const fs::path bad = scratch / "bad.urdf";
    std::ofstream(bad) << robot("0 0 0", upper);
    EXPECT_EQ(cli({bad.string(), "-o", (scratch / "bad.xml").string()}, &err), openplx::cli::kExitInputError)
        << upper;
    EXPECT_NE(err.find(bad.string() + ":6:"), std::string::npos) << upper << "\n" << err;
    EXPECT_NE(err.find("is not a number (`" + upper + "`)"), std::string::npos) << err;
  }
}

// bullet3's prismatic.urdf gives <limit> without the effort and velocity URDF requires. MuJoCo accepts it,
// and urdfdom alone would not: we read it with a warning there (and --strict makes that an error).
TEST(UrdfImport, LimitWithoutEffortIsReadWithAWarning) {
  const fs::path path = fs::absolute(kUrdf / "bullet3" / "prismatic.urdf").lexically_normal();
  const openplx::testing::ScratchDir scratch;
  const fs::path out = scratch / "prismatic.xml";
  std::string err;
  EXPECT_EQ(cli({path.string(), "-o", out.string(), "--check"}, &err), 0) << err;
  EXPECT_EQ(err.rfind(path.string() +
                          ":46:2: warning: the <limit> of joint `joint_baseLink_childA` has no effort and "
                          "velocity (URDF requires them); read as no limit [urdf-warning]",
                      0),
            0u)
      << err;
  EXPECT_EQ(cli({path.string(), "-o", out.string(), "--strict"}, &err), openplx::cli::kExitInputError);
}

TEST(UrdfImport, UrdfConvertsDirectlyAndChecksInMuJoCo) {
  const openplx::testing::ScratchDir scratch;
  const fs::path out = scratch / "r2d2.xml";
  std::string err;
  EXPECT_EQ(cli({(kUrdf / "bullet3" / "r2d2.urdf").string(), "-o", out.string(), "--check"}, &err), 0) << err;
  EXPECT_TRUE(fs::exists(out));
}

// samples/urdf_pantilt.openplx imports bullet3's pan-tilt head, makes the tilt link 8 kg and adds torque
// motors and angle outputs: the runtime drives it by those names.
TEST(UrdfImport, ExtendedUrdfRobotIsDrivenByTheRuntime) {
  rt::Simulation sim = rt::Simulation::load(std::string(OPENPLX_SAMPLES_DIR) + "/urdf_pantilt.openplx");
  const mjModel* m = sim.model();
  EXPECT_DOUBLE_EQ(m->body_mass[mj_name2id(m, mjOBJ_BODY, "tilt_link")], 8.0);  // the override
  rt::Input pan = sim.input("pan_torque");
  rt::Output pan_angle = sim.output("pan_angle"), tilt_angle = sim.output("tilt_angle");
  const int pan_joint = mj_name2id(m, mjOBJ_JOINT, "pan_joint");
  const int motor = mj_name2id(m, mjOBJ_ACTUATOR, "pan_motor");
  ASSERT_GE(motor, 0);
  EXPECT_EQ(m->actuator_trnid[2 * motor], pan_joint);
  pan.set(0.5);
  EXPECT_EQ(sim.data()->ctrl[motor], 0.5);
  sim.advance(0.5);
  EXPECT_EQ(pan_angle.real(), sim.data()->qpos[m->jnt_qposadr[pan_joint]]);
  EXPECT_GT(std::abs(tilt_angle.real()), 0.1);  // the 8 kg link, 5 m out, falls about the tilt axis
}

// widowx's second gripper finger mimics the first (multiplier 1): a joint equality keeps them together while
// a force drives the leader. MuJoCo's own URDF compiler drops <mimic> (and rejects widowx's massless links).
TEST(UrdfImport, MimicJointFollowsItsLeader) {
  rt::Simulation sim = rt::Simulation::load((kUrdf / "bullet3" / "widowx" / "widowx.urdf").string());
  const mjModel* m = sim.model();
  const int leader = mj_name2id(m, mjOBJ_JOINT, "gripper_prismatic_joint_1");
  const int follower = mj_name2id(m, mjOBJ_JOINT, "gripper_prismatic_joint_2");
  ASSERT_GE(leader, 0);
  ASSERT_GE(follower, 0);
  EXPECT_GE(mj_name2id(m, mjOBJ_EQUALITY, "gripper_prismatic_joint_2_mimic"), 0);
  mjData* d = sim.data();
  double moved = 0;
  for (int k = 0; k < 200; ++k) {
    d->qfrc_applied[m->jnt_dofadr[leader]] = 0.5;
    sim.step();
    const double q1 = d->qpos[m->jnt_qposadr[leader]], q2 = d->qpos[m->jnt_qposadr[follower]];
    moved = std::max(moved, std::abs(q1));
    // The equality is soft (MuJoCo's default solref): it holds the pair within a millimetre.
    EXPECT_NEAR(q2, q1, 1e-3) << "step " << k;
  }
  EXPECT_GT(moved, 1e-3);  // the leader did move
}

}  // namespace
