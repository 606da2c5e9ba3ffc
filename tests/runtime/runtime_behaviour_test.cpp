// The corpus behaviours of ../shared/corpus/README.md, driven through the public runtime API as a user's
// controller would: inputs by OpenPLX name before a step, outputs by name after it.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "openplx/runtime/simulation.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace rt = openplx::runtime;
namespace fs = std::filesystem;

std::string corpus(const std::string& file) {
  return (fs::path(OPENPLX_CORPUS_DIR) / "agxunity" / file).string();
}

Eigen::Vector3d world_position(rt::Simulation& sim, const char* body) {
  const int id = mj_name2id(sim.model(), mjOBJ_BODY, body);
  EXPECT_GE(id, 0) << body;
  return Eigen::Map<const Eigen::Vector3d>(sim.data()->xpos + 3 * id);
}

// signal_test: the velocity motor follows motorSpeedInput within 0.2 s, to 1e-6 (the motor's kv is capped at
// half of Euler's stability limit, so the speed error halves every step: 100 steps leave 1e-30).
TEST(RuntimeBehaviour, SignalTestMotorTracksItsSpeedInput) {
  rt::Simulation sim = rt::Simulation::load(corpus("signal_test.openplx"));
  rt::Input speed = sim.input("motorSpeedInput");
  rt::Output velocity = sim.output("angularVelocity");
  rt::Output rpy = sim.output("boxRPY");
  speed.set(1.0);
  sim.step();
  EXPECT_GE(velocity.real(), 0.99);  // the motor is a constraint: one step
  sim.advance(0.2);
  EXPECT_NEAR(velocity.real(), 1.0, 1e-6);
  speed.set(-1.0);
  sim.advance(0.1);
  EXPECT_NEAR(velocity.real(), -1.0, 1e-6);
  // boxRPY is the box's world rotation as roll, pitch, yaw: R = Rz(yaw) Ry(pitch) Rx(roll).
  const Eigen::Vector3d a = rpy.vec3();
  const Eigen::Matrix3d r = (Eigen::AngleAxisd(a.z(), Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(a.y(), Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(a.x(), Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  const int box = mj_name2id(sim.model(), mjOBJ_BODY, "box");
  const mjtNum* q = sim.data()->xquat + 4 * box;
  const Eigen::Matrix3d expected = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).toRotationMatrix();
  EXPECT_LT((r - expected).norm(), 1e-12);
  EXPECT_GT(std::abs(a.z()), 1e-3);  // it turned about z, so this compares something
}

// torque_range: the range input bounds the motor's torque from the next step on, and the range output reads
// it.
TEST(RuntimeBehaviour, TorqueRangeBoundsTheMotor) {
  rt::Simulation sim = rt::Simulation::load(corpus("torque_range.openplx"));
  rt::Output torque = sim.output("pendulum.motor.torque_output");
  rt::Output range_out = sim.output("pendulum.motor.torque_range_output");
  rt::Input range = sim.input("pendulum.motor.torque_range_input");
  sim.step();
  EXPECT_GT(std::abs(torque.real()), 2.0);
  range.set(Eigen::Vector2d(-1, 1));
  sim.step();
  EXPECT_LE(std::abs(torque.real()), 1.0);
  EXPECT_EQ(range_out.vec2(), Eigen::Vector2d(-1, 1));
  range.set(Eigen::Vector2d(2, 3));
  sim.step();
  EXPECT_EQ(range_out.vec2(), Eigen::Vector2d(2, 3));
  EXPECT_GE(torque.real(), 2.0);
  EXPECT_LE(torque.real(), 3.0);
}

// simpler_inverted_pendulum: a 10000 N push along +x at the rod-local point (0, 0, 1) for one step, the
// corpus controller (motor speed = 5 (0 - a) - 0.2 w) keeps the hinge at 0 within 0.1 degree over 2 s.
TEST(RuntimeBehaviour, InvertedPendulumControllerRecoversFromAPush) {
  rt::Simulation sim = rt::Simulation::load(corpus("simpler_inverted_pendulum.openplx"));
  rt::Input motor = sim.input("PendulumScene.motor_input");  // the root model's name may lead
  rt::Output angle = sim.output("hinge_angle_output");
  rt::Output rate = sim.output("hinge_angular_velocity_output");
  rt::Output torque = sim.output("rod_motor.torque_output");
  const int rod = mj_name2id(sim.model(), mjOBJ_BODY, "rod");
  mjData* d = sim.data();
  double largest = 0, push_torque = 0, held = 0;
  for (int k = 0; sim.time() < 2.0 - 1e-9; ++k) {
    motor.set(5.0 * (0.0 - angle.real()) - 0.2 * rate.real());
    for (int i = 0; i < 6; ++i) d->xfrc_applied[6 * rod + i] = 0;
    if (k == 0) {
      // Force at the COM plus the torque of moving it to the point (world axes).
      const mjtNum* r = d->xmat + 9 * rod;
      const Eigen::Vector3d point =
          Eigen::Map<const Eigen::Vector3d>(d->xpos + 3 * rod) +
          Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(r) * Eigen::Vector3d(0, 0, 1);
      const Eigen::Vector3d force(10000, 0, 0);
      const Eigen::Vector3d torque =
          (point - Eigen::Map<const Eigen::Vector3d>(d->xipos + 3 * rod)).cross(force);
      for (int i = 0; i < 3; ++i) {
        d->xfrc_applied[6 * rod + i] = force[i];
        d->xfrc_applied[6 * rod + 3 + i] = torque[i];
      }
      // The push's torque about the hinge axis (the hinge is at the world origin).
      const int joint = mj_name2id(sim.model(), mjOBJ_JOINT, "hinge");
      const Eigen::Vector3d axis = Eigen::Map<const Eigen::Vector3d>(d->xaxis + 3 * joint);
      push_torque =
          (point - Eigen::Map<const Eigen::Vector3d>(d->xanchor + 3 * joint)).cross(force).dot(axis);
    }
    sim.step();
    if (k == 0) held = torque.real();
    largest = std::max(largest, std::abs(angle.real()));
  }
  // The motor has no effort limit, so, as in AGX, it is a rigid velocity constraint: it takes the push's
  // whole torque in that step and the rod never leaves the tolerance.
  EXPECT_GT(std::abs(push_torque), 1000);
  EXPECT_NEAR(held, -push_torque, 0.01 * std::abs(push_torque));
  EXPECT_LT(largest, 0.1 * M_PI / 180);
  EXPECT_NEAR(angle.real(), 0.0, 0.1 * M_PI / 180);
}

// LinearSpringTest and LinearRangeTest: the falling rod rests on its spring / range end after 2 s.
TEST(RuntimeBehaviour, FallingRodRestsOnSpringAndOnRange) {
  for (const auto& [file, z] : {std::pair{"LinearRangeTest.openplx", -1.0}}) {  // the spring's: mjcf_test
    SCOPED_TRACE(file);
    rt::Simulation sim = rt::Simulation::load(corpus(file));
    rt::Output position = sim.output("falling_rod.rod1.position_output");
    rt::Output velocity = sim.output("falling_rod.rod1.linear_velocity_world_output");
    sim.advance(2.0);
    EXPECT_NEAR(sim.time(), 2.0, 1e-9);
    EXPECT_NEAR(position.vec3().z(), z, 1e-3);
    EXPECT_NEAR(velocity.vec3().z(), 0.0, 1e-3);
    EXPECT_EQ(position.vec3(), world_position(sim, "falling_rod.rod1"));  // current after the step
  }
}

// drive_train_velocity_input: a 1-D velocity motor drives a shaft tied to the hinge by a rigid joint
// equality. As in AGX, the hinge turns at 1 rad/s after one step (measured 0.99905: the motor constraint
// is exact, the coupling relaxes in about two steps), and at -1 rad/s 0.1 s after the target flips, under
// the 10 kg rod's gravity torque (measured error 6e-6 rad/s).
TEST(RuntimeBehaviour, DriveTrainMotorTurnsTheHinge) {
  rt::Simulation sim = rt::Simulation::load(corpus("drive_train_velocity_input.openplx"));
  rt::Output speed = sim.output("pendulum.hinge.angular_velocity_output");
  sim.step();
  EXPECT_GE(speed.real(), 0.99);  // target_speed defaults to 1 for Physics1D motors
  sim.advance(0.1);
  EXPECT_NEAR(speed.real(), 1.0, 1e-4);
  sim.input("velocity_motor_input").set(-1.0);
  sim.advance(0.1);
  EXPECT_NEAR(speed.real(), -1.0, 1e-4);
}

// differential_test: the motor turns the drive shaft, the differential splits it to two axles, one through a
// -1 gear: after 0.5 s both pendulums turn, in opposite directions, at equal speeds (0.001, the corpus's).
TEST(RuntimeBehaviour, DifferentialTurnsBothRodsOppositeWays) {
  rt::Simulation sim = rt::Simulation::load(corpus("differential_test.openplx"));
  rt::Output w1 = sim.output("pendulum1.hinge.angular_velocity_output");
  rt::Output w2 = sim.output("pendulum2.hinge.angular_velocity_output");
  sim.advance(0.5);
  EXPECT_GE(std::abs(w1.real()), 0.1);
  EXPECT_GE(std::abs(w2.real()), 0.1);
  EXPECT_NEAR(w1.real(), -w2.real(), 1e-3);
}

}  // namespace

namespace {

// A thrown ball: the runtime starts from the emitter's "initial" keyframe, so the OpenPLX initial velocity is
// the state at time 0, and after 0.5 s the ball is 2 m along x and g t² / 2 lower.
TEST(RuntimeBehaviour, FreeBodyStartsWithItsInitialVelocity) {
  const openplx::testing::ScratchDir scratch;
  const fs::path file = scratch / "thrown_ball.openplx";
  std::ofstream(file) << "Scene is Physics3D.System:\n"
                         "    ball is Physics3D.Bodies.RigidBody:\n"
                         "        inertia.mass: 1\n"
                         "        kinematics.initial_local_linear_velocity: {4, 0, 0}\n"
                         "        geometry is Physics3D.Geometries.Sphere:\n"
                         "            radius: 0.1\n";
  rt::Simulation sim = rt::Simulation::load(file.string());
  EXPECT_EQ(sim.data()->qvel[0], 4.0);
  sim.advance(0.5);
  const Eigen::Vector3d p = world_position(sim, "ball");
  EXPECT_NEAR(p.x(), 2.0, 1e-9);
  // Semi-implicit Euler drops g h t / 2 below the exact parabola: 9.81 · 0.002 · 0.5 / 2 ≈ 5 mm.
  EXPECT_NEAR(p.z(), -0.5 * 9.81 * 0.25, 0.006);
}

}  // namespace
