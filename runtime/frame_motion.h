// The motion of a frame (a site or a body frame) in world axes, and the same seen from a reference frame
// (a connector output's `relative_to`). One definition for the runtime's reads; MuJoCo's frame sensors with
// reftype="site" compute the position, orientation and velocities the same way.
#pragma once

#include <Eigen/Core>

namespace openplx::runtime {

struct FrameMotion {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();                               // origin, world
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();                           // world from frame
  Eigen::Vector3d v = Eigen::Vector3d::Zero(), w = Eigen::Vector3d::Zero();  // velocity, angular velocity
  Eigen::Vector3d a = Eigen::Vector3d::Zero();      // coordinate acceleration d2p/dt2 (gravity not included)
  Eigen::Vector3d alpha = Eigen::Vector3d::Zero();  // angular acceleration
};

// x = R_r^T (p - p_r): the frame's origin in the reference's axes.
inline Eigen::Vector3d relative_position(const FrameMotion& f, const FrameMotion& r) {
  return r.R.transpose() * (f.p - r.p);
}
inline Eigen::Matrix3d relative_rotation(const FrameMotion& f, const FrameMotion& r) {
  return r.R.transpose() * f.R;
}
// dx/dt, with dR_r/dt = [w_r]x R_r.
inline Eigen::Vector3d relative_linear_velocity(const FrameMotion& f, const FrameMotion& r) {
  return r.R.transpose() * (f.v - r.v - r.w.cross(f.p - r.p));
}
inline Eigen::Vector3d relative_angular_velocity(const FrameMotion& f, const FrameMotion& r) {
  return r.R.transpose() * (f.w - r.w);
}
// d2x/dt2: differentiating R_r^T (dr - w_r x r) once more gives
// R_r^T (d2r - alpha_r x r - 2 w_r x dr + w_r x (w_r x r)), r = p - p_r.
inline Eigen::Vector3d relative_linear_acceleration(const FrameMotion& f, const FrameMotion& r) {
  const Eigen::Vector3d d = f.p - r.p, dv = f.v - r.v;
  return r.R.transpose() * (f.a - r.a - r.alpha.cross(d) - 2.0 * r.w.cross(dv) + r.w.cross(r.w.cross(d)));
}
// The derivative of R_r^T (w - w_r): R_r^T (alpha - alpha_r - w_r x w).
inline Eigen::Vector3d relative_angular_acceleration(const FrameMotion& f, const FrameMotion& r) {
  return r.R.transpose() * (f.alpha - r.alpha - r.w.cross(f.w));
}

}  // namespace openplx::runtime
