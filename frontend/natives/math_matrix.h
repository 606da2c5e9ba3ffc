// Numeric core of Math.Matrix3x3 / Math.Matrix4x4 / Math.Line (../shared/spec/bundles-api.md §1). Pure Eigen,
// no project deps. Matrices are row-major in OpenPLX (e<row><col>); here they are Eigen::Matrix3d / Matrix4d
// indexed m(row, col). Factories taking lists return std::nullopt when a list has the wrong length.
#pragma once

#include <optional>
#include <span>

#include <Eigen/Geometry>

namespace openplx::natives {

// 9 values e00 e01 e02 e10 ... e22.
std::optional<Eigen::Matrix3d> matrix3_from_row_major(std::span<const double> values);
// Each argument is one row (resp. column) of 3 values.
std::optional<Eigen::Matrix3d> matrix3_from_rows(std::span<const double> r0, std::span<const double> r1,
                                                 std::span<const double> r2);
std::optional<Eigen::Matrix3d> matrix3_from_columns(std::span<const double> c0, std::span<const double> c1,
                                                    std::span<const double> c2);
Eigen::Matrix3d matrix3_diag(double x, double y, double z);

// 16 values e00 e01 e02 e03 e10 ... e33.
std::optional<Eigen::Matrix4d> matrix4_from_row_major(std::span<const double> values);
// Each argument is one row (resp. column) of 4 values.
std::optional<Eigen::Matrix4d> matrix4_from_rows(std::span<const double> r0, std::span<const double> r1,
                                                 std::span<const double> r2, std::span<const double> r3);
std::optional<Eigen::Matrix4d> matrix4_from_columns(std::span<const double> c0, std::span<const double> c1,
                                                    std::span<const double> c2, std::span<const double> c3);

// Affine matrix [R(q) v; 0 0 0 1], R(q) the rotation of q/|q| (zero quaternion: identity, as quat_normal).
Eigen::Matrix4d matrix4_from_vec3_quat(const Eigen::Vector3d& v, const Eigen::Quaterniond& q);
// The last column's first three entries.
Eigen::Vector3d matrix4_affine_translation(const Eigen::Matrix4d& m);
// Unit quaternion of the rotation nearest (Frobenius) to the upper-left 3x3 block, i.e. the rotation factor
// of its polar decomposition: scale and shear are dropped, a reflection is replaced by the closest proper
// rotation. An all-zero block gives identity.
Eigen::Quaterniond matrix4_affine_rotation(const Eigen::Matrix4d& m);

// Math.Line.length(): |end - start|.
double line_length(const Eigen::Vector3d& start, const Eigen::Vector3d& end);

}  // namespace openplx::natives
