// Rigid 1-D couplings are exact (docs/mapping.md "Drivetrains", "Couplings"): a shaft held 1:1 to a hinge or
// prismatic joint by a HingeActuator/PrismaticActuator is folded into that joint, so the joint follows the
// velocity motor on the shaft within the step, under any load the motor's effort range holds, at dt 0.002 and
// 0.02; the shaft's signals read the joint. Gears keep a rigid equality (their ratio changes at run time):
// within 1e-6 0.1 s after a target flip.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>
#include <utility>

#include "openplx/runtime/simulation.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace rt = openplx::runtime;

constexpr double kEffortLimit = 1e5;  // N m (N): the velocity motor's range, symmetric
constexpr double kShaftInertia = 1.0;

// A 10 kg, 1 m rod on a hinge about y at its lower end (drive_train_velocity_input), or a 10 kg block on a
// prismatic joint along x, driven through a shaft: a velocity motor and a load torque motor on the shaft, a
// HingeActuator or PrismaticActuator tying the shaft to the joint; `gear_ratio` (0: none) puts a gear and a
// second shaft between them.
std::string drive(bool prismatic, double gear_ratio) {
  const std::string mate = prismatic ? "Prismatic" : "Hinge";
  std::string text =
      "Rod is Physics3D.Bodies.RigidBody:\n"
      "    inertia.mass: 10\n"
      "    geometry is Physics3D.Geometries.Box:\n"
      "        size: Math.Vec3.from_xyz(0.1, 0.1, 1)\n"
      "    mate_connector is Physics3D.Interactions.MateConnector:\n"
      "        position.z: -0.5\n"
      "        main_axis: Math.Vec3." +
      std::string(prismatic ? "X" : "Y") +
      "_AXIS()\n"
      "        normal: Math.Vec3.Z_AXIS()\n"
      "Scene is Physics3D.System:\n"
      "    world_connector is Physics3D.Interactions.MateConnector:\n"
      "        main_axis: Math.Vec3." +
      std::string(prismatic ? "X" : "Y") +
      "_AXIS()\n"
      "        normal: Math.Vec3." +
      std::string(prismatic ? "Z" : "X") +
      "_AXIS()\n"
      "        position.x: 1\n"
      "    rod is Rod\n"
      "    joint is Physics3D.Interactions." +
      mate +
      ":\n"
      "        connectors: [rod.mate_connector, world_connector]\n" +
      (prismatic ? "" : "        initial_angle: Math.PI * 0.3\n") +
      "    shaft is DriveTrain.Shaft:\n"
      "        inertia.inertia: " +
      std::to_string(kShaftInertia) +
      "\n"
      "    motor is Physics1D.Interactions.RotationalVelocityMotor:\n"
      "        connectors: [shaft.input]\n"
      "        target_speed: 1\n"
      "        max_effort: " +
      std::to_string(kEffortLimit) + "\n        min_effort: " + std::to_string(-kEffortLimit) +
      "\n"
      "    load is DriveTrain.TorqueMotor:\n"
      "        connectors: [shaft.input]\n";
  std::string driven = "shaft";
  if (gear_ratio != 0) {
    text +=
        "    output_shaft is DriveTrain.Shaft:\n"
        "        inertia.inertia: 0.1\n"
        "    gear is DriveTrain.Gear:\n"
        "        ratio: " +
        std::to_string(gear_ratio) + "\n        connectors: [shaft.output, output_shaft.input]\n";
    driven = "output_shaft";
  }
  return text + "    actuator is DriveTrain." + mate + "Actuator:\n        connector_1d: " + driven +
         ".output\n        mate_3d: joint\n";
}

rt::Simulation load(const openplx::testing::ScratchDir& dir, const std::string& text, double timestep) {
  const auto file = dir / "model.openplx";
  std::ofstream(file) << text;
  rt::LoadOptions options;
  options.timestep = timestep;
  return rt::Simulation::load(file.string(), options);
}

struct Case {
  bool prismatic;
  double timestep;
  double load_fraction;  // of what the motor's range leaves beyond accelerating the drive by 2 per step
};

TEST(RigidCoupling, ActuatorFollowsTheShaftMotorWithinTheStep) {
  for (const bool prismatic : {false, true}) {
    for (const double h : {0.002, 0.02}) {
      for (const double fraction : {0.0, 0.5, -0.5, 0.95, -0.95}) {
        SCOPED_TRACE(std::string(prismatic ? "prismatic" : "hinge") + " h=" + std::to_string(h) +
                     " load=" + std::to_string(fraction));
        const openplx::testing::ScratchDir dir;
        rt::Simulation sim = load(dir, drive(prismatic, 0), h);
        const mjModel* m = sim.model();
        EXPECT_EQ(m->nv, 1);  // the joint alone: no shaft, no motor reference, no equality
        EXPECT_EQ(m->neq, 0);
        // Inertia the motor drives: the rod about its end (3.34 kg m^2) or sliding (10 kg), and the shaft as
        // the joint's armature (MuJoCo's mass matrix holds both).
        const int dof = m->jnt_dofadr[mj_name2id(m, mjOBJ_JOINT, "joint")];
        const double driven = sim.data()->qM[m->dof_Madr[dof]];
        EXPECT_NEAR(driven, kShaftInertia + (prismatic ? 10.0 : 10 * (1 + 0.01) / 12 + 10 * 0.25), 1e-9);
        const double gravity = prismatic ? 0.0 : 10 * 9.81 * 0.5;
        const double headroom = kEffortLimit - driven * 2 / h - gravity;
        ASSERT_GT(headroom, 0);
        const double load = fraction * headroom;
        sim.input("load.torque_input").set(load);
        rt::Output speed = sim.output(prismatic ? "joint.velocity_output" : "joint.angular_velocity_output");
        rt::Output shaft_speed = sim.output("shaft.angular_velocity_output");
        sim.step();
        // The motor's row is exact (docs/mapping.md "Constraint rows the runtime owns"): the coupling adds
        // nothing.
        EXPECT_NEAR(speed.real(), 1.0, 1e-6);
        EXPECT_EQ(shaft_speed.real(), speed.real());
        sim.advance(0.05);
        sim.input("motor.target_angular_velocity_input").set(-1.0);
        sim.advance(0.1);
        EXPECT_NEAR(speed.real(), -1.0, 1e-6);
      }
    }
  }
}

// The shaft's angle output reads the joint less its initial angle (a shaft starts at 0); the motor's torque
// output carries the load.
TEST(RigidCoupling, ShaftSignalsReadTheJointItIsFoldedInto) {
  const openplx::testing::ScratchDir dir;
  rt::Simulation sim = load(dir, drive(false, 0), 0.002);
  rt::Output hinge_angle = sim.output("joint.angle_output");
  rt::Output shaft_angle = sim.output("shaft.angle_output");
  const double initial = hinge_angle.real();
  EXPECT_NEAR(initial, 3.14159265358979 * 0.3, 1e-12);
  EXPECT_EQ(shaft_angle.real(), 0.0);
  sim.input("load.torque_input").set(100.0);
  sim.advance(0.5);
  EXPECT_NEAR(shaft_angle.real(), hinge_angle.real() - initial, 1e-12);
  EXPECT_NEAR(shaft_angle.real(), 0.5, 2 * sim.timestep());  // 1 rad/s from the first step on
}

// A gear keeps a rigid equality (its ratio input re-anchors it at run time), deadbeat but for the impedance's
// leak: per step at most (1 - d) h A tau of speed, A = 1 / I_joint + 1 / (ratio^2 I_input) the row's inverse
// inertia and tau the rod's weight torque it carries (measured well inside: 3.6e-6 rad/s at ratio -1 and dt
// 0.02, 3e-4 of 10 rad/s at ratio 0.1). 0.1 s after a flip the joint is on the target over the gear within
// that, for ratios either way and both steps.
TEST(RigidCoupling, GearFollowsAFlipWithinATenthOfASecond) {
  for (const double ratio : {-1.0, 2.0, 10.0, 0.1}) {
    for (const double h : {0.002, 0.02}) {
      SCOPED_TRACE("ratio=" + std::to_string(ratio) + " h=" + std::to_string(h));
      const openplx::testing::ScratchDir dir;
      rt::Simulation sim = load(dir, drive(false, ratio), h);
      EXPECT_EQ(sim.model()->nv, 2);  // the joint (carrying the output shaft) and the input shaft
      rt::Output speed = sim.output("joint.angular_velocity_output");
      const double rod = 10 * (1 + 0.01) / 12 + 10 * 0.25, output_shaft = 0.1;
      const double inverse_inertia = 1 / (rod + output_shaft) + 1 / (ratio * ratio * kShaftInertia);
      const double tolerance = (1 - 0.9999) * h * inverse_inertia * 10 * 9.81 * 0.5;
      sim.advance(0.1);
      EXPECT_NEAR(speed.real(), 1.0 / ratio, tolerance);
      sim.input("motor.target_angular_velocity_input").set(-1.0);
      sim.advance(0.1);
      EXPECT_NEAR(speed.real(), -1.0 / ratio, tolerance);
    }
  }
}

// A gearbox keeps its equality too (gear inputs re-anchor it): 0.1 s after each shift the output turns at
// the input's 1 rad/s over the selected ratio within 1e-6, at both steps (the step right after a shift lags
// by the impedance's leak: 0.49997 for 0.5).
TEST(RigidCoupling, GearBoxSettlesOnEachGearWithinATenthOfASecond) {
  for (const double h : {0.002, 0.02}) {
    SCOPED_TRACE("h=" + std::to_string(h));
    const openplx::testing::ScratchDir dir;
    rt::Simulation sim = load(dir,
                              "Box is Physics3D.System:\n"
                              "    in is DriveTrain.Shaft\n"
                              "    out is DriveTrain.Shaft\n"
                              "    drive is Physics1D.Interactions.RotationalVelocityMotor:\n"
                              "        connectors: [in.input]\n"
                              "    box is DriveTrain.GearBox:\n"
                              "        connectors: [in.output, out.input]\n"
                              "        forward_gears: [4.0, 2.0]\n"
                              "        reverse_gears: [-5.0]\n"
                              "        initial_gear: 1\n",
                              h);
    rt::Output out = sim.output("out.angular_velocity_output");
    rt::Input gear = sim.input("box.gear_input");
    sim.advance(0.1);
    EXPECT_NEAR(out.real(), 0.25, 1e-6);
    for (const auto& [selected, ratio] : {std::pair(2, 2.0), std::pair(-1, -5.0), std::pair(1, 4.0)}) {
      gear.set(static_cast<double>(selected));
      sim.advance(0.1);
      EXPECT_NEAR(out.real(), 1 / ratio, 1e-6) << "gear " << selected;
    }
  }
}

// One shaft driving two hinges: the shaft folds into the first, the second follows the first by a rigid
// equality (within its leak, 3e-4 after the first step); 0.1 s on both turn at the motor's 1 rad/s.
TEST(RigidCoupling, SecondJointOnAShaftFollowsTheFirst) {
  const std::string rod =
      "Rod is Physics3D.Bodies.RigidBody:\n"
      "    inertia.mass: 10\n"
      "    geometry is Physics3D.Geometries.Box:\n"
      "        size: Math.Vec3.from_xyz(0.1, 0.1, 1)\n"
      "    end is Physics3D.Interactions.MateConnector:\n"
      "        main_axis: Math.Vec3.Y_AXIS()\n"
      "        normal: Math.Vec3.Z_AXIS()\n";
  std::string scene =
      "Scene is Physics3D.System:\n    shaft is DriveTrain.Shaft\n"
      "    motor is Physics1D.Interactions.RotationalVelocityMotor:\n"
      "        connectors: [shaft.input]\n";
  for (const std::string k : {"1", "2"}) {
    scene += "    pivot" + k + " is Physics3D.Interactions.MateConnector:\n" +
             "        main_axis: Math.Vec3.Y_AXIS()\n        normal: Math.Vec3.X_AXIS()\n" +
             "        position.y: " + (k == "1" ? "0.2" : "-0.2") + "\n    rod" + k + " is Rod\n    hinge" +
             k + " is Physics3D.Interactions.Hinge:\n        connectors: [rod" + k + ".end, pivot" + k +
             "]\n" + "    actuator" + k +
             " is DriveTrain.HingeActuator:\n        connector_1d: shaft.output\n" +
             "        mate_3d: hinge" + k + "\n";
  }
  for (const double h : {0.002, 0.02}) {
    SCOPED_TRACE("h=" + std::to_string(h));
    const openplx::testing::ScratchDir dir;
    rt::Simulation sim = load(dir, rod + scene, h);
    EXPECT_EQ(sim.model()->neq, 1);
    rt::Output first = sim.output("hinge1.angular_velocity_output");
    rt::Output second = sim.output("hinge2.angular_velocity_output");
    sim.step();
    EXPECT_NEAR(first.real(), 1.0, 1e-6);
    EXPECT_NEAR(second.real(), 1.0, 1e-6);
    sim.advance(0.1);
    EXPECT_NEAR(first.real(), 1.0, 1e-6);
    EXPECT_NEAR(second.real(), 1.0, 1e-6);
  }
}

}  // namespace
