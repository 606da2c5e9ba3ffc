// URDF import through urdfdom: a robot description becomes OpenPLX source text that the front end reads like
// any imported document, so an imported robot can be extended in OpenPLX (motors, outputs, overrides).
//
// The generated model derives from Physics3D.System: one RigidBody per link (mass, inertia tensor at the
// inertial frame, collision geometries, visual geometries with their colours), and per joint a MateConnector
// in the parent at the joint origin and one in the child at its frame (both with main_axis = the joint
// axis), joined by a Hinge (revolute, continuous), Prismatic or Lock (fixed); limits become ranges, mimic a
// Urdf.Mimic, <dynamics> and effort/velocity limits a Urdf.JointProperties. The root link is locked to the
// world, as MuJoCo's own URDF compiler fixes it.
//
// Every generated line remembers the URDF element it came from, so diagnostics about the robot (here, in
// SNAP or in the emitter) point at the URDF's own file and line.
#pragma once

#include <string>

#include "frontend/urdf/urdf_result.h"

namespace openplx::frontend {

// Converts the URDF at `path` whose text is `urdf_text` into model `model_name`. Runs inside the importer
// module; the front end calls import_urdf (urdf_importer.h).
UrdfImport convert_urdf(const std::string& path, const std::string& urdf_text, const std::string& model_name,
                        const UrdfImportOptions& options = {});

}  // namespace openplx::frontend
