// URDF import through urdfdom: a robot description becomes OpenPLX source text that the front end reads like
// any imported document, so an imported robot can be extended in OpenPLX (motors, outputs, overrides).
//
// The generated model derives from Physics3D.System: one RigidBody per link (mass, inertia tensor at the
// inertial frame, collision geometries, visual geometries), and per joint a MateConnector in the parent at
// the joint origin and one in the child at its frame (both with main_axis = the joint axis), joined by a
// Hinge (revolute, continuous), Prismatic or Lock (fixed); limits become ranges. The root link is locked to
// the world, as MuJoCo's own URDF compiler fixes it.
#pragma once

#include <optional>
#include <string>

namespace openplx::frontend {

// OpenPLX text declaring model `model_name` for the URDF at `path`, or nullopt with `error`.
std::optional<std::string> urdf_to_openplx(const std::string& path, const std::string& model_name,
                                           std::string& error);

}  // namespace openplx::frontend
