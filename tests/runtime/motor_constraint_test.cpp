// Motors, springs, ranges and couplings behave like AGX's constraints (docs/mapping.md "Velocity motors",
// "Springs", "Couplings"): a velocity motor reaches its target in one step and holds it under a load
// within its effort range without creep, slips at exactly its limit beyond it; enable inputs switch motors,
// springs and ranges; a rigid loop holds; the initial keyframe alone starts the motors in plain MuJoCo.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "openplx/runtime/simulation.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace rt = openplx::runtime;

// A 1 kg, 1 m rod on a hinge about y, lying along +x: gravity pulls it with m g L / 2 = 4.905 N m about
// the hinge. Its inertia about the hinge is m L^2 / 3 (+ the thin cross-section's m w^2 / 12).
std::string rod_on_motor(const std::string& motor_lines) {
  return "Rod is Physics3D.Bodies.RigidBody:\n"
         "    inertia.mass: 1\n"
         "    geometry is Physics3D.Geometries.Box:\n"
         "        size: {1, 0.02, 0.02}\n"
         "    end is Physics3D.Interactions.MateConnector:\n"
         "        position.x: -0.5\n"
         "        main_axis: Math.Vec3.Y_AXIS()\n"
         "        normal: Math.Vec3.X_AXIS()\n"
         "Scene is Physics3D.System:\n"
         "    pivot is Physics3D.Interactions.MateConnector:\n"
         "        main_axis: Math.Vec3.Y_AXIS()\n"
         "        normal: Math.Vec3.X_AXIS()\n"
         "    rod is Rod\n"
         "    hinge is Physics3D.Interactions.Hinge:\n"
         "        connectors: [pivot, rod.end]\n"
         "    motor is Physics3D.Interactions.RotationalVelocityMotor:\n"
         "        connectors: [pivot, rod.end]\n" +
         motor_lines;
}

constexpr double kGravityTorque = 1.0 * 9.81 * 0.5;

rt::Simulation load(const openplx::testing::ScratchDir& dir, const std::string& text) {
  const auto file = dir / "model.openplx";
  std::ofstream(file) << text;
  return rt::Simulation::load(file.string());
}

TEST(MotorConstraint, ReachesItsTargetInOneStepUnderLoad) {
  const openplx::testing::ScratchDir dir;
  rt::Simulation sim = load(dir, rod_on_motor("        target_speed: 1\n"));
  rt::Output speed = sim.output("hinge.angular_velocity_output");
  sim.step();
  EXPECT_GE(std::abs(speed.real()), 0.99);
  sim.advance(0.5);
  EXPECT_NEAR(std::abs(speed.real()), 1.0, 1e-5);
}

// Holding 0 against gravity within its range: no creep. Noslip makes the friction row exact (without it, its
// impedance 0.9999 leaves h (1 - d) a0 = 3e-6 rad/s, a0 = tau / I = 4.9 / 0.333 = 14.7 rad/s^2); what is
// left is the reference joint's give, tau h / (1e9 I) = 2.9e-11 rad/s, 5.9e-11 rad in 2 s.
TEST(MotorConstraint, HoldsZeroUnderALoadWithoutCreep) {
  const openplx::testing::ScratchDir dir;
  rt::Simulation sim = load(dir, rod_on_motor("        max_effort: 10\n        min_effort: -10\n"));
  rt::Output angle = sim.output("hinge.angle_output");
  rt::Output speed = sim.output("hinge.angular_velocity_output");
  rt::Output torque = sim.output("motor.torque_output");
  sim.advance(2.0);
  EXPECT_LT(std::abs(angle.real()), 1e-10);
  EXPECT_LT(std::abs(speed.real()), 5e-11);
  EXPECT_NEAR(std::abs(torque.real()), kGravityTorque, 1e-3);  // it carries the rod
}

// Beyond its range it slips, pushing with exactly its limit: the rod starts falling at
// (tau_g - limit) / I.
TEST(MotorConstraint, SlipsAtExactlyItsEffortLimit) {
  const openplx::testing::ScratchDir dir;
  rt::Simulation sim = load(dir, rod_on_motor("        max_effort: 2\n        min_effort: -2\n"));
  rt::Output torque = sim.output("motor.torque_output");
  rt::Output speed = sim.output("hinge.angular_velocity_output");
  sim.step();
  EXPECT_NEAR(std::abs(torque.real()), 2.0, 1e-9);
  const double inertia = 1.0 * (1.0 / 3 + 0.02 * 0.02 / 12);
  EXPECT_NEAR(std::abs(speed.real()), (kGravityTorque - 2.0) / inertia * sim.timestep(), 1e-6);
}

// A disabled motor pushes with nothing; its enable input switches it on and the enabled output follows.
TEST(MotorConstraint, EnableInputSwitchesTheMotor) {
  const openplx::testing::ScratchDir dir;
  rt::Simulation sim = load(dir, rod_on_motor("        enabled: false\n"));
  rt::Output enabled = sim.output("motor.interaction_enabled_output");
  rt::Output speed = sim.output("hinge.angular_velocity_output");
  EXPECT_FALSE(enabled.boolean());
  sim.step();
  const double inertia = 1.0 * (1.0 / 3 + 0.02 * 0.02 / 12);
  EXPECT_NEAR(std::abs(speed.real()), kGravityTorque / inertia * sim.timestep(), 1e-6);  // free fall
  sim.input("motor.enable_interaction_input").set(true);
  sim.step();
  EXPECT_TRUE(enabled.boolean());
  EXPECT_LT(std::abs(speed.real()), 1e-5);  // held at its target 0 again
  sim.input("motor.enable_interaction_input").set(false);
  sim.step();
  EXPECT_GT(std::abs(speed.real()), 0.01);
}

// A spring's enable input: off, the rod falls freely; on, the spring pulls it toward its rest.
TEST(SpringConstraint, EnableInputSwitchesTheSpring) {
  const openplx::testing::ScratchDir dir;
  std::string text = rod_on_motor("        enabled: false\n");
  text +=
      "    spring is Physics3D.Interactions.TorsionSpring:\n"
      "        connectors: [pivot, rod.end]\n"
      "        flexibility.stiffness: 100\n"
      "        enabled: false\n";
  rt::Simulation sim = load(dir, text);
  rt::Output torque = sim.output("spring.torque_output");
  sim.advance(0.1);
  EXPECT_EQ(torque.real(), 0.0);
  sim.input("spring.enable_interaction_input").set(true);
  sim.step();
  rt::Output angle = sim.output("hinge.angle_output");
  rt::Output speed = sim.output("hinge.angular_velocity_output");
  // k (rest - q), less its damping t k qdot at AGX's default relaxation time t = 2/60 s
  EXPECT_NEAR(torque.real(), -100 * angle.real() - 100 * (2.0 / 60) * speed.real(), 1.0);
  EXPECT_GT(std::abs(torque.real()), 1.0);
}

// A range's enable input: off, the rod falls past it; on, the limit holds it.
TEST(RangeConstraint, EnableInputSwitchesTheRange) {
  const openplx::testing::ScratchDir dir;
  std::string text = rod_on_motor("        enabled: false\n");
  text +=
      "    range is Physics3D.Interactions.RotationalRange:\n"
      "        connectors: [pivot, rod.end]\n"
      "        start: -0.1\n"
      "        end: 0.1\n"
      "        enabled: false\n";
  rt::Simulation sim = load(dir, text);
  rt::Output angle = sim.output("hinge.angle_output");
  sim.advance(0.5);
  EXPECT_GT(std::abs(angle.real()), 0.2);  // fell through the disabled range
  sim.input("range.enable_interaction_input").set(true);
  EXPECT_TRUE(sim.output("range.interaction_enabled_output").boolean());
}

// A parallelogram four-bar closed by a rigid hinge (two connect equalities) falls for 2 s: crank and
// rocker stay parallel within 1 mrad (measured: 3e-9 rad with the stiff equalities, 9e-5 with MuJoCo's
// default softness).
TEST(CouplingConstraint, FourBarStaysClosed) {
  const openplx::testing::ScratchDir dir;
  const std::string link =
      "    inertia.mass: 1\n"
      "    geometry is Physics3D.Geometries.Box:\n"
      "        size: {0.05, 0.05, 0.5}\n"
      "    top is Physics3D.Interactions.MateConnector:\n"
      "        position.z: 0.25\n"
      "        main_axis: Math.Vec3.Y_AXIS()\n"
      "        normal: Math.Vec3.X_AXIS()\n"
      "    bottom is Physics3D.Interactions.MateConnector:\n"
      "        position.z: -0.25\n"
      "        main_axis: Math.Vec3.Y_AXIS()\n"
      "        normal: Math.Vec3.X_AXIS()\n";
  const std::string connector = "        main_axis: Math.Vec3.Y_AXIS()\n        normal: Math.Vec3.X_AXIS()\n";
  rt::Simulation sim = load(dir, "Link is Physics3D.Bodies.RigidBody:\n" + link +
                                     "Coupler is Physics3D.Bodies.RigidBody:\n"
                                     "    inertia.mass: 1\n"
                                     "    geometry is Physics3D.Geometries.Box:\n"
                                     "        size: {1, 0.05, 0.05}\n"
                                     "    left is Physics3D.Interactions.MateConnector:\n"
                                     "        position.x: -0.5\n" +
                                     connector +
                                     "    right is Physics3D.Interactions.MateConnector:\n"
                                     "        position.x: 0.5\n" +
                                     connector +
                                     "FourBar is Physics3D.System:\n"
                                     "    ground_left is Physics3D.Interactions.MateConnector:\n" +
                                     connector +
                                     "    ground_right is Physics3D.Interactions.MateConnector:\n"
                                     "        position.x: 1\n" +
                                     connector +
                                     "    crank is Link\n"
                                     "    rocker is Link\n"
                                     "    coupler is Coupler\n"
                                     "    crank_hinge is Physics3D.Interactions.Hinge:\n"
                                     "        initial_angle: 0.5\n"
                                     "        connectors: [ground_left, crank.top]\n"
                                     "    rocker_hinge is Physics3D.Interactions.Hinge:\n"
                                     "        initial_angle: 0.5\n"
                                     "        connectors: [ground_right, rocker.top]\n"
                                     "    left_hinge is Physics3D.Interactions.Hinge:\n"
                                     "        initial_angle: -0.5\n"
                                     "        connectors: [crank.bottom, coupler.left]\n"
                                     "    right_hinge is Physics3D.Interactions.Hinge:\n"
                                     "        connectors: [rocker.bottom, coupler.right]\n");
  rt::Output crank = sim.output("crank_hinge.angle_output");
  rt::Output rocker = sim.output("rocker_hinge.angle_output");
  double worst = 0, swing = 0;
  while (sim.time() < 2.0 - 1e-9) {
    sim.step();
    worst = std::max(worst, std::abs(crank.real() - rocker.real()));
    swing = std::max(swing, std::abs(crank.real() - 0.5));
  }
  EXPECT_GT(swing, 0.5);  // it swung through the bottom
  EXPECT_LT(worst, 1e-3);
}

// drive_train_velocity_input in plain MuJoCo, without the runtime: mj_resetDataKeyframe on the emitted
// "initial" key starts the motor's stand-in at its target (1 rad/s): a damper b = I / h pulling the hinge
// toward it, which halves the speed error each step and lags by the pendulum's weight over b at rest (AGX,
// and the runtime's row, give 1 rad/s after one step).
TEST(MotorConstraint, TheInitialKeyframeStartsMotorsInPlainMuJoCo) {
  const openplx::testing::ScratchDir dir;
  rt::Simulation sim =
      rt::Simulation::load(std::string(OPENPLX_CORPUS_DIR) + "/agxunity/drive_train_velocity_input.openplx");
  const auto xml = dir / "drive.xml";
  std::ofstream(xml) << sim.mjcf();
  char error[1000] = "";
  mjModel* m = mj_loadXML(xml.c_str(), nullptr, error, sizeof(error));
  ASSERT_NE(m, nullptr) << error;
  mjData* d = mj_makeData(m);
  mj_resetDataKeyframe(m, d, mj_name2id(m, mjOBJ_KEY, "initial"));
  mj_step(m, d);
  const int hinge = mj_name2id(m, mjOBJ_JOINT, "pendulum.hinge");
  const int shaft = mj_name2id(m, mjOBJ_JOINT, "pendulum.shaft");
  EXPECT_NEAR(d->qvel[m->jnt_dofadr[hinge]], 0.5, 0.01);
  if (shaft >= 0) {
    EXPECT_NEAR(d->qvel[m->jnt_dofadr[hinge]], d->qvel[m->jnt_dofadr[shaft]], 1e-3);
  }
  while (d->time < 0.5) mj_step(m, d);
  EXPECT_NEAR(d->qvel[m->jnt_dofadr[hinge]], 1.0, 5e-3);
  mj_deleteData(d);
  mj_deleteModel(m);
}

}  // namespace

namespace {

// drive_train_velocity_input with its text edited: each pair replaces `from` by `to`.
std::string edited_drive_train(const std::vector<std::pair<std::string, std::string>>& edits) {
  std::ifstream in(std::string(OPENPLX_CORPUS_DIR) + "/agxunity/drive_train_velocity_input.openplx");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const auto& [from, to] : edits) {
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
  }
  return text;
}

// Loads `text`, sets `input` to `value` and simulates 0.5 s.
template <typename V>
rt::Simulation half_second_after(const openplx::testing::ScratchDir& dir, const std::string& text,
                                 const char* input, V value) {
  rt::Simulation sim = load(dir, text);
  sim.input(input).set(value);
  sim.advance(0.5);
  return sim;
}

// A brake holding the shaft the 10 kg rod hangs from (gravity torque 30.2 N m at its initial angle): at
// 1000 N m it holds the hinge (|w| <= 1e-4 after 0.5 s) carrying the rod's torque; at fraction
// 0.01 (10 N m) it slips carrying exactly 10 N m; at 0 the rod swings freely.
TEST(DriveTrainFriction, BrakeHoldsWithinItsCapacityAndSlipsBeyond) {
  const std::string text = edited_drive_train(
      {{"    motor is Physics1D.Interactions.RotationalVelocityMotor:\n        connectors: [shaft.input]\n",
        "    brake is DriveTrain.ManualBrake:\n        torque_capacity: 1000\n"
        "        initial_engagement_fraction: 1\n        min_relative_slip_ratio: 0.01\n"
        "        connectors: [shaft.input]\n"},
       {"    velocity_motor_input is Physics.Signals.AngularVelocity1DInput:\n        source: pendulum.motor",
        "    brake_torque is Physics.Signals.Torque1DOutput:\n        source: pendulum.brake"}});
  for (const double fraction : {1.0, 0.01, 0.0}) {
    SCOPED_TRACE(fraction);
    const openplx::testing::ScratchDir dir;
    rt::Simulation sim = half_second_after(dir, text, "pendulum.brake.engagement_fraction_input", fraction);
    const double speed = sim.output("pendulum.hinge.angular_velocity_output").real();
    const double torque = sim.output("brake_torque").real();
    if (fraction == 1.0) {
      EXPECT_LT(std::abs(speed), 1e-4);
      EXPECT_GT(std::abs(torque), 10.0);  // it carries the rod (measured 30.2 N m), within its capacity
      EXPECT_LT(std::abs(torque), 1000.0);
    } else {
      EXPECT_GT(std::abs(speed), 1.0);
      EXPECT_NEAR(std::abs(torque), 1000 * fraction, 1e-9);
    }
    EXPECT_NEAR(sim.output("pendulum.brake.engagement_fraction_output").real(), fraction, 1e-12);
  }
}

// drive_train_brake: the motor's shaft drives the hinge's shaft through an automatic
// brake (1000 N m) in the power line; the motor's effort is limited to 200 N m. Disengaged, the brake passes
// the motor's 1.0 rad/s to the hinge; engaged (ramped in over 0.1 s) it holds the line at 0 against the
// motor within 0.5 s.
TEST(DriveTrainFriction, BrakeInThePowerLinePassesWhenDisengagedAndHoldsWhenEngaged) {
  const std::string text = edited_drive_train(
      {{"        connectors: [shaft.input]\n",
        "        connectors: [shaft.input]\n        min_effort: -200\n        max_effort: 200\n"},
       {"    hinge_actuator is DriveTrain.HingeActuator:\n        connector_1d: shaft.output",
        "    line_shaft is DriveTrain.Shaft:\n        inertia.inertia: 0.1\n"
        "    brake is DriveTrain.AutomaticBrake:\n        torque_capacity: 1000\n"
        "        initial_engagement_fraction: 1\n        min_relative_slip_ratio: 0.01\n"
        "        initially_engaged: false\n        connectors: [shaft.output, line_shaft.input]\n"
        "    hinge_actuator is DriveTrain.HingeActuator:\n        connector_1d: line_shaft.output"}});
  const openplx::testing::ScratchDir dir;
  rt::Simulation sim = load(dir, text);
  sim.input("velocity_motor_input").set(1.0);
  rt::Output speed = sim.output("pendulum.hinge.angular_velocity_output");
  sim.advance(0.5);
  EXPECT_NEAR(speed.real(), 1.0, 1e-4);
  EXPECT_FALSE(sim.output("pendulum.brake.engaged_output").boolean());
  sim.input("pendulum.brake.engage_input").set(true);
  sim.advance(0.5);
  EXPECT_NEAR(speed.real(), 0.0, 1e-4);
  EXPECT_TRUE(sim.output("pendulum.brake.engaged_output").boolean());
  // It carries the motor's full 200 N m and the rod's weight, within its capacity.
  const double torque = std::abs(sim.output("pendulum.brake.torque_output").real());
  EXPECT_GT(torque, 200.0 - 31.0);
  EXPECT_LT(torque, 1000.0);
}

// drive_train_velocity_input with an automatic clutch (100 N m, initially engaged) between the motor's shaft
// and a 0.1 kg m^2 output shaft that drives the hinge.
std::string with_automatic_clutch() {
  return edited_drive_train(
      {{"    hinge_actuator is DriveTrain.HingeActuator:\n        connector_1d: shaft.output",
        "    output_shaft is DriveTrain.Shaft:\n        inertia.inertia: 0.1\n"
        "    clutch is DriveTrain.AutomaticClutch:\n        torque_capacity: 100\n"
        "        initial_engagement_fraction: 1\n        min_relative_slip_ratio: 0.01\n"
        "        initially_engaged: true\n        connectors: [shaft.output, output_shaft.input]\n"
        "    hinge_actuator is DriveTrain.HingeActuator:\n        connector_1d: output_shaft.output"}});
}

// An automatic clutch between the motor's shaft and the hinge's: engaged, it carries the motor's torque to
// the hinge (1 rad/s, more than 1 N m through it); disengaged (ramped out over 0.1 s), it carries nothing
// and the rod swings free of the motor.
TEST(DriveTrainFriction, ClutchTransmitsWhenEngaged) {
  const std::string text = with_automatic_clutch();
  for (const bool engaged : {true, false}) {
    SCOPED_TRACE(engaged);
    const openplx::testing::ScratchDir dir;
    rt::Simulation sim = half_second_after(dir, text, "pendulum.clutch.engage_input", engaged);
    const double speed = sim.output("pendulum.hinge.angular_velocity_output").real();
    const double torque = sim.output("pendulum.clutch.torque_output").real();
    EXPECT_EQ(sim.output("pendulum.clutch.engaged_output").boolean(), engaged);
    if (engaged) {
      EXPECT_NEAR(speed, 1.0, 1e-4);
      EXPECT_GT(std::abs(torque), 1.0);
      EXPECT_LT(std::abs(sim.output("pendulum.clutch.slip_velocity_output").real()), 1e-4);
    } else {
      EXPECT_LT(std::abs(torque), 1.0);
      EXPECT_LT(speed, -1.0);  // the rod falls back, free of the motor
    }
  }
}

// A gear of ratio 2 (input speed over output speed) between the motor's shaft and the hinge's: the hinge
// turns at 0.5 rad/s and the gear's torque output carries the rod. Its ratio input changes the ratio from
// the next step on without moving the shafts (the equality is re-anchored): 0.25 rad/s, the angle
// continuous.
TEST(DriveTrainGear, RatioAndTorqueSignals) {
  const openplx::testing::ScratchDir dir;
  rt::Simulation sim = load(
      dir,
      edited_drive_train(
          {{"    hinge_actuator is DriveTrain.HingeActuator:\n        connector_1d: shaft.output",
            "    output_shaft is DriveTrain.Shaft:\n        inertia.inertia: 0.1\n"
            "    gear is DriveTrain.Gear:\n        ratio: 2\n"
            "        connectors: [shaft.output, output_shaft.input]\n"
            "    hinge_actuator is DriveTrain.HingeActuator:\n        connector_1d: output_shaft.output"}}));
  rt::Output speed = sim.output("pendulum.hinge.angular_velocity_output");
  rt::Output angle = sim.output("pendulum.hinge.angle_output");
  sim.advance(0.2);
  EXPECT_NEAR(speed.real(), 0.5, 1e-4);
  EXPECT_EQ(sim.output("pendulum.gear.ratio_output").real(), 2.0);
  const double torque = sim.output("pendulum.gear.torque_output").real();
  EXPECT_GT(std::abs(torque), 10.0);  // the rod's gravity torque, some 30 N m
  EXPECT_LT(std::abs(torque), 100.0);
  sim.input("pendulum.gear.ratio_input").set(4.0);
  const double before = angle.real();
  sim.step();
  EXPECT_NEAR(angle.real() - before, 0.25 * sim.timestep(), 1e-4);  // no jump
  sim.advance(0.2);
  EXPECT_NEAR(speed.real(), 0.25, 1e-4);
  EXPECT_EQ(sim.output("pendulum.gear.ratio_output").real(), 4.0);
}

// An automatic clutch's disengagement ramps over its duration input: 0.5 s, so halfway after 0.25 s.
TEST(DriveTrainFriction, AutomaticClutchRampsOverItsDuration) {
  const openplx::testing::ScratchDir dir;
  rt::Simulation sim = load(dir, with_automatic_clutch());
  rt::Output fraction = sim.output("pendulum.clutch.engagement_fraction_output");
  EXPECT_EQ(fraction.real(), 1.0);
  sim.input("pendulum.clutch.disengagement_duration_input").set(0.5);
  EXPECT_EQ(sim.output("pendulum.clutch.disengagement_duration_output").real(), 0.5);
  sim.input("pendulum.clutch.engage_input").set(false);
  sim.advance(0.25);
  EXPECT_NEAR(fraction.real(), 0.5, sim.timestep() / 0.5 + 1e-12);
  sim.advance(0.3);
  EXPECT_EQ(fraction.real(), 0.0);
}

// drive_train_torque_input: drive_train_velocity_input with a DriveTrain.TorqueMotor on
// the shaft. -1000 N m for 1 s through the rigid hinge actuator spins the hinge past -10 rad/s: about
// -1000 N m s / (1 kg m^2 shaft + 10 kg rod about its end, m L^2 / 3 = 3.3 kg m^2), less gravity's share.
TEST(DriveTrainMotor, TorqueMotorOnAShaftDrivesTheHinge) {
  const openplx::testing::ScratchDir dir;
  const std::string text = edited_drive_train(
      {{"motor is Physics1D.Interactions.RotationalVelocityMotor:", "motor is DriveTrain.TorqueMotor:"},
       {"velocity_motor_input is Physics.Signals.AngularVelocity1DInput:",
        "torque_input is Physics.Signals.Torque1DInput:"}});
  rt::Simulation sim = load(dir, text);
  sim.input("torque_input").set(-1000.0);
  sim.advance(1.0);
  EXPECT_NEAR(sim.output("pendulum.motor.torque_output").real(), -1000.0, 1e-9);
  const double speed = sim.output("pendulum.hinge.angular_velocity_output").real();
  EXPECT_LE(speed, -10.0);
  EXPECT_NEAR(speed, -1000.0 / (1.0 + 10.0 / 3), 0.1 * 1000.0 / (1.0 + 10.0 / 3));
}

}  // namespace
