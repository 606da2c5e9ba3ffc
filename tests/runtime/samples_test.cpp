// Every sample loads through the runtime and behaves as its comment says.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "openplx/runtime/simulation.h"

namespace {

namespace rt = openplx::runtime;

std::string sample(const std::string& name) {
  return std::string(OPENPLX_SAMPLES_DIR) + "/" + name;
}

// A point given in a body's frame, in world coordinates.
Eigen::Vector3d world_point(rt::Simulation& sim, const char* body, const Eigen::Vector3d& local) {
  const int id = mj_name2id(sim.model(), mjOBJ_BODY, body);
  EXPECT_GE(id, 0) << body;
  const mjtNum* q = sim.data()->xquat + 4 * id;
  return Eigen::Map<const Eigen::Vector3d>(sim.data()->xpos + 3 * id) +
         Eigen::Quaterniond(q[0], q[1], q[2], q[3]) * local;
}

// The four-bar swings under gravity while its loop-closing hinge (an equality) stays closed: MuJoCo's soft
// equality with default solref lets it open by millimetres (mapping guide: 0.4-2 mm on a driven four-bar).
TEST(Samples, FourBarSwingsAndStaysClosed) {
  rt::Simulation sim = rt::Simulation::load(sample("four_bar.openplx"));
  rt::Output crank = sim.output("crank_pivot.angle_output");
  const double start = crank.real();
  double swing = 0, gap = 0;
  while (sim.time() < 5.0) {
    sim.step();
    swing = std::max(swing, std::abs(crank.real() - start));
    gap = std::max(
        gap, (world_point(sim, "coupler", {0.5, 0, 0}) - world_point(sim, "rocker", {0.25, 0, 0})).norm());
  }
  EXPECT_GT(swing, 0.5);
  EXPECT_LT(gap, 5e-3);
}

// A PD controller written against the arm's signals holds both joints at their targets against gravity.
TEST(Samples, TwoJointArmFollowsAPdController) {
  rt::Simulation sim = rt::Simulation::load(sample("two_joint_arm.openplx"));
  rt::Input shoulder_torque = sim.input("shoulder_torque");
  rt::Input elbow_torque = sim.input("elbow_torque");
  rt::Output shoulder = sim.output("shoulder_angle"), elbow = sim.output("elbow_angle");
  rt::Output shoulder_speed = sim.output("shoulder_speed"), elbow_speed = sim.output("elbow_speed");
  rt::Output tip = sim.output("tip_position");
  while (sim.time() < 4.0) {
    shoulder_torque.set(60 * (0.5 - shoulder.real()) - 6 * shoulder_speed.real());
    elbow_torque.set(30 * (-0.4 - elbow.real()) - 3 * elbow_speed.real());
    sim.step();
  }
  // A PD controller without integral action settles where its spring balances gravity: within 0.2 rad here
  // (worst case 9.3 N m of gravity on the shoulder over 60 N m/rad), and it must be still.
  EXPECT_NEAR(shoulder.real(), 0.5, 0.2);
  EXPECT_NEAR(elbow.real(), -0.4, 0.2);
  EXPECT_NEAR(shoulder_speed.real(), 0, 1e-3);
  EXPECT_NEAR(elbow_speed.real(), 0, 1e-3);
  // The tip output is the lower segment's frame origin, which MuJoCo also reports.
  EXPECT_LT((tip.vec3() - world_point(sim, "lower", Eigen::Vector3d::Zero())).norm(), 1e-12);
}

// Left alone, the pole falls from 0.1 rad; the force input pushes the cart along the rail.
TEST(Samples, CartPolePoleFallsAndThePushMovesTheCart) {
  rt::Simulation sim = rt::Simulation::load(sample("cart_pole.openplx"));
  rt::Output angle = sim.output("pole_angle");
  EXPECT_NEAR(angle.real(), 0.1, 1e-12);
  sim.advance(1.0);
  EXPECT_GT(std::abs(angle.real()), 0.5);
  rt::Simulation pushed = rt::Simulation::load(sample("cart_pole.openplx"));
  pushed.input("push").set(10.0);
  pushed.advance(0.5);
  // 10 N on 1.1 kg for 0.5 s moves the cart about F t^2 / (2 m) = 1.1 m (less the pole's reaction).
  EXPECT_GT(pushed.output("cart_position").real(), 0.8);
  EXPECT_LT(pushed.output("cart_position").real(), 1.5);
}

TEST(Samples, PendulumSwingsBackThroughZero) {
  rt::Simulation sim = rt::Simulation::load(sample("pendulum.openplx"));
  rt::Output angle = sim.output("hinge.angle_output");
  EXPECT_NEAR(angle.real(), 0.3, 1e-12);
  double lowest = angle.real();
  while (sim.time() < 2.0) {
    sim.step();
    lowest = std::min(lowest, angle.real());
  }
  EXPECT_LT(lowest, -0.25);  // it swings to the other side (a little energy goes to Euler's damping)
}

}  // namespace
