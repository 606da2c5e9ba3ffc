// The tests' model that diverges on demand: a 1 g rod hanging on a hinge (started 0.3 rad off), so that a
// torque MuJoCo 2.2.2 accepts (1e8 N m) gives it an angular acceleration (about 3e11 rad/s^2) beyond the
// 1e10 it checks for: bad QACC on the step the torque acts.
#pragma once

namespace openplx::testing {

inline constexpr const char* kLightRodPendulum =
    "Rod is Physics3D.Bodies.RigidBody:\n"
    "    inertia.mass: 0.001\n"
    "    geometry is Physics3D.Geometries.Box:\n"
    "        size: {0.05, 0.05, 1.0}\n"
    "    top is Physics3D.Interactions.MateConnector:\n"
    "        position.z: 0.5\n"
    "        main_axis: Math.Vec3.Y_AXIS()\n"
    "        normal: Math.Vec3.Z_AXIS()\n"
    "Pendulum is Physics3D.System:\n"
    "    pivot is Physics3D.Interactions.MateConnector:\n"
    "        main_axis: Math.Vec3.Y_AXIS()\n"
    "        normal: Math.Vec3.Z_AXIS()\n"
    "    rod is Rod\n"
    "    hinge is Physics3D.Interactions.Hinge:\n"
    "        connectors: [rod.top, pivot]\n"
    "        initial_angle: 0.3\n";

// Appended to kLightRodPendulum: the torque motor (input `motor.torque_input`) that makes it diverge.
inline constexpr const char* kLightRodMotor =
    "    motor is Physics3D.Interactions.TorqueMotor:\n"
    "        connectors: [rod.top, pivot]\n";

}  // namespace openplx::testing
