#include "frontend/natives/math_rotation.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace openplx::natives {

namespace {

// Direction of v, or nullopt for the zero vector. Dividing by the largest |component| first keeps tiny and
// huge vectors from under/overflowing in the squared norm.
std::optional<Eigen::Vector3d> unit(const Eigen::Vector3d& v) {
  const double scale = v.cwiseAbs().maxCoeff();
  if (scale == 0.0) return std::nullopt;
  const Eigen::Vector3d w = v / scale;
  return w / w.norm();
}

Eigen::Vector3d world_axis(char c) {
  if (c == 'x') return Eigen::Vector3d::UnitX();
  if (c == 'y') return Eigen::Vector3d::UnitY();
  return Eigen::Vector3d::UnitZ();
}

// Published order: the static list, then the rotating list (../shared/spec/bundles-api.md §1).
constexpr std::array<std::string_view, 24> kEulerConventions = {
    "xyzs", "xyxs", "xzys", "xzxs", "yzxs", "yzys", "yxzs", "yxys", "zxys", "zxzs", "zyxs", "zyzs",
    "zyxr", "xyxr", "yzxr", "xzxr", "xzyr", "yzyr", "zxyr", "yxyr", "yxzr", "zxzr", "xyzr", "zyzr"};

}  // namespace

Eigen::Quaterniond quat_from_xyzw(double x, double y, double z, double w) {
  return {w, x, y, z};
}

std::array<double, 4> quat_to_xyzw(const Eigen::Quaterniond& q) {
  return {q.x(), q.y(), q.z(), q.w()};
}

Eigen::Quaterniond quat_angle_axis(double angle, const Eigen::Vector3d& axis) {
  const auto n = unit(axis);
  if (!n) return Eigen::Quaterniond::Identity();
  const double half = 0.5 * angle;
  return {std::cos(half), std::sin(half) * n->x(), std::sin(half) * n->y(), std::sin(half) * n->z()};
}

Eigen::Quaterniond quat_from_to(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  const auto a = unit(from);
  const auto b = unit(to);
  if (!a || !b) return Eigen::Quaterniond::Identity();
  const double d = a->dot(*b);
  // a × b == a × (b - a) == a × (b + a); using the small difference avoids cancellation, so the axis stays
  // orthogonal to `a` to full precision even for nearly (anti)parallel inputs.
  const Eigen::Vector3d c = d >= 0.0 ? a->cross(*b - *a) : a->cross(*b + *a);
  const auto axis = unit(c);
  if (!axis) {
    if (d > 0.0) return Eigen::Quaterniond::Identity();
    return quat_angle_axis(std::numbers::pi, orthogonal_unit_vector(*a));
  }
  return quat_angle_axis(std::atan2(c.norm(), d), *axis);
}

Eigen::Quaterniond quat_normal(const Eigen::Quaterniond& q) {
  const double n = q.norm();
  if (n == 0.0) return Eigen::Quaterniond::Identity();
  return Eigen::Quaterniond(q.coeffs() / n);
}

Eigen::Vector3d quat_rotate(const Eigen::Quaterniond& q, const Eigen::Vector3d& v) {
  // Eigen's q * v assumes a unit quaternion; normalising first makes it equal q·v·q⁻¹ for any q ≠ 0.
  return quat_normal(q) * v;
}

Eigen::Quaterniond quat_conj(const Eigen::Quaterniond& q) {
  return {q.w(), -q.x(), -q.y(), -q.z()};
}

Eigen::Quaterniond quat_inverse(const Eigen::Quaterniond& q) {
  const double n2 = q.squaredNorm();
  if (n2 == 0.0) return Eigen::Quaterniond(Eigen::Vector4d::Zero());
  return Eigen::Quaterniond(quat_conj(q).coeffs() / n2);
}

std::optional<Eigen::Quaterniond> quat_from_euler(std::string_view convention, double alpha, double beta,
                                                  double gamma) {
  if (std::find(kEulerConventions.begin(), kEulerConventions.end(), convention) == kEulerConventions.end())
    return std::nullopt;
  const Eigen::Quaterniond qi = quat_angle_axis(alpha, world_axis(convention[0]));
  const Eigen::Quaterniond qj = quat_angle_axis(beta, world_axis(convention[1]));
  const Eigen::Quaterniond qk = quat_angle_axis(gamma, world_axis(convention[2]));
  // Static: later rotations act about fixed axes, so they multiply from the left. Rotating: from the right.
  return convention[3] == 's' ? qk * qj * qi : qi * qj * qk;
}

std::vector<std::string_view> euler_conventions() {
  return {kEulerConventions.begin(), kEulerConventions.end()};
}

Eigen::Vector3d orthogonal_unit_vector(const Eigen::Vector3d& v) {
  const auto u = unit(v);
  if (!u) return Eigen::Vector3d::UnitX();
  // Strict comparisons keep the tie order x, y, z.
  int axis = 0;
  if (std::abs((*u)[1]) < std::abs((*u)[axis])) axis = 1;
  if (std::abs((*u)[2]) < std::abs((*u)[axis])) axis = 2;
  // |u × e| = sqrt(1 - u_axis²) >= sqrt(2/3), so this never degenerates.
  const Eigen::Vector3d c = u->cross(Eigen::Vector3d::Unit(axis));
  return c / c.norm();
}

double angle_between_vectors(const Eigen::Vector3d& v1, const Eigen::Vector3d& v2,
                             const Eigen::Vector3d& rot) {
  // atan2 is scale-invariant in its two arguments, so unit inputs give the same angle without overflow.
  const auto a = unit(v1);
  const auto b = unit(v2);
  if (!a || !b) return 0.0;
  const Eigen::Vector3d c = a->cross(*b);
  const auto n = unit(rot);
  if (!n) return std::atan2(c.norm(), a->dot(*b));
  const double angle = std::atan2(c.dot(*n), a->dot(*b));
  // atan2(-0.0, negative) is -pi; the range is (-pi, pi].
  return angle == -std::numbers::pi ? std::numbers::pi : angle;
}

Affine affine_compose(const Affine& lhs, const Affine& rhs) {
  return {quat_rotate(lhs.rotation, rhs.position) + lhs.position, lhs.rotation * rhs.rotation};
}

Affine affine_inverse(const Affine& a) {
  const Eigen::Quaterniond r = quat_inverse(a.rotation);
  return {-quat_rotate(r, a.position), r};
}

Affine affine_inverse_of(const Eigen::Vector3d& p, const Eigen::Quaterniond& r) {
  return affine_inverse({p, r});
}

std::optional<Affine> affine_from_axes(const Eigen::Vector3d& new_z, const Eigen::Vector3d& new_x,
                                       const Eigen::Vector3d& position) {
  const auto z = unit(new_z);
  const auto x0 = unit(new_x);
  if (!z || !x0) return std::nullopt;
  Eigen::Vector3d x = *x0 - x0->dot(*z) * *z;
  if (!(x.norm() > 1e-12)) return std::nullopt;
  x -= x.dot(*z) * *z;  // second Gram-Schmidt pass: one pass leaves O(eps/|x⊥|) of z behind
  x.normalize();
  Eigen::Matrix3d r;
  r.col(0) = x;
  r.col(1) = z->cross(x);
  r.col(2) = *z;
  return Affine{position, Eigen::Quaterniond(r).normalized()};
}

Eigen::Vector3d affine_transform_point(const Affine& a, const Eigen::Vector3d& v) {
  return quat_rotate(a.rotation, v) + a.position;
}

Eigen::Vector3d affine_transform_vector(const Affine& a, const Eigen::Vector3d& v) {
  return quat_rotate(a.rotation, v);
}

}  // namespace openplx::natives
