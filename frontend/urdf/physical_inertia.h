// Physical plausibility of a rigid body's inertia tensor, and the repair applied to one that is not.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

namespace openplx::frontend {

struct InertiaRepair {
  Eigen::Matrix3d tensor;  // the repaired tensor, in the same frame
  std::string what;        // what was wrong and what was done, for the warning
};

// A tensor is physical when its principal moments, as MuJoCo 2.2.2 computes them from these numbers
// (mujoco_principal_inertia.h), are not negative and satisfy the triangle inequality (A + B >= C, exactly, as
// MuJoCo's compiler checks it). Otherwise the principal moments become their mean (MuJoCo's
// `balanceinertia` rule, which keeps the trace), or, when that mean is not positive, those of a solid
// sphere of water density and the given mass. A zero principal moment that keeps the triangle inequality
// (an ideal rod) is reported but kept, as MuJoCo keeps it. nullopt when the tensor is physical or the mass
// is not positive.
std::optional<InertiaRepair> repair_inertia(double mass, const Eigen::Matrix3d& tensor);

}  // namespace openplx::frontend
