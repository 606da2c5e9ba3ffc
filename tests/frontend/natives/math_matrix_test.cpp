// Hand values and independent constructions (hand-written rotation matrices, polar decompositions known by
// construction) for the Matrix3x3 / Matrix4x4 / Line natives. Tolerance 1e-12 unless a value is exact.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "frontend/natives/math_matrix.h"

namespace nat = openplx::natives;
using Eigen::Matrix3d;
using Eigen::Matrix4d;
using Eigen::Quaterniond;
using Eigen::Vector3d;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTol = 1e-12;

double max_diff(const auto& a, const auto& b) {
  return (a - b).cwiseAbs().maxCoeff();
}

double quat_diff_up_to_sign(const Quaterniond& a, const Quaterniond& b) {
  return std::min(max_diff(a.coeffs(), b.coeffs()), max_diff(a.coeffs(), -b.coeffs()));
}

// Rotation of t about Z and about X, written out.
Matrix3d rot_z(double t) {
  Matrix3d m;
  m << std::cos(t), -std::sin(t), 0, std::sin(t), std::cos(t), 0, 0, 0, 1;
  return m;
}
Matrix3d rot_x(double t) {
  Matrix3d m;
  m << 1, 0, 0, 0, std::cos(t), -std::sin(t), 0, std::sin(t), std::cos(t);
  return m;
}

// Unit quaternion (w, x, y, z) for a rotation of t about a unit axis, from the half-angle definition.
Quaterniond half_angle(double t, const Vector3d& unit_axis) {
  const double s = std::sin(t / 2);
  return {std::cos(t / 2), s * unit_axis.x(), s * unit_axis.y(), s * unit_axis.z()};
}

Matrix4d affine(const Matrix3d& block, const Vector3d& t) {
  Matrix4d m = Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = block;
  m.topRightCorner<3, 1>() = t;
  return m;
}

TEST(MathMatrix3, FromRowMajorIsRowMajor) {
  const std::vector<double> v = {1, 2, 3, 4, 5, 6, 7, 8, 9};
  const auto m = nat::matrix3_from_row_major(v);
  ASSERT_TRUE(m);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) EXPECT_EQ((*m)(r, c), 3 * r + c + 1);  // e<r><c>
  EXPECT_FALSE(nat::matrix3_from_row_major(std::vector<double>(8, 1.0)));
  EXPECT_FALSE(nat::matrix3_from_row_major(std::vector<double>(10, 1.0)));
  EXPECT_FALSE(nat::matrix3_from_row_major({}));
}

TEST(MathMatrix3, FromRowsAndColumns) {
  const std::vector<double> a = {1, 2, 3}, b = {4, 5, 6}, c = {7, 8, 9}, short_line = {1, 2};
  const auto rows = nat::matrix3_from_rows(a, b, c);
  const auto cols = nat::matrix3_from_columns(a, b, c);
  ASSERT_TRUE(rows && cols);
  Matrix3d expected;
  expected << 1, 2, 3, 4, 5, 6, 7, 8, 9;
  EXPECT_EQ(*rows, expected);
  EXPECT_EQ(*cols, expected.transpose());
  EXPECT_EQ((*cols)(0, 1), 4);  // second column starts with b[0]
  EXPECT_FALSE(nat::matrix3_from_rows(a, short_line, c));
  EXPECT_FALSE(nat::matrix3_from_columns(a, b, std::vector<double>{1, 2, 3, 4}));
}

TEST(MathMatrix3, Diag) {
  Matrix3d expected;
  expected << 2, 0, 0, 0, -3, 0, 0, 0, 0.5;
  EXPECT_EQ(nat::matrix3_diag(2, -3, 0.5), expected);
}

TEST(MathMatrix4, FromRowMajorRowsAndColumns) {
  std::vector<double> v(16);
  for (int i = 0; i < 16; ++i) v[i] = i + 1;
  const auto m = nat::matrix4_from_row_major(v);
  ASSERT_TRUE(m);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) EXPECT_EQ((*m)(r, c), 4 * r + c + 1);
  EXPECT_FALSE(nat::matrix4_from_row_major(std::vector<double>(9, 1.0)));

  const std::vector<double> r0 = {1, 2, 3, 4}, r1 = {5, 6, 7, 8}, r2 = {9, 10, 11, 12}, r3 = {13, 14, 15, 16};
  const auto rows = nat::matrix4_from_rows(r0, r1, r2, r3);
  const auto cols = nat::matrix4_from_columns(r0, r1, r2, r3);
  ASSERT_TRUE(rows && cols);
  EXPECT_EQ(*rows, *m);
  EXPECT_EQ(*cols, m->transpose());
  EXPECT_FALSE(nat::matrix4_from_rows(r0, r1, r2, std::vector<double>{1, 2, 3}));
  EXPECT_FALSE(nat::matrix4_from_columns(r0, std::vector<double>{}, r2, r3));
}

TEST(MathMatrix4, FromVec3QuatHandValue) {
  // 90° about Z: columns are the images of X (= Y) and Y (= -X).
  Matrix4d expected;
  expected << 0, -1, 0, 1, 1, 0, 0, 2, 0, 0, 1, 3, 0, 0, 0, 1;
  const Quaterniond q = half_angle(kPi / 2, Vector3d::UnitZ());
  EXPECT_LT(max_diff(nat::matrix4_from_vec3_quat(Vector3d(1, 2, 3), q), expected), kTol);
  // A scaled quaternion is the same rotation; the zero quaternion is identity.
  EXPECT_LT(max_diff(nat::matrix4_from_vec3_quat(Vector3d(1, 2, 3), Quaterniond(2.5 * q.coeffs())), expected),
            kTol);
  EXPECT_EQ(nat::matrix4_from_vec3_quat(Vector3d(1, 2, 3), Quaterniond(0, 0, 0, 0)),
            affine(Matrix3d::Identity(), Vector3d(1, 2, 3)));
  // A general rotation: 0.3 rad about X.
  EXPECT_LT(max_diff(nat::matrix4_from_vec3_quat(Vector3d(-1, 0, 4), half_angle(0.3, Vector3d::UnitX())),
                     affine(rot_x(0.3), Vector3d(-1, 0, 4))),
            kTol);
}

TEST(MathMatrix4, AffineTranslation) {
  std::vector<double> v(16);
  for (int i = 0; i < 16; ++i) v[i] = i + 1;
  EXPECT_EQ(nat::matrix4_affine_translation(*nat::matrix4_from_row_major(v)), Vector3d(4, 8, 12));
}

TEST(MathMatrix4, AffineRotationOfRotationBlock) {
  const Quaterniond qz = half_angle(kPi / 2, Vector3d::UnitZ());
  EXPECT_LT(quat_diff_up_to_sign(nat::matrix4_affine_rotation(affine(rot_z(kPi / 2), Vector3d(5, 6, 7))), qz),
            kTol);
  const Vector3d axis = Vector3d(1, -2, 0.5).normalized();
  for (double t : {0.0, 0.4, -2.0, 3.0, kPi}) {
    // Round trip through from_vec3_quat.
    const Quaterniond q = half_angle(t, axis);
    EXPECT_LT(quat_diff_up_to_sign(
                  nat::matrix4_affine_rotation(nat::matrix4_from_vec3_quat(Vector3d::Zero(), q)), q),
              kTol)
        << t;
  }
  EXPECT_EQ(nat::matrix4_affine_rotation(Matrix4d::Zero()).coeffs(), Quaterniond::Identity().coeffs());
}

TEST(MathMatrix4, AffineRotationDropsScaleAndFixesReflection) {
  // The polar factor of R·S (S symmetric positive definite) is R, and so is that of S·R.
  const Matrix3d r = rot_z(0.7) * rot_x(-1.1);
  const Quaterniond expected = half_angle(0.7, Vector3d::UnitZ()) * half_angle(-1.1, Vector3d::UnitX());
  const Matrix3d s = Vector3d(2, 3, 0.5).asDiagonal();
  EXPECT_LT(quat_diff_up_to_sign(nat::matrix4_affine_rotation(affine(r * s, Vector3d::Zero())), expected),
            kTol);
  EXPECT_LT(quat_diff_up_to_sign(nat::matrix4_affine_rotation(affine(s * r, Vector3d::Zero())), expected),
            kTol);
  // R·diag(3, 2, -1) has SVD (R·diag(1,1,-1))·diag(3,2,1)·I; the nearest proper rotation flips the direction
  // of the smallest singular value back, giving R.
  const Matrix3d reflected = r * Vector3d(3, 2, -1).asDiagonal();
  EXPECT_LT(quat_diff_up_to_sign(nat::matrix4_affine_rotation(affine(reflected, Vector3d::Zero())), expected),
            kTol);
}

TEST(MathLine, Length) {
  EXPECT_EQ(nat::line_length(Vector3d(1, 2, 3), Vector3d(4, 6, 3)), 5.0);
  EXPECT_EQ(nat::line_length(Vector3d(1, 2, 3), Vector3d(1, 2, 3)), 0.0);
  EXPECT_NEAR(nat::line_length(Vector3d(0, 0, 0), Vector3d(1, 1, 1)), std::sqrt(3.0), 1e-15);
}

}  // namespace
