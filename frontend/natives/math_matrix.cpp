#include "frontend/natives/math_matrix.h"

#include <Eigen/SVD>

#include "frontend/natives/math_rotation.h"

namespace openplx::natives {

namespace {

// Row-major fill of an N x N matrix from N lines of N values each; `as_rows` false writes them as columns.
template <int N, typename... Lines>
std::optional<Eigen::Matrix<double, N, N>> from_lines(bool as_rows, Lines... lines) {
  const std::span<const double> all[] = {lines...};
  Eigen::Matrix<double, N, N> m;
  for (int i = 0; i < N; ++i) {
    if (all[i].size() != static_cast<std::size_t>(N)) return std::nullopt;
    for (int j = 0; j < N; ++j) (as_rows ? m(i, j) : m(j, i)) = all[i][j];
  }
  return m;
}

template <int N>
std::optional<Eigen::Matrix<double, N, N>> from_row_major(std::span<const double> values) {
  if (values.size() != static_cast<std::size_t>(N * N)) return std::nullopt;
  Eigen::Matrix<double, N, N> m;
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) m(i, j) = values[i * N + j];
  return m;
}

}  // namespace

std::optional<Eigen::Matrix3d> matrix3_from_row_major(std::span<const double> values) {
  return from_row_major<3>(values);
}

std::optional<Eigen::Matrix3d> matrix3_from_rows(std::span<const double> r0, std::span<const double> r1,
                                                 std::span<const double> r2) {
  return from_lines<3>(true, r0, r1, r2);
}

std::optional<Eigen::Matrix3d> matrix3_from_columns(std::span<const double> c0, std::span<const double> c1,
                                                    std::span<const double> c2) {
  return from_lines<3>(false, c0, c1, c2);
}

Eigen::Matrix3d matrix3_diag(double x, double y, double z) {
  return Eigen::Vector3d(x, y, z).asDiagonal();
}

std::optional<Eigen::Matrix4d> matrix4_from_row_major(std::span<const double> values) {
  return from_row_major<4>(values);
}

std::optional<Eigen::Matrix4d> matrix4_from_rows(std::span<const double> r0, std::span<const double> r1,
                                                 std::span<const double> r2, std::span<const double> r3) {
  return from_lines<4>(true, r0, r1, r2, r3);
}

std::optional<Eigen::Matrix4d> matrix4_from_columns(std::span<const double> c0, std::span<const double> c1,
                                                    std::span<const double> c2, std::span<const double> c3) {
  return from_lines<4>(false, c0, c1, c2, c3);
}

Eigen::Matrix4d matrix4_from_vec3_quat(const Eigen::Vector3d& v, const Eigen::Quaterniond& q) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = quat_normal(q).toRotationMatrix();
  m.topRightCorner<3, 1>() = v;
  return m;
}

Eigen::Vector3d matrix4_affine_translation(const Eigen::Matrix4d& m) {
  return m.topRightCorner<3, 1>();
}

Eigen::Quaterniond matrix4_affine_rotation(const Eigen::Matrix4d& m) {
  const Eigen::Matrix3d a = m.topLeftCorner<3, 3>();
  if (a.isZero(0.0)) return Eigen::Quaterniond::Identity();
  // Polar factor U·Vᵀ; if it is a reflection, flip the direction of the smallest singular value (Eigen sorts
  // them in decreasing order) to get the nearest proper rotation.
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(a, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d u = svd.matrixU();
  const Eigen::Matrix3d v = svd.matrixV();
  if ((u * v.transpose()).determinant() < 0.0) u.col(2) = -u.col(2);
  return Eigen::Quaterniond(u * v.transpose()).normalized();
}

double line_length(const Eigen::Vector3d& start, const Eigen::Vector3d& end) {
  return (end - start).norm();
}

}  // namespace openplx::natives
