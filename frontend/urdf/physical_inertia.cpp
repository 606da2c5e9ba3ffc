#include "frontend/urdf/physical_inertia.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <sstream>

namespace openplx::frontend {

std::optional<InertiaRepair> repair_inertia(double mass, const Eigen::Matrix3d& tensor) {
  if (!(mass > 0)) return std::nullopt;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(tensor);
  const Eigen::Vector3d p = eigen.eigenvalues();  // ascending
  // Relative slack: a thin rod or a flat plate sits exactly on the triangle inequality's edge.
  const double slack = 1e-9 * std::max(p.cwiseAbs().maxCoeff(), 1e-300);
  const bool positive = p.minCoeff() > 0;
  const bool triangle = p(0) + p(1) + slack >= p(2);
  if (positive && triangle) return std::nullopt;
  std::ostringstream what;
  what.precision(6);
  if (p.minCoeff() == 0 && triangle) {  // an ideal rod (or point): a limit of physical bodies MuJoCo accepts
    what << "principal moments " << p(0) << ", " << p(1) << ", " << p(2)
         << " include a zero (an ideal thin rod); kept as written, as MuJoCo's own importer keeps it";
    return InertiaRepair{tensor, what.str()};
  }
  what << "principal moments " << p(0) << ", " << p(1) << ", " << p(2)
       << (positive ? " violate the triangle inequality (A + B >= C)" : " are not all positive");
  double mean = p.sum() / 3;
  if (mean > 0) {
    what << "; they were set to their mean " << mean;
  } else {
    const double radius = std::cbrt(3 * mass / (4 * M_PI * 1000.0));
    mean = 0.4 * mass * radius * radius;
    what << "; they were set to " << mean << ", a solid sphere's of the same mass at water density";
  }
  return InertiaRepair{mean * Eigen::Matrix3d::Identity(), what.str()};  // equal moments: any frame
}

}  // namespace openplx::frontend
