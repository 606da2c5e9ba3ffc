// Test support: the OpenPLX text of an N-link planar arm, the owned-rows prototype's benchmark
// (/work/shared/design/owned-rows.md): N boxes of 1 kg, 0.3 m long (0.04 m square section), chained end to
// end by hinges about the world y axis (horizontal, so gravity loads every hinge), starting straight out
// along +x from a world pivot at the origin. Every hinge has a RotationalVelocityMotor limited to +-effort.
//
// Names, for k = 0 .. N-1 (the OpenPLX paths, which are also the MuJoCo joint names):
//   link{k}   the bodies            hinge{k}  the hinges (MuJoCo hinge joints)   motor{k}  the motors
//   speed{k}  Physics.Signals.AngularVelocity1DInput on motor{k} (its target, rad/s)
//   angle{k}  Physics.Signals.AngleOutput on hinge{k}   rate{k}  Physics.Signals.AngularVelocity1DOutput
//   motor{k}.torque_output  the torque the motor carries (the bundle's own output)
// A positive hinge angle turns the next link from +x toward -z: gravity pulls every hinge toward +angle.
#pragma once

#include <sstream>
#include <string>

namespace openplx::testing {

struct ArmChain {
  int links = 7;
  double effort = 200;  // N m: each motor's min_effort -effort, max_effort +effort
  double target = 0;    // rad/s: every motor's target_speed
  // A RotationalRange [range_start, range_end] on every hinge when range_start < range_end.
  double range_start = 0, range_end = 0;
};

constexpr double kArmLinkMass = 1.0, kArmLinkLength = 0.3, kArmLinkWidth = 0.04;

inline std::string arm_number(double x) {
  std::ostringstream out;
  out.precision(17);
  out << x;
  return out.str();
}

inline std::string arm_chain(const ArmChain& arm) {
  const std::string half = arm_number(kArmLinkLength / 2);
  std::string text =
      "Link is Physics3D.Bodies.RigidBody:\n"
      "    inertia.mass: " +
      arm_number(kArmLinkMass) +
      "\n"
      "    geometry is Physics3D.Geometries.Box:\n"
      "        size: {" +
      arm_number(kArmLinkLength) + ", " + arm_number(kArmLinkWidth) + ", " + arm_number(kArmLinkWidth) +
      "}\n"
      "    root is Physics3D.Interactions.MateConnector:\n"
      "        position.x: -" +
      half +
      "\n"
      "        main_axis: Math.Vec3.Y_AXIS()\n"
      "        normal: Math.Vec3.X_AXIS()\n"
      "    tip is Physics3D.Interactions.MateConnector:\n"
      "        position.x: " +
      half +
      "\n"
      "        main_axis: Math.Vec3.Y_AXIS()\n"
      "        normal: Math.Vec3.X_AXIS()\n"
      "Arm is Physics3D.System:\n"
      "    base is Physics3D.Interactions.MateConnector:\n"
      "        main_axis: Math.Vec3.Y_AXIS()\n"
      "        normal: Math.Vec3.X_AXIS()\n";
  for (int k = 0; k < arm.links; ++k) {
    const std::string n = std::to_string(k);
    const std::string parent = k == 0 ? "base" : "link" + std::to_string(k - 1) + ".tip";
    text += "    link" + n + " is Link\n";
    text += "    hinge" + n + " is Physics3D.Interactions.Hinge:\n        connectors: [" + parent + ", link" +
            n + ".root]\n";
    text += "    motor" + n +
            " is Physics3D.Interactions.RotationalVelocityMotor:\n        connectors: hinge" + n +
            ".connectors\n        target_speed: " + arm_number(arm.target) +
            "\n        min_effort: " + arm_number(-arm.effort) +
            "\n        max_effort: " + arm_number(arm.effort) + "\n";
    if (arm.range_start < arm.range_end) {
      text += "    range" + n + " is Physics3D.Interactions.RotationalRange:\n        connectors: hinge" + n +
              ".connectors\n        start: " + arm_number(arm.range_start) +
              "\n        end: " + arm_number(arm.range_end) + "\n";
    }
    text += "    speed" + n + " is Physics.Signals.AngularVelocity1DInput:\n        source: motor" + n + "\n";
    text += "    angle" + n + " is Physics.Signals.AngleOutput:\n        source: hinge" + n + "\n";
    text += "    rate" + n + " is Physics.Signals.AngularVelocity1DOutput:\n        source: hinge" + n + "\n";
  }
  return text;
}

}  // namespace openplx::testing
