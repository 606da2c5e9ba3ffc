// URDF through urdfdom: robots load directly and through `import`, can be extended in OpenPLX and driven by
// the runtime, and bad URDFs are errors, never crashes.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "openplx/runtime/simulation.h"
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

TEST(UrdfImport, EveryFailUrdfIsRejectedWithExitOne) {
  size_t rejected = 0;
  for (const auto& entry : fs::directory_iterator(kUrdf / "urdfdom")) {
    if (entry.path().filename().string().rfind("fail_", 0) != 0) continue;
    SCOPED_TRACE(entry.path().string());
    std::string err;
    EXPECT_EQ(cli({entry.path().string()}, &err), openplx::cli::kExitInputError);
    EXPECT_NE(err.find("error: urdfdom rejected " + fs::absolute(entry.path()).lexically_normal().string()),
              std::string::npos)
        << err;
    ++rejected;
  }
  EXPECT_EQ(rejected, 8u);
}

TEST(UrdfImport, UnknownJointTypeIsAnError) {
  std::string err;
  EXPECT_EQ(cli({(kUrdf / "bullet3" / "hinge.urdf").string()}, &err), openplx::cli::kExitInputError);
  EXPECT_NE(err.find("error: "), std::string::npos) << err;
}

TEST(UrdfImport, UrdfConvertsDirectlyAndChecksInMuJoCo) {
  const fs::path out = fs::temp_directory_path() / "openplx_urdf_import_test" / "r2d2.xml";
  fs::create_directories(out.parent_path());
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
