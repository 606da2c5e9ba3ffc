// A 2 kg box on a vertical slide, held to the world by a flexible Lock of 2000 N/m: under gravity it settles
// m g / k = 9.81 mm low. Shared by the soft-constraint tests of both MuJoCo versions.
#pragma once

namespace openplx::testing {

inline constexpr const char* kSoftLockScene =
    "Box is Physics3D.Bodies.RigidBody:\n"
    "    inertia.mass: 2\n"
    "    geometry is Physics3D.Geometries.Box:\n"
    "        size: {0.1, 0.1, 0.1}\n"
    "    c is Physics3D.Interactions.MateConnector:\n"
    "        main_axis: Math.Vec3.Z_AXIS()\n"
    "        normal: Math.Vec3.X_AXIS()\n"
    "Scene is Physics3D.System:\n"
    "    w is Physics3D.Interactions.MateConnector:\n"
    "        main_axis: Math.Vec3.Z_AXIS()\n"
    "        normal: Math.Vec3.X_AXIS()\n"
    "    box is Box\n"
    "    slide is Physics3D.Interactions.Prismatic:\n"
    "        connectors: [w, box.c]\n"
    "    lock is Physics3D.Interactions.Lock:\n"
    "        connectors: [w, box.c]\n"
    "        flexibility becomes Physics3D.Interactions.Flexibility.LinearElasticLockFlexibility:\n"
    "            default_stiffness: 2000\n";

}  // namespace openplx::testing
