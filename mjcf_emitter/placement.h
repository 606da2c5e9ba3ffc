// `--pose`: an emitted model moved as a whole to a pose in a bigger scene. MuJoCo 2.2.2 has no <frame> and
// allows free joints only in bodies that hang from the world, so the model cannot be wrapped in a body of its
// own; instead everything given in world coordinates moves: the world's top-level bodies (free, jointed,
// static and mocap alike), its geoms, sites, cameras and lights, equality anchors given in the world frame,
// free joints' velocities in keyframes and <statistic center>.
#pragma once

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <string_view>

#include "mjcf_emitter/xml.h"

namespace openplx::mjcf {

struct Placement {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
};

// "x y z" or "x y z qw qx qy qz" (spaces or commas; the quaternion is normalized). nullopt with `error`
// when it is neither.
std::optional<Placement> parse_placement(std::string_view text, std::string& error);

// Moves the model in `mujoco` (a whole emitted document) by `placement`.
void place_model(Element& mujoco, const Placement& placement);

}  // namespace openplx::mjcf
