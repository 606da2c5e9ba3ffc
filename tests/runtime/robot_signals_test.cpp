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
