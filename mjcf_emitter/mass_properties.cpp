#include "mjcf_emitter/mass_properties.h"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace openplx::mjcf {

std::optional<MassProperties> unit_density_properties(const snap::Geometry& g) {
  MassProperties p;
  using Shape = snap::Geometry::Shape;
  switch (g.shape) {
    case Shape::Box: {
      const double a = g.size.x(), b = g.size.y(), c = g.size.z();
      p.mass = a * b * c;
      p.inertia.diagonal() << p.mass * (b * b + c * c) / 12, p.mass * (a * a + c * c) / 12,
          p.mass * (a * a + b * b) / 12;
      return p;
    }
    case Shape::Sphere: {
      const double r = g.size.x();
      p.mass = 4.0 / 3.0 * M_PI * r * r * r;
      p.inertia.diagonal().setConstant(0.4 * p.mass * r * r);
      return p;
    }
    case Shape::Cylinder: {
      const double r = g.size.x(), h = g.size.y();
      p.mass = M_PI * r * r * h;
      const double across = p.mass * (3 * r * r + h * h) / 12;
      p.inertia.diagonal() << across, 0.5 * p.mass * r * r, across;
      return p;
    }
    case Shape::Capsule: {
      // A cylinder of height h and two hemispheres of radius r at its ends.
      const double r = g.size.x(), h = g.size.y();
      const double mc = M_PI * r * r * h;
      const double mh = 4.0 / 3.0 * M_PI * r * r * r;  // both hemispheres
      p.mass = mc + mh;
      const double axial = mc * r * r / 2 + mh * 2 * r * r / 5;
      const double across = mc * (h * h / 12 + r * r / 4) + mh * (2 * r * r / 5 + h * h / 4 + 3 * h * r / 8);
      p.inertia.diagonal() << across, axial, across;
      return p;
    }
    default:
      return std::nullopt;
  }
}

std::optional<MassProperties> combine(const std::vector<std::pair<const snap::Geometry*, double>>& parts) {
  std::vector<MassProperties> placed;
  MassProperties total;
  for (const auto& [g, density] : parts) {
    std::optional<MassProperties> unit = unit_density_properties(*g);
    if (!unit) continue;
    MassProperties p;
    p.mass = unit->mass * density;
    p.com = g->local.position;
    const Eigen::Matrix3d r = g->local.rotation.toRotationMatrix();
    p.inertia = r * (unit->inertia * density) * r.transpose();
    total.mass += p.mass;
    total.com += p.mass * p.com;
    placed.push_back(p);
  }
  if (placed.empty() || total.mass <= 0) return std::nullopt;
  total.com /= total.mass;
  for (const MassProperties& p : placed) {
    const Eigen::Vector3d d = p.com - total.com;
    total.inertia += p.inertia + p.mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
  }
  return total;
}

}  // namespace openplx::mjcf
