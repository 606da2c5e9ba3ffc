// MuJoCo 2.2.2's principal moments of an inertia tensor, to the last bit, and the rule its compiler accepts
// them by. MuJoCo diagonalises `fullinertia` (and a URDF <inertia>) with a Jacobi iteration of its own
// (mju_eig3), then refuses any permutation with A + B < C, exactly, with no tolerance (unless
// `balanceinertia`). A check that uses another eigen solver, or a tolerance, disagrees with it on tensors at
// the edge (a flat plate, A + B == C up to rounding): it passes a tensor MuJoCo then refuses. So the emitter
// and the URDF importer run the same iteration on the same numbers; tests/urdf/mujoco_inertia_test.cpp
// compares it with libmujoco's mju_eig3 bit for bit. Header only: the URDF importer module and the emitter
// both use it. (Floating-point contraction must stay off, as it is in our x86-64 builds without -march.)
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>

namespace openplx::mujoco_inertia {

using Quat = std::array<double, 4>;  // w, x, y, z

struct Principal {
  std::array<double, 3> moments;  // in MuJoCo's order (decreasing, equal ones left in place)
  Quat axes;                      // rotation from the principal frame to the tensor's frame
};

namespace detail {

inline constexpr double kTolerance = 1e-12;  // MuJoCo's eigEPS (1000 mjMINVAL)

// Row-major rotation matrix of a unit quaternion; the identity quaternion gives the identity exactly.
inline void rotation(const Quat& q, double m[9]) {
  if (q[0] == 1 && q[1] == 0 && q[2] == 0 && q[3] == 0) {
    for (int i = 0; i < 9; ++i) m[i] = i % 4 == 0 ? 1 : 0;
    return;
  }
  const double ww = q[0] * q[0], wx = q[0] * q[1], wy = q[0] * q[2], wz = q[0] * q[3];
  const double xx = q[1] * q[1], xy = q[1] * q[2], xz = q[1] * q[3];
  const double yy = q[2] * q[2], yz = q[2] * q[3], zz = q[3] * q[3];
  m[0] = ww + xx - yy - zz;
  m[4] = ww - xx + yy - zz;
  m[8] = ww - xx - yy + zz;
  m[1] = 2 * (xy - wz);
  m[2] = 2 * (xz + wy);
  m[3] = 2 * (xy + wz);
  m[5] = 2 * (yz - wx);
  m[6] = 2 * (xz - wy);
  m[7] = 2 * (yz + wx);
}

// a = a * b (Hamilton product).
inline void multiply(Quat& a, const Quat& b) {
  const Quat r{a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
               a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
               a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
               a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
  a = r;
}

inline void normalize(Quat& q) {
  const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (norm < 1e-15) {
    q = {1, 0, 0, 0};
    return;
  }
  const double inverse = 1 / norm;
  for (double& c : q) c *= inverse;
}

// Row-major 3x3 products, summed in index order as MuJoCo's loops sum them (terms whose left factor is 0
// skipped, which changes nothing).
inline void transpose_times(double out[9], const double a[9], const double b[9]) {  // out = a' b
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) {
      double sum = 0;
      for (int j = 0; j < 3; ++j)
        if (a[3 * j + i] != 0) sum += a[3 * j + i] * b[3 * j + k];
      out[3 * i + k] = sum;
    }
}
inline void times(double out[9], const double a[9], const double b[9]) {  // out = a b
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) {
      double sum = 0;
      for (int j = 0; j < 3; ++j)
        if (a[3 * i + j] != 0) sum += a[3 * i + j] * b[3 * j + k];
      out[3 * i + k] = sum;
    }
}

}  // namespace detail

// The principal moments MuJoCo 2.2.2 finds for the symmetric tensor with these moments and products, as
// `fullinertia="xx yy zz xy xz yz"` gives them: Jacobi rotations about the axis of the largest off-diagonal
// entry, accumulated in a quaternion, until that entry or the rotation is negligible; then a three-step
// bubble sort into decreasing order that swaps only values further apart than the tolerance.
inline Principal principal_moments(double xx, double yy, double zz, double xy, double xz, double yz) {
  using namespace detail;
  const double tensor[9] = {xx, xy, xz, xy, yy, yz, xz, yz, zz};
  Principal p{{0, 0, 0}, {1, 0, 0, 0}};
  Quat& q = p.axes;
  double axes[9], half[9], d[9];
  for (int iteration = 0; iteration < 500; ++iteration) {
    rotation(q, axes);
    transpose_times(half, axes, tensor);
    times(d, half, axes);
    p.moments = {d[0], d[4], d[8]};
    int row = 1, column = 2, about = 0;
    if (std::abs(d[1]) > std::abs(d[2]) && std::abs(d[1]) > std::abs(d[5])) {
      row = 0, column = 1, about = 2;
    } else if (std::abs(d[2]) > std::abs(d[5])) {
      row = 0, column = 2, about = 1;
    }
    const double off = d[3 * row + column];
    if (std::abs(off) < kTolerance) break;
    const double tau = (d[4 * column] - d[4 * row]) / (2 * off);
    const double t =
        tau >= 0 ? 1.0 / (tau + std::sqrt(1 + tau * tau)) : -1.0 / (-tau + std::sqrt(1 + tau * tau));
    const double c = 1.0 / std::sqrt(1 + t * t);
    if (c > 1.0 - kTolerance) break;
    Quat turn{0, 0, 0, 0};
    const double s = std::sqrt(0.5 - 0.5 * c);
    turn[about + 1] = tau >= 0 ? -s : s;
    if (about == 1) turn[about + 1] = -turn[about + 1];
    turn[0] = std::sqrt(1.0 - turn[about + 1] * turn[about + 1]);
    normalize(turn);
    multiply(q, turn);
    normalize(q);
  }
  for (int step = 0; step < 3; ++step) {
    const int lead = step % 2;
    if (p.moments[lead] + kTolerance < p.moments[lead + 1]) {
      std::swap(p.moments[lead], p.moments[lead + 1]);
      Quat quarter{0.707106781186548, 0, 0, 0};
      quarter[(lead + 2) % 3 + 1] = quarter[0];
      multiply(q, quarter);
      normalize(q);
    }
  }
  return p;
}

// The tensor's upper triangle as MJCF's fullinertia carries it.
inline Principal principal_moments(const Eigen::Matrix3d& t) {
  return principal_moments(t(0, 0), t(1, 1), t(2, 2), t(0, 1), t(0, 2), t(1, 2));
}

// MuJoCo 2.2.2's compiler takes principal moments that are not negative and in which no moment exceeds
// the sum of the other two (A + B >= C for every permutation, compared exactly).
inline bool negative(const std::array<double, 3>& m) {
  return m[0] < 0 || m[1] < 0 || m[2] < 0;
}
inline bool triangle(const std::array<double, 3>& m) {
  return !(m[0] + m[1] < m[2] || m[0] + m[2] < m[1] || m[1] + m[2] < m[0]);
}

}  // namespace openplx::mujoco_inertia
