#include "frontend/urdf/physical_inertia.h"

#include <charconv>
#include <cmath>
#include <sstream>

#include "frontend/urdf/mujoco_principal_inertia.h"

namespace openplx::frontend {
namespace {
// The shortest text that reads back as `v` (the moments that decide are often 1 ulp apart).
std::string shortest(double v) {
  char buffer[32];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof(buffer), v);
  return std::string(buffer, error == std::errc() ? end : buffer);
}
}  // namespace

std::optional<InertiaRepair> repair_inertia(double mass, const Eigen::Matrix3d& tensor) {
  if (!(mass > 0)) return std::nullopt;
  // The moments MuJoCo's importer finds for these very numbers, judged by its compiler's exact rule: no
  // tolerance, so that what passes here loads there (a tolerance let A + B == C minus rounding through).
  const std::array<double, 3> p = mujoco_inertia::principal_moments(tensor).moments;
  const bool positive = !mujoco_inertia::negative(p);
  const bool triangle = mujoco_inertia::triangle(p);
  if (positive && triangle && p[0] > 0 && p[1] > 0 && p[2] > 0) return std::nullopt;
  std::ostringstream what;
  if (positive && triangle) {  // an ideal rod (or point): a limit of physical bodies MuJoCo accepts
    what << "principal moments " << shortest(p[0]) << ", " << shortest(p[1]) << ", " << shortest(p[2])
         << " include a zero (an ideal thin rod); kept as written, as MuJoCo's own importer keeps it";
    return InertiaRepair{tensor, what.str()};
  }
  what << "principal moments " << shortest(p[0]) << ", " << shortest(p[1]) << ", " << shortest(p[2])
       << (positive ? " (as MuJoCo computes them) violate the triangle inequality A + B >= C, which MuJoCo "
                      "checks exactly"
                    : " are not all positive");
  double mean = (p[0] + p[1] + p[2]) / 3;
  if (mean > 0) {
    what << "; they were set to their mean " << shortest(mean) << " (MuJoCo's balanceinertia)";
  } else {
    const double radius = std::cbrt(3 * mass / (4 * M_PI * 1000.0));
    mean = 0.4 * mass * radius * radius;
    what << "; they were set to " << shortest(mean) << ", a solid sphere's of the same mass at water density";
  }
  return InertiaRepair{mean * Eigen::Matrix3d::Identity(), what.str()};  // equal moments: any frame
}

}  // namespace openplx::frontend
