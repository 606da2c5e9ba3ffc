// Numeric core of Math.Vec3 / Math.Quat / Math.AffineTransform (../shared/spec/bundles-api.md §1, Appendix
// A). Pure functions on Eigen types, no dependency on the rest of the project; the evaluator wraps them.
// Quaternions are Eigen::Quaterniond. Beware: Eigen's 4-argument constructor takes (w, x, y, z), while
// OpenPLX fields are (x, y, z, w); use quat_from_xyzw / quat_to_xyzw at the boundary.
#pragma once

#include <array>
#include <optional>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

namespace openplx::natives {

// ---- Quat -------------------------------------------------------------------------------------------

// OpenPLX field order (x, y, z, w) <-> Eigen. No normalisation: Math.Quat.from_xyzw stores what it is given.
Eigen::Quaterniond quat_from_xyzw(double x, double y, double z, double w);
std::array<double, 4> quat_to_xyzw(const Eigen::Quaterniond& q);

// Rotation of `angle` radians (right-handed) about `axis`; the axis is normalised, a zero axis gives
// identity.
Eigen::Quaterniond quat_angle_axis(double angle, const Eigen::Vector3d& axis);

// Shortest rotation taking the direction of `from` onto the direction of `to` (lengths are ignored).
// Parallel (or a zero input) -> identity; antiparallel -> rotation of pi about orthogonal_unit_vector(from).
Eigen::Quaterniond quat_from_to(const Eigen::Vector3d& from, const Eigen::Vector3d& to);

// q / |q|; the zero quaternion gives identity (so every quaternion names some rotation).
Eigen::Quaterniond quat_normal(const Eigen::Quaterniond& q);

// Rotates v by q·v·q⁻¹, i.e. by quat_normal(q): non-unit quaternions rotate without scaling, zero acts as
// identity.
Eigen::Vector3d quat_rotate(const Eigen::Quaterniond& q, const Eigen::Vector3d& v);

// (-x, -y, -z, w).
Eigen::Quaterniond quat_conj(const Eigen::Quaterniond& q);

// conj(q) / |q|²; the zero quaternion has no inverse and gives the zero quaternion (as Eigen does).
Eigen::Quaterniond quat_inverse(const Eigen::Quaterniond& q);

// Euler-angle factories Math.Quat.from_euler_angles_<convention>(alpha, beta, gamma). A convention is three
// axes i j k (adjacent axes differ: the 12 Shoemake orders) and a frame suffix. R_a(t) is the right-handed
// rotation by t about world axis a.
//   suffix s, static (extrinsic) frame: rotate by alpha about the FIXED axis i, then beta about fixed j, then
//     gamma about fixed k:             R = R_k(gamma) · R_j(beta) · R_i(alpha)
//   suffix r, rotating (intrinsic) frame: rotate by alpha about i, then beta about the new j, then gamma
//     about the newest k:              R = R_i(alpha) · R_j(beta) · R_k(gamma)
// So "<ijk>s"(a, b, c) == "<kji>r"(c, b, a). Unknown convention -> nullopt.
std::optional<Eigen::Quaterniond> quat_from_euler(std::string_view convention, double alpha, double beta,
                                                  double gamma);

// All 24 convention names in the order of the published OpenPLX list (12 static, then 12 rotating).
std::vector<std::string_view> euler_conventions();

// ---- Vec3 -------------------------------------------------------------------------------------------

// Math.Vec3.get_orthogonal_unit_vector (the algorithm is unpublished; ours, used everywhere):
// v × e, normalised, where e is the world axis whose |component| in v is smallest (ties: x, then y, then z).
// E.g. Z -> (0,1,0), X -> (0,0,1), Y -> (0,0,-1). The zero vector gives (1,0,0).
Eigen::Vector3d orthogonal_unit_vector(const Eigen::Vector3d& v);

// Math.Vec3.angle_between_vectors: signed angle in (-pi, pi] from v1 to v2, right-handed about rot:
// atan2(dot(cross(v1, v2), rot/|rot|), dot(v1, v2)); -pi is reported as pi. A zero rot gives the unsigned
// angle in [0, pi]; a zero v1 or v2 gives 0.
double angle_between_vectors(const Eigen::Vector3d& v1, const Eigen::Vector3d& v2,
                             const Eigen::Vector3d& rot);

// ---- AffineTransform --------------------------------------------------------------------------------

// Rigid transform x -> rotation·x + position. Default: identity. Rotations are used as given (the zero
// quaternion acts as identity through quat_rotate); compose does not renormalise.
struct Affine {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
};

// lhs ∘ rhs (rhs applied first): position = lhs.r·rhs.p + lhs.p, rotation = lhs.r·rhs.r.
Affine affine_compose(const Affine& lhs, const Affine& rhs);

// The inverse transform: rotation = quat_inverse(r), position = -(r⁻¹·p).
Affine affine_inverse(const Affine& a);

// Math.AffineTransform.inverse_of(p, r): the inverse of the transform (p, r).
Affine affine_inverse_of(const Eigen::Vector3d& p, const Eigen::Quaterniond& r);

// Math.AffineTransform.from_axes: the rotation maps Z to z = new_z/|new_z| and X to x = the part of new_x
// orthogonal to z (Gram-Schmidt), normalised; Y = z × x. nullopt when new_z is zero or new_x has no part
// orthogonal to it (|x⊥| <= 1e-12·|new_x|), so the caller can report the error (snap.md §2.2).
std::optional<Affine> affine_from_axes(const Eigen::Vector3d& new_z, const Eigen::Vector3d& new_x,
                                       const Eigen::Vector3d& position);

// rotation·v + position, and rotation·v.
Eigen::Vector3d affine_transform_point(const Affine& a, const Eigen::Vector3d& v);
Eigen::Vector3d affine_transform_vector(const Affine& a, const Eigen::Vector3d& v);

}  // namespace openplx::natives
