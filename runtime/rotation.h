// Roll, pitch and yaw of MuJoCo orientations: R = Rz(yaw) Ry(pitch) Rx(roll) (static x-y-z axes), the
// convention of OpenPLX's RPY outputs.
#pragma once

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

namespace openplx::runtime {

// `r`: a row-major 3x3 rotation matrix (MuJoCo's xmat layout).
inline Eigen::Vector3d rpy_from_matrix(const mjtNum* r) {
  const double pitch = std::asin(std::clamp(-r[6], -1.0, 1.0));
  return {std::atan2(r[7], r[8]), pitch, std::atan2(r[3], r[0])};
}

// `q`: a unit quaternion w, x, y, z.
inline Eigen::Vector3d rpy_from_quat(const mjtNum* q) {
  mjtNum r[9];
  mju_quat2Mat(r, q);
  return rpy_from_matrix(r);
}

}  // namespace openplx::runtime
