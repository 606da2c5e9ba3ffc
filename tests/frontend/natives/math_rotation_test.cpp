// Every expectation here comes from a hand value or an independent formula (elementary rotation matrices
// written out with cos/sin, Rodrigues' formula, 4x4 homogeneous products), never from the function itself.
// Default tolerance 1e-12: the code under test does O(10) roundings of O(1) numbers (~1e-15), so 1e-12 only
// fails on a real error. Looser tolerances say why where they appear.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <string>

#include "frontend/natives/math_rotation.h"

namespace nat = openplx::natives;
using Eigen::Matrix3d;
using Eigen::Matrix4d;
using Eigen::Quaterniond;
using Eigen::Vector3d;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTol = 1e-12;

Matrix3d rot_x(double t) {
  Matrix3d m;
  m << 1, 0, 0, 0, std::cos(t), -std::sin(t), 0, std::sin(t), std::cos(t);
  return m;
}
Matrix3d rot_y(double t) {
  Matrix3d m;
  m << std::cos(t), 0, std::sin(t), 0, 1, 0, -std::sin(t), 0, std::cos(t);
  return m;
}
Matrix3d rot_z(double t) {
  Matrix3d m;
  m << std::cos(t), -std::sin(t), 0, std::sin(t), std::cos(t), 0, 0, 0, 1;
  return m;
}
Matrix3d rot_about(char axis, double t) {
  return axis == 'x' ? rot_x(t) : axis == 'y' ? rot_y(t) : rot_z(t);
}

// Rotation matrix of q/|q|, written out (not Eigen's toRotationMatrix).
Matrix3d matrix_of(const Quaterniond& q_in) {
  const double n =
      std::sqrt(q_in.w() * q_in.w() + q_in.x() * q_in.x() + q_in.y() * q_in.y() + q_in.z() * q_in.z());
  const double w = q_in.w() / n, x = q_in.x() / n, y = q_in.y() / n, z = q_in.z() / n;
  Matrix3d m;
  m << 1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),  //
      2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),   //
      2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y);
  return m;
}

// Rodrigues: R = I + sin t K + (1 - cos t) K², K the cross-product matrix of the unit axis.
Matrix3d rodrigues(double t, const Vector3d& axis) {
  const Vector3d k = axis / axis.norm();
  Matrix3d kx;
  kx << 0, -k.z(), k.y(), k.z(), 0, -k.x(), -k.y(), k.x(), 0;
  return Matrix3d::Identity() + std::sin(t) * kx + (1 - std::cos(t)) * kx * kx;
}

Matrix4d homogeneous(const nat::Affine& a) {
  Matrix4d h = Matrix4d::Identity();
  h.topLeftCorner<3, 3>() = matrix_of(a.rotation);
  h.topRightCorner<3, 1>() = a.position;
  return h;
}

double max_diff(const auto& a, const auto& b) {
  return (a - b).cwiseAbs().maxCoeff();
}

// q and -q are the same rotation.
double quat_diff_up_to_sign(const Quaterniond& a, const Quaterniond& b) {
  return std::min(max_diff(a.coeffs(), b.coeffs()), max_diff(a.coeffs(), -b.coeffs()));
}

struct Rng {
  std::mt19937 engine{12345};
  std::uniform_real_distribution<double> uni{-1.0, 1.0};
  double operator()(double lo, double hi) { return lo + (hi - lo) * 0.5 * (uni(engine) + 1.0); }
  Vector3d vec(double scale = 10.0) { return Vector3d(uni(engine), uni(engine), uni(engine)) * scale; }
  Quaterniond quat() { return Quaterniond(uni(engine), uni(engine), uni(engine), uni(engine)).normalized(); }
};

// Angle of the rotation q (in [0, pi]).
double rotation_angle(const Quaterniond& q) {
  return 2 * std::atan2(q.vec().norm(), std::abs(q.w()));
}

// ---- Quat basics -------------------------------------------------------------------------------------

TEST(MathQuat, FromXyzwKeepsOpenPlxFieldOrder) {
  const Quaterniond q = nat::quat_from_xyzw(1, 2, 3, 4);
  EXPECT_EQ(q.x(), 1);
  EXPECT_EQ(q.y(), 2);
  EXPECT_EQ(q.z(), 3);
  EXPECT_EQ(q.w(), 4);
  EXPECT_EQ(nat::quat_to_xyzw(q), (std::array<double, 4>{1, 2, 3, 4}));
}

TEST(MathQuat, AngleAxisHandValues) {
  const Quaterniond q = nat::quat_angle_axis(kPi / 2, Vector3d(0, 0, 5));
  EXPECT_NEAR(q.x(), 0, kTol);
  EXPECT_NEAR(q.y(), 0, kTol);
  EXPECT_NEAR(q.z(), std::sqrt(0.5), kTol);
  EXPECT_NEAR(q.w(), std::sqrt(0.5), kTol);
  EXPECT_EQ(nat::quat_to_xyzw(nat::quat_angle_axis(1.3, Vector3d::Zero())),
            (std::array<double, 4>{0, 0, 0, 1}));
}

TEST(MathQuat, AngleAxisMatchesRodrigues) {
  const Vector3d axes[] = {{1, 0, 0}, {0, -2, 0}, {1, 2, 3}, {-0.3, 0.1, 7}, {1e-200, 3e-200, -2e-200}};
  const double angles[] = {0.0, 0.25, -1.0, kPi / 2, kPi, -kPi, 4.0, 7.5, -12.0};
  for (const Vector3d& axis : axes)
    for (double angle : angles)
      EXPECT_LT(max_diff(matrix_of(nat::quat_angle_axis(angle, axis)),
                         rodrigues(angle, axis / axis.cwiseAbs().maxCoeff())),
                kTol)
          << "angle " << angle << " axis " << axis.transpose();
}

TEST(MathQuat, AppendixBCase87HalfTurnAboutZ) {
  const Vector3d v = nat::quat_rotate(nat::quat_angle_axis(kPi, Vector3d::UnitZ()), Vector3d::UnitX());
  EXPECT_LT(max_diff(v, Vector3d(-1, 0, 0)), 1e-9);  // the spec's tolerance
  EXPECT_LT(max_diff(v, Vector3d(-1, 0, 0)), 1e-15);
}

TEST(MathQuat, NormalHandValues) {
  EXPECT_EQ(nat::quat_to_xyzw(nat::quat_normal(nat::quat_from_xyzw(0, 0, 0, 2))),
            (std::array<double, 4>{0, 0, 0, 1}));
  EXPECT_EQ(nat::quat_to_xyzw(nat::quat_normal(nat::quat_from_xyzw(1, 1, 1, 1))),
            (std::array<double, 4>{0.5, 0.5, 0.5, 0.5}));
  const auto q = nat::quat_to_xyzw(nat::quat_normal(nat::quat_from_xyzw(3, 0, -4, 0)));
  EXPECT_NEAR(q[0], 0.6, 1e-15);
  EXPECT_NEAR(q[2], -0.8, 1e-15);
  EXPECT_EQ(nat::quat_to_xyzw(nat::quat_normal(nat::quat_from_xyzw(0, 0, 0, 0))),
            (std::array<double, 4>{0, 0, 0, 1}));
}

TEST(MathQuat, RotateMatchesQuaternionMatrixAndIgnoresScale) {
  EXPECT_LT(max_diff(nat::quat_rotate(nat::quat_angle_axis(kPi / 2, Vector3d::UnitZ()), Vector3d(1, 0, 0)),
                     Vector3d(0, 1, 0)),
            kTol);
  EXPECT_LT(max_diff(nat::quat_rotate(nat::quat_angle_axis(kPi / 2, Vector3d::UnitX()), Vector3d(0, 2, 0)),
                     Vector3d(0, 0, 2)),
            kTol);
  Rng rng;
  for (int i = 0; i < 50; ++i) {
    const Quaterniond q = rng.quat();
    const Vector3d v = rng.vec();
    EXPECT_LT(max_diff(nat::quat_rotate(q, v), matrix_of(q) * v), kTol);
    // q·v·q⁻¹ is invariant under scaling q.
    EXPECT_LT(max_diff(nat::quat_rotate(Quaterniond(3.5 * q.coeffs()), v), matrix_of(q) * v), kTol);
  }
  EXPECT_EQ(nat::quat_rotate(nat::quat_from_xyzw(0, 0, 0, 0), Vector3d(1, 2, 3)), Vector3d(1, 2, 3));
}

TEST(MathQuat, ConjAndInverseHandValues) {
  const Quaterniond q = nat::quat_from_xyzw(1, 2, 3, 4);
  EXPECT_EQ(nat::quat_to_xyzw(nat::quat_conj(q)), (std::array<double, 4>{-1, -2, -3, 4}));
  const auto inv = nat::quat_to_xyzw(nat::quat_inverse(q));  // |q|² = 30
  const double expected[] = {-1.0 / 30, -2.0 / 30, -3.0 / 30, 4.0 / 30};
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(inv[i], expected[i], 1e-16);
  // Hamilton product q·q⁻¹ = 1.
  EXPECT_LT(max_diff((q * nat::quat_inverse(q)).coeffs(), Quaterniond::Identity().coeffs()), kTol);
  // For a unit quaternion the inverse is the conjugate.
  const Quaterniond u = nat::quat_angle_axis(0.7, Vector3d(1, -1, 2));
  EXPECT_LT(max_diff(nat::quat_inverse(u).coeffs(), nat::quat_conj(u).coeffs()), kTol);
  EXPECT_EQ(nat::quat_to_xyzw(nat::quat_inverse(nat::quat_from_xyzw(0, 0, 0, 0))),
            (std::array<double, 4>{0, 0, 0, 0}));
}

// ---- from_to -----------------------------------------------------------------------------------------

TEST(MathQuat, FromToMapsDirectionWithMinimalAngle) {
  Rng rng;
  for (int i = 0; i < 300; ++i) {
    const Vector3d from = rng.vec(rng(0.01, 100));
    const Vector3d to = rng.vec(rng(0.01, 100));
    const Quaterniond q = nat::quat_from_to(from, to);
    EXPECT_NEAR(q.norm(), 1.0, kTol);
    EXPECT_LT(max_diff(matrix_of(q) * from.normalized(), to.normalized()), kTol);
    // Every rotation taking a to b turns by at least acos(a·b); equality means minimal. acos has slope
    // 1/sin near ±1, so the reference itself carries ~1e-16/sin error: 1e-9 covers random pairs.
    const double dot = std::clamp(from.normalized().dot(to.normalized()), -1.0, 1.0);
    EXPECT_NEAR(rotation_angle(q), std::acos(dot), 1e-9);
    // The minimal rotation turns about from × to (right-handed, so w >= 0 with a positive axis).
    const Vector3d axis = from.cross(to).normalized();
    EXPECT_LT(max_diff(q.vec().normalized(), axis * (q.w() >= 0 ? 1 : -1)), 1e-9);
  }
}

TEST(MathQuat, FromToParallelIsIdentity) {
  const Quaterniond q = nat::quat_from_to(Vector3d(1, 2, 3), Vector3d(2, 4, 6));
  EXPECT_LT(max_diff(q.coeffs(), Quaterniond::Identity().coeffs()), 1e-15);
  EXPECT_EQ(nat::quat_to_xyzw(nat::quat_from_to(Vector3d(0, 0, 4), Vector3d(0, 0, 1))),
            (std::array<double, 4>{0, 0, 0, 1}));
  // A zero vector has no direction: identity.
  EXPECT_EQ(nat::quat_to_xyzw(nat::quat_from_to(Vector3d::Zero(), Vector3d(1, 0, 0))),
            (std::array<double, 4>{0, 0, 0, 1}));
}

TEST(MathQuat, FromToAntiparallelIsHalfTurnAboutOrthogonalUnitVector) {
  // orthogonal_unit_vector((1,2,3)) = (1,2,3) × X / |..| = (0,3,-2)/√13 by hand.
  const Quaterniond q = nat::quat_from_to(Vector3d(1, 2, 3), Vector3d(-1, -2, -3));
  const double s = std::sqrt(13.0);
  EXPECT_LT(quat_diff_up_to_sign(q, Quaterniond(0, 0, 3 / s, -2 / s)), 1e-15);
  EXPECT_LT(max_diff(matrix_of(q) * Vector3d(1, 2, 3), Vector3d(-1, -2, -3)), kTol);
  // X -> -X: orthogonal_unit_vector(X) = X × Y = Z, so a half turn about Z.
  EXPECT_LT(
      quat_diff_up_to_sign(nat::quat_from_to(Vector3d(2, 0, 0), Vector3d(-1, 0, 0)), Quaterniond(0, 0, 0, 1)),
      1e-15);
}

TEST(MathQuat, FromToNearlyAntiparallelStaysAccurate) {
  const Vector3d a = Vector3d(1, 2, 3).normalized();
  const Vector3d perp = Vector3d(0, 3, -2).normalized();
  for (double eps : {1e-3, 1e-7, 1e-10, 1e-13}) {
    const Vector3d b = (-a + eps * perp).normalized();
    const Quaterniond q = nat::quat_from_to(a, b);
    EXPECT_LT(max_diff(matrix_of(q) * a, b), kTol) << eps;
    EXPECT_NEAR(rotation_angle(q), kPi - std::atan(eps), kTol) << eps;
  }
  for (double eps : {1e-7, 1e-13}) {
    const Vector3d b = (a + eps * perp).normalized();
    EXPECT_LT(max_diff(matrix_of(nat::quat_from_to(a, b)) * a, b), kTol) << eps;
  }
}

// ---- Euler -------------------------------------------------------------------------------------------

TEST(MathEuler, ListsAll24Conventions) {
  const auto list = nat::euler_conventions();
  const std::set<std::string> expected = {"xyzs", "xyxs", "xzys", "xzxs", "yzxs", "yzys", "yxzs", "yxys",
                                          "zxys", "zxzs", "zyxs", "zyzs", "xyzr", "xyxr", "xzyr", "xzxr",
                                          "yzxr", "yzyr", "yxzr", "yxyr", "zxyr", "zxzr", "zyxr", "zyzr"};
  EXPECT_EQ(list.size(), 24u);
  EXPECT_EQ(std::set<std::string>(list.begin(), list.end()), expected);
  for (std::string_view name : list) EXPECT_TRUE(nat::quat_from_euler(name, 0.1, 0.2, 0.3)) << name;
}

TEST(MathEuler, MatchesElementaryRotationMatrixProducts) {
  const double triples[][3] = {
      {0.1, 0.2, 0.3}, {-1.2, 0.7, 2.9}, {kPi / 2, kPi / 2, 0}, {3.0, -2.5, 1.0}, {0, 0, kPi}};
  for (std::string_view name : nat::euler_conventions()) {
    for (const auto& t : triples) {
      const Matrix3d ri = rot_about(name[0], t[0]);
      const Matrix3d rj = rot_about(name[1], t[1]);
      const Matrix3d rk = rot_about(name[2], t[2]);
      const Matrix3d expected = name[3] == 's' ? Matrix3d(rk * rj * ri) : Matrix3d(ri * rj * rk);
      const auto q = nat::quat_from_euler(name, t[0], t[1], t[2]);
      ASSERT_TRUE(q) << name;
      EXPECT_NEAR(q->norm(), 1.0, kTol);
      EXPECT_LT(max_diff(matrix_of(*q), expected), kTol) << name << " " << t[0] << " " << t[1] << " " << t[2];
    }
  }
}

TEST(MathEuler, StaticEqualsReversedRotating) {
  for (std::string_view name : nat::euler_conventions()) {
    if (name[3] != 's') continue;
    const std::string reversed = {name[2], name[1], name[0], 'r'};
    const auto s = nat::quat_from_euler(name, 0.4, -1.1, 2.2);
    const auto r = nat::quat_from_euler(reversed, 2.2, -1.1, 0.4);
    ASSERT_TRUE(s && r) << name;
    EXPECT_LT(quat_diff_up_to_sign(*s, *r), kTol) << name;
  }
}

TEST(MathEuler, HandExamplesDistinguishStaticFromRotating) {
  // Static xyz: 90° about X takes Y to Z, then 90° about the fixed Y takes Z to X.
  const auto s = nat::quat_from_euler("xyzs", kPi / 2, kPi / 2, 0);
  EXPECT_LT(max_diff(nat::quat_rotate(*s, Vector3d::UnitY()), Vector3d::UnitX()), kTol);
  // Rotating xyz: R = Rx(90)·Ry(90); Ry leaves Y alone, then Rx takes Y to Z.
  const auto r = nat::quat_from_euler("xyzr", kPi / 2, kPi / 2, 0);
  EXPECT_LT(max_diff(nat::quat_rotate(*r, Vector3d::UnitY()), Vector3d::UnitZ()), kTol);
  // Aerospace yaw only: zyxr(90°, 0, 0) takes X to Y.
  const auto yaw = nat::quat_from_euler("zyxr", kPi / 2, 0, 0);
  EXPECT_LT(max_diff(nat::quat_rotate(*yaw, Vector3d::UnitX()), Vector3d::UnitY()), kTol);
}

TEST(MathEuler, UnknownConventionIsNullopt) {
  for (std::string_view bad : {"", "xyz", "xxys", "xyys", "XYZs", "xyzq", "xyzss", "wxyr"})
    EXPECT_FALSE(nat::quat_from_euler(bad, 0.1, 0.2, 0.3)) << bad;
}

// ---- Vec3 --------------------------------------------------------------------------------------------

TEST(MathVec3, OrthogonalUnitVectorHandValues) {
  EXPECT_EQ(nat::orthogonal_unit_vector(Vector3d(0, 0, 1)), Vector3d(0, 1, 0));
  EXPECT_EQ(nat::orthogonal_unit_vector(Vector3d(1, 0, 0)), Vector3d(0, 0, 1));
  EXPECT_EQ(nat::orthogonal_unit_vector(Vector3d(0, 1, 0)), Vector3d(0, 0, -1));
  EXPECT_EQ(nat::orthogonal_unit_vector(Vector3d(0, 0, -5)), Vector3d(0, -1, 0));
  // Three-way tie picks X: (1,1,1) × X = (0,1,-1).
  EXPECT_LT(max_diff(nat::orthogonal_unit_vector(Vector3d(1, 1, 1)), Vector3d(0, 1, -1) / std::sqrt(2.0)),
            1e-15);
  // Smallest component y: (3,-1,2) × Y = (-2,0,3).
  EXPECT_LT(max_diff(nat::orthogonal_unit_vector(Vector3d(3, -1, 2)), Vector3d(-2, 0, 3) / std::sqrt(13.0)),
            1e-15);
  EXPECT_EQ(nat::orthogonal_unit_vector(Vector3d::Zero()), Vector3d(1, 0, 0));
  // Extreme magnitudes do not under/overflow.
  EXPECT_EQ(nat::orthogonal_unit_vector(Vector3d(0, 0, 1e-310)), Vector3d(0, 1, 0));
  EXPECT_EQ(nat::orthogonal_unit_vector(Vector3d(0, 0, 1e300)), Vector3d(0, 1, 0));
}

TEST(MathVec3, OrthogonalUnitVectorIsUnitAndOrthogonal) {
  Rng rng;
  for (int i = 0; i < 200; ++i) {
    const Vector3d v = rng.vec(rng(1e-3, 1e3));
    const Vector3d u = nat::orthogonal_unit_vector(v);
    EXPECT_NEAR(u.norm(), 1.0, 1e-15);
    EXPECT_LT(std::abs(u.dot(v)) / v.norm(), 1e-15);
  }
}

TEST(MathVec3, AngleBetweenVectorsSigns) {
  const Vector3d x = Vector3d::UnitX(), y = Vector3d::UnitY(), z = Vector3d::UnitZ();
  EXPECT_NEAR(nat::angle_between_vectors(x, y, z), kPi / 2, kTol);
  EXPECT_NEAR(nat::angle_between_vectors(x, y, -z), -kPi / 2, kTol);
  EXPECT_NEAR(nat::angle_between_vectors(3 * x, 0.5 * y, 7 * z), kPi / 2, kTol);  // lengths do not matter
  EXPECT_NEAR(nat::angle_between_vectors(x, Vector3d(1, -1, 0), z), -kPi / 4, kTol);
  EXPECT_NEAR(nat::angle_between_vectors(Vector3d(2, 0, 0), Vector3d(0, 0, 3), -y), kPi / 2,
              kTol);  // X×Z = -Y
  EXPECT_EQ(nat::angle_between_vectors(x, x, z), 0.0);
  EXPECT_EQ(nat::angle_between_vectors(x, -x, z), kPi);
  // Just short of the boundary from below stays negative.
  EXPECT_NEAR(nat::angle_between_vectors(x, Vector3d(-1, -1e-3, 0), z), -(kPi - std::atan(1e-3)), kTol);
  // Zero rot: unsigned angle. Zero vector: 0.
  EXPECT_NEAR(nat::angle_between_vectors(x, Vector3d(1, -1, 0), Vector3d::Zero()), kPi / 4, kTol);
  EXPECT_EQ(nat::angle_between_vectors(Vector3d::Zero(), y, z), 0.0);
}

TEST(MathVec3, AngleBetweenVectorsReportsPiNotMinusPi) {
  // Signed zeros chosen so the raw formula gives atan2(-0.0, -1) = -pi: cross(-X, X) = (0, 0, -0) and
  // rot = (-0, -0, 1) make every product of the dot -0.
  const Vector3d v1(-1, 0, 0), v2(1, 0, 0), rot(-0.0, -0.0, 1);
  const double raw = std::atan2(v1.cross(v2).dot(rot), v1.dot(v2));
  ASSERT_EQ(raw, -kPi);  // the case really is on the boundary
  EXPECT_EQ(nat::angle_between_vectors(v1, v2, rot), kPi);
}

TEST(MathVec3, AngleBetweenVectorsRecoversRodriguesAngle) {
  Rng rng;
  for (int i = 0; i < 200; ++i) {
    const Vector3d v1 = rng.vec();
    Vector3d n = rng.vec();
    n = (n - n.dot(v1) / v1.squaredNorm() * v1).normalized();  // rot normal to the plane of v1, v2
    const double theta = rng(-kPi + 1e-6, kPi);
    const Vector3d v2 = rng(0.1, 10) * (rodrigues(theta, n) * v1);
    EXPECT_NEAR(nat::angle_between_vectors(v1, v2, rng(0.1, 10) * n), theta, kTol);
  }
}

// ---- AffineTransform ---------------------------------------------------------------------------------

TEST(MathAffine, ComposeMatchesHomogeneousProduct) {
  const nat::Affine turn{Vector3d(1, 0, 0), nat::quat_angle_axis(kPi / 2, Vector3d::UnitZ())};
  const nat::Affine shift{Vector3d(0, 1, 0), Quaterniond::Identity()};
  // turn∘shift: shift first, then the turn maps (0,1,0) to (-1,0,0), then +(1,0,0).
  EXPECT_LT(max_diff(nat::affine_compose(turn, shift).position, Vector3d(0, 0, 0)), kTol);
  EXPECT_LT(max_diff(nat::affine_compose(shift, turn).position, Vector3d(1, 1, 0)), kTol);
  Rng rng;
  for (int i = 0; i < 50; ++i) {
    const nat::Affine a{rng.vec(), rng.quat()}, b{rng.vec(), rng.quat()};
    EXPECT_LT(max_diff(homogeneous(nat::affine_compose(a, b)), homogeneous(a) * homogeneous(b)), kTol);
  }
}

TEST(MathAffine, InverseMatchesMatrixInverse) {
  Rng rng;
  for (int i = 0; i < 50; ++i) {
    const nat::Affine a{rng.vec(), rng.quat()};
    const Matrix4d expected = homogeneous(a).inverse();
    EXPECT_LT(max_diff(homogeneous(nat::affine_inverse(a)), expected), kTol);
    EXPECT_LT(max_diff(homogeneous(nat::affine_inverse_of(a.position, a.rotation)), expected), kTol);
    EXPECT_LT(max_diff(homogeneous(nat::affine_compose(a, nat::affine_inverse(a))), Matrix4d::Identity()),
              kTol);
  }
  // Hand value: the inverse of "turn 90° about Z, then move by (1,2,3)".
  const nat::Affine inv =
      nat::affine_inverse_of(Vector3d(1, 2, 3), nat::quat_angle_axis(kPi / 2, Vector3d::UnitZ()));
  EXPECT_LT(max_diff(inv.position, Vector3d(-2, 1, -3)), kTol);
  EXPECT_LT(max_diff(nat::affine_transform_point(inv, Vector3d(1, 3, 3)), Vector3d(1, 0, 0)), kTol);
}

TEST(MathAffine, TransformPointAndVector) {
  const nat::Affine a{Vector3d(1, 2, 3), nat::quat_angle_axis(kPi / 2, Vector3d::UnitZ())};
  EXPECT_LT(max_diff(nat::affine_transform_point(a, Vector3d::UnitX()), Vector3d(1, 3, 3)), kTol);
  EXPECT_LT(max_diff(nat::affine_transform_vector(a, Vector3d::UnitX()), Vector3d(0, 1, 0)), kTol);
  Rng rng;
  for (int i = 0; i < 50; ++i) {
    const nat::Affine b{rng.vec(), rng.quat()};
    const Vector3d v = rng.vec();
    const Eigen::Vector4d point = homogeneous(b) * Eigen::Vector4d(v.x(), v.y(), v.z(), 1);
    const Eigen::Vector4d vector = homogeneous(b) * Eigen::Vector4d(v.x(), v.y(), v.z(), 0);
    EXPECT_LT(max_diff(nat::affine_transform_point(b, v), Vector3d(point.head<3>())), kTol);
    EXPECT_LT(max_diff(nat::affine_transform_vector(b, v), Vector3d(vector.head<3>())), kTol);
  }
}

TEST(MathAffine, FromAxesHandValues) {
  // Z -> X and X -> Y, so Y -> Z × X of the new frame = X × Y = Z.
  const auto a = nat::affine_from_axes(Vector3d(2, 0, 0), Vector3d(0, 3, 0), Vector3d(1, 2, 3));
  ASSERT_TRUE(a);
  Matrix3d expected;
  expected << 0, 0, 1, 1, 0, 0, 0, 1, 0;  // columns: images of X, Y, Z
  EXPECT_LT(max_diff(matrix_of(a->rotation), expected), kTol);
  EXPECT_EQ(a->position, Vector3d(1, 2, 3));
  // new_x is made orthogonal to new_z: (1,0,5) about Z keeps X, so identity.
  const auto b = nat::affine_from_axes(Vector3d(0, 0, 1), Vector3d(1, 0, 5), Vector3d::Zero());
  ASSERT_TRUE(b);
  EXPECT_LT(max_diff(matrix_of(b->rotation), Matrix3d::Identity()), kTol);
}

TEST(MathAffine, FromAxesMapsZAndXAsDocumented) {
  Rng rng;
  for (int i = 0; i < 100; ++i) {
    const Vector3d nz = rng.vec(), nx = rng.vec(), p = rng.vec();
    const auto a = nat::affine_from_axes(nz, nx, p);
    ASSERT_TRUE(a);
    const Vector3d z = nz.normalized();
    const Vector3d x = (nx - nx.dot(z) * z).normalized();
    const Matrix3d r = matrix_of(a->rotation);
    EXPECT_LT(max_diff(Vector3d(r * Vector3d::UnitZ()), z), kTol);
    EXPECT_LT(max_diff(Vector3d(r * Vector3d::UnitX()), x), kTol);
    EXPECT_LT(max_diff(Vector3d(r * Vector3d::UnitY()), z.cross(x)), kTol);
    EXPECT_EQ(a->position, p);
  }
}

TEST(MathAffine, FromAxesNearlyParallelXKeepsFrameOrthonormal) {
  // new_x = z + 1e-9·perp: its orthogonal part is tiny. One Gram-Schmidt pass would leave ~1e-7 of z in X
  // and the quaternion of that skewed frame would miss Z by ~5e-8; the second pass keeps Z exact.
  const Vector3d z = Vector3d(1, 2, 3).normalized();
  const Vector3d perp = Vector3d(0, 3, -2).normalized();
  const auto a = nat::affine_from_axes(z, z + 1e-9 * perp, Vector3d::Zero());
  ASSERT_TRUE(a);
  const Matrix3d r = matrix_of(a->rotation);
  EXPECT_LT(max_diff(Vector3d(r * Vector3d::UnitZ()), z), kTol);
  // X itself is ill-conditioned: rounding z (1e-16) turns a 1e-9 orthogonal part by ~1e-7, hence 1e-6.
  EXPECT_LT(max_diff(Vector3d(r * Vector3d::UnitX()), perp), 1e-6);
}

TEST(MathAffine, FromAxesRejectsDegenerateAxes) {
  EXPECT_FALSE(nat::affine_from_axes(Vector3d::Zero(), Vector3d::UnitX(), Vector3d::Zero()));
  EXPECT_FALSE(nat::affine_from_axes(Vector3d::UnitZ(), Vector3d::Zero(), Vector3d::Zero()));
  EXPECT_FALSE(nat::affine_from_axes(Vector3d(1, 2, 3), Vector3d(2, 4, 6), Vector3d::Zero()));
  EXPECT_FALSE(nat::affine_from_axes(Vector3d(1, 2, 3), Vector3d(-1, -2, -3), Vector3d::Zero()));
}

TEST(MathAffine, FromAxesAgreesWithSnapQuaternionConstruction) {
  // snap.md §2.2: q1 = from_to(Z, m), x' = q1·X, phi = angle_between_vectors(x', n, m), q = angle_axis(phi,
  // m)·q1.
  Rng rng;
  for (int i = 0; i < 100; ++i) {
    const Vector3d m = rng.vec().normalized();
    Vector3d n = rng.vec();
    n = (n - n.dot(m) * m).normalized();
    const Quaterniond q1 = nat::quat_from_to(Vector3d::UnitZ(), m);
    const double phi = nat::angle_between_vectors(nat::quat_rotate(q1, Vector3d::UnitX()), n, m);
    const Quaterniond q = nat::quat_angle_axis(phi, m) * q1;
    const auto a = nat::affine_from_axes(m, n, Vector3d::Zero());
    ASSERT_TRUE(a);
    EXPECT_LT(max_diff(matrix_of(a->rotation), matrix_of(q)), kTol);
  }
}

}  // namespace
