// Mass properties of rigid bodies from their primitive collision geometries, for bodies whose OpenPLX
// inertia gives a mass but no tensor (or neither). Uniform density per geometry; the parallel-axis theorem
// combines the parts about their common centre of mass.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "snap/resolved_system.h"

namespace openplx::mjcf {

struct MassProperties {
  double mass = 0.0;
  Eigen::Vector3d com = Eigen::Vector3d::Zero();      // in the body frame
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  // about com, body axes
};

// Volume and inertia per unit density of one primitive in its own frame (cylinders and capsules along
// local Y, as OpenPLX defines them); nullopt for meshes and planes.
std::optional<MassProperties> unit_density_properties(const snap::Geometry& geometry);

// The combined properties of `parts` (each with its density); nullopt when no part is a primitive.
std::optional<MassProperties> combine(const std::vector<std::pair<const snap::Geometry*, double>>& parts);

}  // namespace openplx::mjcf
