// Generators of large, realistic OpenPLX documents for benchmarks: the shapes real files have (bodies with
// geometry and connectors, systems of mates, comments, vectors and calls), repeated with unique names.
#pragma once

#include <string>

namespace openplx::bench {

// A document of at least `bytes` bytes, deterministic for a given size.
inline std::string generate_document(size_t bytes) {
  std::string out;
  out.reserve(bytes + 4096);
  out += "# generated benchmark document\n";
  for (size_t i = 0; out.size() < bytes; ++i) {
    const std::string n = std::to_string(i);
    out += "Rod" + n + " is Physics3D.Bodies.RigidBody:\n";
    out += "    inertia.mass: " + std::to_string(1 + i % 17) + ".5  # kilograms\n";
    out += "    geometry is Physics3D.Geometries.Box:\n";
    out += "        size: Math.Vec3.from_xyz(0.1, 0.1, " + std::to_string(1 + i % 5) + ")\n";
    out += "    connector is Physics3D.Interactions.MateConnector:\n";
    out += "        position.z: -geometry.size.z * 0.5 + 2.5e-3\n";
    out += "        main_axis: Math.Vec3.Y_AXIS()\n";
    out += "        normal: {0, 0, 1}\n";
    out += "\n";
    out += "Scene" + n + " is Physics3D.System:\n";
    out += "    .doc: \"\"\"A rod on a hinge,\n    generated.\"\"\"\n";
    out += "    rod is Rod" + n + "\n";
    out += "    world_connector is Physics3D.Interactions.MateConnector:\n";
    out += "        position: {0, " + std::to_string(i % 7) + ", 0.5}\n";
    out += "    hinge is Physics3D.Interactions.Hinge:\n";
    out += "        connectors: [rod.connector, world_connector]\n";
    out += "        initial_angle: Math.PI / 4\n";
    out += "\n";
  }
  return out;
}

}  // namespace openplx::bench

namespace openplx::bench {

// A model of `groups` x `parts_per_group` Part instances, each with Reals, an expression and a Vec3 value.
inline std::string generate_instances(size_t groups, size_t parts_per_group) {
  std::string out =
      "Part:\n"
      "    mass is Real: 1.0\n"
      "    offset is Math.Vec3: {0, 0, 0.5}\n"
      "    scaled is Real: mass * 2 + offset.z\n"
      "Group:\n";
  for (size_t p = 0; p < parts_per_group; ++p) {
    out += "    p" + std::to_string(p) + " is Part:\n        mass: " + std::to_string(p + 1) + ".5\n";
  }
  out += "Scene:\n";
  for (size_t g = 0; g < groups; ++g) out += "    g" + std::to_string(g) + " is Group\n";
  return out;
}

}  // namespace openplx::bench

namespace openplx::bench {

// A Physics3D scene of `bodies` links: a chain (each link hinged to the previous one, the first to the
// world) when `chain` is true, else a wide tree of `bodies / 10` trunks with 9 branches each. Every link has
// a box, two connectors 1 m apart and a hinge; nothing is placed by hand, so SNAP places every body.
inline std::string generate_mechanism(size_t bodies, bool chain) {
  std::string out =
      "Link is Physics3D.Bodies.RigidBody:\n"
      "    inertia.mass: 1\n"
      "    geometry is Physics3D.Geometries.Box:\n"
      "        size: {0.1, 0.1, 1}\n"
      "    bottom is Physics3D.Interactions.MateConnector:\n"
      "        main_axis: Math.Vec3.Y_AXIS()\n"
      "        normal: Math.Vec3.Z_AXIS()\n"
      "    top is Physics3D.Interactions.MateConnector:\n"
      "        position: {0, 0, 1}\n"
      "        main_axis: Math.Vec3.Y_AXIS()\n"
      "        normal: Math.Vec3.Z_AXIS()\n"
      "Scene is Physics3D.System:\n"
      "    base is Physics3D.Interactions.MateConnector:\n"
      "        main_axis: Math.Vec3.Y_AXIS()\n"
      "        normal: Math.Vec3.Z_AXIS()\n";
  for (size_t i = 0; i < bodies; ++i) out += "    l" + std::to_string(i) + " is Link\n";
  for (size_t i = 0; i < bodies; ++i) {
    std::string parent;
    if (chain) {
      parent = i == 0 ? "base" : "l" + std::to_string(i - 1) + ".top";
    } else {
      const size_t trunk = i / 10 * 10;
      parent = i == trunk ? "base" : "l" + std::to_string(trunk) + ".top";
    }
    out += "    h" + std::to_string(i) + " is Physics3D.Interactions.Hinge:\n        connectors: [" + parent +
           ", l" + std::to_string(i) + ".bottom]\n        initial_angle: 0.01\n";
  }
  return out;
}

}  // namespace openplx::bench
