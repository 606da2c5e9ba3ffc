// Friction-row drives and ranges are as hard as AGX's rows (docs/mapping.md "Velocity motors", "Clutches and
// brakes", "Physics3D: motors, springs and ranges"): a brake holds a saturated motor at any effort up to its
// capacity and slips carrying exactly its capacity beyond; a velocity motor holds its target under any load
// up to its effort limit; a range holds against any motor up to its effort limit, hinge and prismatic, at h =
// 0.002 and 0.02 s.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "openplx/runtime/simulation.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace rt = openplx::runtime;

constexpr double kImpedance = 0.9999;  // the rigid rows' (MuJoCo's largest)
const std::vector<double> kTimesteps{0.002, 0.02};

rt::Simulation load(const openplx::testing::ScratchDir& dir, const std::string& text, double h) {
  const auto file = dir / "model.openplx";
  std::ofstream(file) << text;
  rt::LoadOptions options;
  options.timestep = h;
  return rt::Simulation::load(file.string(), options);
}

std::string replaced(std::string text, const std::vector<std::pair<std::string, std::string>>& edits) {
  for (const auto& [from, to] : edits) {
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
  }
  return text;
}

// drive_train_velocity_input with its motor limited to +-effort and an engaged automatic brake of 1e6 N m
// in the power line between the motor's shaft and the hinge's.
std::string braked_drive_train(double effort) {
  std::ifstream in(std::string(OPENPLX_CORPUS_DIR) + "/agxunity/drive_train_velocity_input.openplx");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string e = std::to_string(effort);
  return replaced(
      text,
      {{"        connectors: [shaft.input]\n",
        "        connectors: [shaft.input]\n        min_effort: -" + e + "\n        max_effort: " + e + "\n"},
       {"    hinge_actuator is DriveTrain.HingeActuator:\n        connector_1d: shaft.output",
        "    line_shaft is DriveTrain.Shaft:\n        inertia.inertia: 0.1\n"
        "    brake is DriveTrain.AutomaticBrake:\n        torque_capacity: 1000000\n"
        "        initial_engagement_fraction: 1\n        min_relative_slip_ratio: 0.01\n"
        "        initially_engaged: true\n        connectors: [shaft.output, line_shaft.input]\n"
        "    hinge_actuator is DriveTrain.HingeActuator:\n        connector_1d: line_shaft.output"}});
}

// AGX's drive_train_brake check: the hinge at 0 within 1e-4 rad/s after 0.5 s against the motor pushing for
// 1 rad/s, whatever its effort up to the brake's capacity (measured 1e-14). Beyond, the brake slips carrying
// exactly its capacity and the motor reaches its target, short by its reference joint's give tau h / (1e9 I)
// (tau the 1e6 N m it pushes, I = 4.8 kg m^2 the line it drives: 4.2e-7 rad/s at h = 0.002).
TEST(HardRows, BrakeHoldsAnyMotorUpToItsCapacityAndSlipsBeyond) {
  for (const double h : kTimesteps) {
    for (const double effort : {1e3, 1e5, 9e5, 2e6}) {
      SCOPED_TRACE("h " + std::to_string(h) + ", motor effort " + std::to_string(effort));
      const openplx::testing::ScratchDir dir;
      rt::Simulation sim = load(dir, braked_drive_train(effort), h);
      sim.input("velocity_motor_input").set(1.0);
      sim.advance(0.5);
      const double speed = sim.output("pendulum.hinge.angular_velocity_output").real();
      const double torque = std::abs(sim.output("pendulum.brake.torque_output").real());
      if (effort < 1e6) {
        EXPECT_LT(std::abs(speed), 1e-4);
        EXPECT_LT(torque, 1e6);
      } else {
        constexpr double kLineInertia = 4.4;  // at least: shafts 1 + 0.1, the 10 kg rod about its end 3.3
        EXPECT_NEAR(speed, 1.0, 1e6 * h / (1e9 * kLineInertia));
        EXPECT_NEAR(torque, 1e6, 1e-6 * 1e6);
      }
    }
  }
}

// A rod of `mass` kg, 1 m, on a hinge about y lying along +x (gravity torque m g / 2), held at 0 by a
// velocity motor limited to +-10 N m.
std::string rod_on_motor(double mass) {
  return "Rod is Physics3D.Bodies.RigidBody:\n"
         "    inertia.mass: " +
         std::to_string(mass) +
         "\n"
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
         "        connectors: [pivot, rod.end]\n"
         "        max_effort: 10\n"
         "        min_effort: -10\n";
}

// Loads up to the effort limit: the rod's weight pulls with 2.5 to 9.8 N m. With noslip the friction row is
// exact; what is left is the reference joint's give: it outweighs the rod 1e9 times and its servo meets its
// target within a step, so the motor's reaction tau turns it at tau h / (1e9 I) (measured: exactly that).
TEST(HardRows, VelocityMotorHoldsItsTargetUnderAnyLoadUpToItsLimit) {
  for (const double h : kTimesteps) {
    for (const double mass : {0.5, 1.0, 1.5, 2.0}) {
      SCOPED_TRACE("h " + std::to_string(h) + ", rod " + std::to_string(mass) + " kg");
      const openplx::testing::ScratchDir dir;
      rt::Simulation sim = load(dir, rod_on_motor(mass), h);
      sim.advance(2.0);
      const double load = mass * 9.81 * 0.5, inertia = mass * (1.0 / 3 + 0.02 * 0.02 / 12);
      const double creep = load * h / (1e9 * inertia);
      EXPECT_LT(std::abs(sim.output("hinge.angular_velocity_output").real()), 1.5 * creep);
      EXPECT_LT(std::abs(sim.output("hinge.angle_output").real()), 1.5 * creep * 2.0);
      EXPECT_NEAR(std::abs(sim.output("motor.torque_output").real()), load, 1e-3 * load);
    }
  }
}

// A 5 kg, 1 m arm in the horizontal plane (no gravity torque) on a hinge about z, or a 5 kg slider, with a
// range [-0.5, 0.5] and a motor pushing toward its end: a velocity motor at 1 (rad or m)/s or a torque/force
// motor, with efforts up to 5,000.
std::string pushed_into_range(bool prismatic, const std::string& motor) {
  const std::string mate = prismatic ? "Prismatic" : "Hinge";
  const std::string kind = prismatic ? "Linear" : "Rotational";
  return "Arm is Physics3D.Bodies.RigidBody:\n"
         "    inertia.mass: 5\n"
         "    geometry is Physics3D.Geometries.Box:\n"
         "        size: {1, 0.05, 0.05}\n"
         "    end is Physics3D.Interactions.MateConnector:\n"
         "        position.x: -0.5\n"
         "        main_axis: " +
         std::string(prismatic ? "Math.Vec3.X_AXIS()" : "Math.Vec3.Z_AXIS()") +
         "\n"
         "        normal: " +
         std::string(prismatic ? "Math.Vec3.Y_AXIS()" : "Math.Vec3.X_AXIS()") +
         "\n"
         "Scene is Physics3D.System:\n"
         "    pivot is Physics3D.Interactions.MateConnector:\n"
         "        main_axis: " +
         std::string(prismatic ? "Math.Vec3.X_AXIS()" : "Math.Vec3.Z_AXIS()") +
         "\n"
         "        normal: " +
         std::string(prismatic ? "Math.Vec3.Y_AXIS()" : "Math.Vec3.X_AXIS()") +
         "\n"
         "    arm is Arm\n"
         "    joint is Physics3D.Interactions." +
         mate +
         ":\n"
         "        connectors: [pivot, arm.end]\n"
         "    range is Physics3D.Interactions." +
         kind +
         "Range:\n"
         "        connectors: [pivot, arm.end]\n"
         "        start: -0.5\n"
         "        end: 0.5\n"
         "    motor is Physics3D.Interactions." +
         motor + "        connectors: [pivot, arm.end]\n";
}

// The range holds: 2 s on, the joint rests at its end, exactly (the runtime owns the limit row: AGX's law,
// its softness's bias cancelled; docs/mapping.md "Constraint rows the runtime owns"). Under MuJoCo's own
// softness it rested (1 - d)/d a0 / k past it (4.8e-6 rad at 5,000 N m and h = 0.002, 4.8e-4 at 0.02). The
// row exists within 1e-3 of the end, so a joint arriving slower than 1e-3 / h never passes it; a faster one
// passes by up to p0 = v h + a0 h^2 and is taken back, sent out at most p0 / (4h), and the push brings it
// back within v_out^2 / (2 a0), after which it rests at the end for good.
TEST(HardRows, RangeHoldsAgainstAnyMotorUpToItsLimit) {
  for (const bool prismatic : {false, true}) {
    const double inertia = prismatic ? 5.0 : 5.0 * (1.0 / 3 + 0.05 * 0.05 / 12);
    const std::string speed = prismatic ? "joint.velocity_output" : "joint.angular_velocity_output";
    const std::string position = prismatic ? "joint.position_output" : "joint.angle_output";
    for (const double h : kTimesteps) {
      for (const double effort : {50.0, 500.0, 5000.0}) {
        const std::string e = std::to_string(effort);
        const std::string velocity_motor =
            std::string(prismatic ? "LinearVelocityMotor" : "RotationalVelocityMotor") +
            ":\n        target_speed: 1\n        min_effort: -" + e + "\n        max_effort: " + e + "\n";
        const std::string effort_motor = std::string(prismatic ? "ForceMotor" : "TorqueMotor") +
                                         ":\n        " +
                                         (prismatic ? "default_force: " : "default_torque: ") + e + "\n";
        for (const std::string& motor : {velocity_motor, effort_motor}) {
          SCOPED_TRACE((prismatic ? "prismatic, " : "hinge, ") + std::string("h ") + std::to_string(h) +
                       ", " + motor);
          const openplx::testing::ScratchDir dir;
          rt::Simulation sim = load(dir, pushed_into_range(prismatic, motor), h);
          rt::Output q = sim.output(position), v = sim.output(speed);
          const double a0 = effort / inertia;
          double arrival_speed = 0, lowest_after = 1.0, settled_low = 1.0, settled_high = 0.0;
          bool arrived = false;
          while (sim.time() < 2.0 - 1e-9) {
            sim.step();
            if (!arrived) arrival_speed = std::max(arrival_speed, std::abs(v.real()));
            arrived = arrived || q.real() >= 0.5;
            if (arrived) lowest_after = std::min(lowest_after, q.real());
            if (sim.time() > 1.5) {  // taken back from the entry by then: (3/4)^n per step
              settled_low = std::min(settled_low, q.real());
              settled_high = std::max(settled_high, q.real());
            }
          }
          EXPECT_TRUE(arrived);
          const double entry = arrival_speed * h + a0 * h * h, out = entry / (4 * h);
          EXPECT_GE(lowest_after, 0.5 - out * out / (2 * a0) - 1e-9);
          EXPECT_NEAR(q.real(), 0.5, 1e-9);
          EXPECT_GE(settled_low, 0.5 - 1e-9);  // at rest at the end: no bouncing
          EXPECT_LE(settled_high, 0.5 + 1e-9);
          EXPECT_LT(std::abs(v.real()), 1e-6);
        }
      }
    }
  }
}

// A DistanceRange is a tendon limit with the same softness: a 5 kg slider pushed along x by a force motor
// away from a world anchor 0.3 m behind it, the distance kept within [0.1, 0.5], so it stops at x = 0.2; the
// distance's inverse inertia is the slider's 1/m, so the give is the joint range's with a0 = force / m.
TEST(HardRows, DistanceRangeHoldsAgainstAnyPushUpToItsLimit) {
  for (const double h : kTimesteps) {
    for (const double force : {50.0, 500.0, 5000.0}) {
      SCOPED_TRACE("h " + std::to_string(h) + ", force " + std::to_string(force));
      const std::string axes = "        main_axis: Math.Vec3.X_AXIS()\n        normal: Math.Vec3.Y_AXIS()\n";
      const openplx::testing::ScratchDir dir;
      rt::Simulation sim = load(dir,
                                "Slider is Physics3D.Bodies.RigidBody:\n"
                                "    inertia.mass: 5\n"
                                "    geometry is Physics3D.Geometries.Box:\n"
                                "        size: {0.2, 0.2, 0.2}\n"
                                "    end is Physics3D.Interactions.MateConnector:\n" +
                                    axes +
                                    "Scene is Physics3D.System:\n"
                                    "    pivot is Physics3D.Interactions.MateConnector:\n" +
                                    axes +
                                    "    anchor is Physics3D.Interactions.MateConnector:\n"
                                    "        position.x: -0.3\n" +
                                    axes +
                                    "    slider is Slider\n"
                                    "    joint is Physics3D.Interactions.Prismatic:\n"
                                    "        connectors: [pivot, slider.end]\n"
                                    "    range is Physics3D.Interactions.DistanceRange:\n"
                                    "        connectors: [anchor, slider.end]\n"
                                    "        start: 0.1\n"
                                    "        end: 0.5\n"
                                    "    motor is Physics3D.Interactions.ForceMotor:\n"
                                    "        default_force: " +
                                    std::to_string(force) +
                                    "\n"
                                    "        connectors: [pivot, slider.end]\n",
                                h);
      sim.advance(2.0);
      const double give = (1 - kImpedance) / kImpedance * force / 5.0 * std::pow(kImpedance * 2 * h, 2);
      EXPECT_NEAR(sim.output("joint.position_output").real(), 0.2 + give, 0.1 * give + 1e-9);
      EXPECT_LT(std::abs(sim.output("joint.velocity_output").real()), 1e-6);
    }
  }
}

// A range switched on by its enable input is as hard as one enabled from the start: the arm pushed by
// 5,000 N m through a disabled range comes back to its end once the range is enabled.
TEST(HardRows, RangeEnabledByItsInputIsAsHard) {
  for (const double h : kTimesteps) {
    SCOPED_TRACE("h " + std::to_string(h));
    const openplx::testing::ScratchDir dir;
    std::string text = pushed_into_range(false, "TorqueMotor:\n        default_torque: 5000\n");
    text = replaced(text, {{"        end: 0.5\n", "        end: 0.5\n        enabled: false\n"}});
    rt::Simulation sim = load(dir, text, h);
    rt::Output q = sim.output("joint.angle_output");
    sim.advance(0.02);
    EXPECT_GT(q.real(), 0.5);  // through the disabled range
    sim.input("range.enable_interaction_input").set(true);
    sim.advance(2.0);
    const double inertia = 5.0 * (1.0 / 3 + 0.05 * 0.05 / 12), a0 = 5000 / inertia;
    const double give = (1 - kImpedance) / kImpedance * a0 * std::pow(kImpedance * 2 * h, 2);
    EXPECT_NEAR(q.real(), 0.5 + give, 0.1 * give + 1e-9);
  }
}

}  // namespace
