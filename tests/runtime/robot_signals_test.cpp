// Composite robot signals (Robotics.Signals.RobotInput / RobotOutput): the two-joint arm sample driven
// through one RobotInput vector of its two torques and read through one RobotOutput of its angles, speeds and
// tip, exactly as the same arm driven and read signal by signal; wrong sizes are refused.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "openplx/runtime/simulation.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace rt = openplx::runtime;

std::string arm_with_robot_signals() {
  std::ifstream in(std::string(OPENPLX_SAMPLES_DIR) + "/two_joint_arm.openplx");
  std::stringstream text;
  text << in.rdbuf();
  return text.str() +
         "    torques is Robotics.Signals.RobotInput:\n"
         "        targets: [shoulder_torque, elbow_torque]\n"
         "    state is Robotics.Signals.RobotOutput:\n"
         "        joint_sources: [shoulder_angle, elbow_angle, shoulder_speed, elbow_speed]\n"
         "        object_sources: [tip_position]\n";
}

TEST(RobotSignals, OneInputVectorDrivesAndOneOutputVectorReadsTheArm) {
  const openplx::testing::ScratchDir dir;
  const auto file = dir / "arm.openplx";
  std::ofstream(file) << arm_with_robot_signals();
  rt::Simulation robot = rt::Simulation::load(file.string());
  rt::Simulation single = rt::Simulation::load(file.string());
  rt::Input torques = robot.input("torques");
  rt::Output state = robot.output("state");
  EXPECT_EQ(torques.info().value, rt::ValueType::Vector);
  EXPECT_EQ(torques.info().size, 2u);
  EXPECT_EQ(state.info().size, 4u + 3u);
  EXPECT_TRUE(robot.warnings().empty()) << robot.warnings().front();
  for (int k = 0; k < 200; ++k) {
    const double t = 0.002 * k;
    torques.set(Eigen::VectorXd(Eigen::Vector2d(3 * std::sin(5 * t), -2.0)));
    single.input("shoulder_torque").set(3 * std::sin(5 * t));
    single.input("elbow_torque").set(-2.0);
    robot.step();
    single.step();
  }
  const Eigen::VectorXd v = state.vector();
  EXPECT_EQ(v[0], single.output("shoulder_angle").real());
  EXPECT_EQ(v[1], single.output("elbow_angle").real());
  EXPECT_EQ(v[2], single.output("shoulder_speed").real());
  EXPECT_EQ(v[3], single.output("elbow_speed").real());
  EXPECT_EQ(v.tail<3>(), single.output("tip_position").vec3());
  EXPECT_NE(v[1], 0.0);  // it moved
  EXPECT_THROW(torques.set(Eigen::VectorXd(Eigen::Vector3d(1, 2, 3))), rt::SignalError);
  EXPECT_THROW(torques.set(1.0), rt::SignalError);
}

}  // namespace

namespace {

// Control's virtual signals on the arm: a BroadcastInput sends one torque to both joints, an
// AffineTransform1DInput doubles a torque, an AffineTransform1DOutput reads the shoulder in degrees, a
// GroupOutput both angles.
TEST(ControlSignals, BroadcastAffineAndGroupRouteToTheirSignals) {
  const openplx::testing::ScratchDir dir;
  const auto file = dir / "arm.openplx";
  std::ifstream in(std::string(OPENPLX_SAMPLES_DIR) + "/two_joint_arm.openplx");
  std::stringstream text;
  text << in.rdbuf();
  std::ofstream(file) << text.str() +
                             "    both is Control.Virtual.BroadcastInput:\n"
                             "        targets: [shoulder_torque, elbow_torque]\n"
                             "    doubled is Control.Virtual.AffineTransform1DInput:\n"
                             "        target: shoulder_torque\n"
                             "        scale: 2\n"
                             "        offset: 0.5\n"
                             "    shoulder_degrees is Control.Virtual.AffineTransform1DOutput:\n"
                             "        source: shoulder_angle\n"
                             "        scale: 57.29577951308232\n"
                             "    angles is Control.Virtual.GroupOutput:\n"
                             "        sources: [shoulder_angle, elbow_angle]\n";
  rt::Simulation sim = rt::Simulation::load(file.string());
  EXPECT_TRUE(sim.warnings().empty()) << sim.warnings().front();
  sim.input("both").set(1.5);
  EXPECT_EQ(sim.data()->ctrl[0], 1.5);
  EXPECT_EQ(sim.data()->ctrl[1], 1.5);
  sim.input("doubled").set(1.0);
  EXPECT_EQ(sim.data()->ctrl[0], 2.5);  // 2 * 1 + 0.5 to the shoulder only
  EXPECT_EQ(sim.data()->ctrl[1], 1.5);
  sim.advance(0.2);
  const double shoulder = sim.output("shoulder_angle").real();
  EXPECT_NE(shoulder, 0.0);
  EXPECT_DOUBLE_EQ(sim.output("shoulder_degrees").real(), 57.29577951308232 * shoulder);
  const Eigen::VectorXd angles = sim.output("angles").vector();
  ASSERT_EQ(angles.size(), 2);
  EXPECT_EQ(angles[0], shoulder);
  EXPECT_EQ(angles[1], sim.output("elbow_angle").real());
}

}  // namespace
