// Conversions the SimulationState files share: a binding's MuJoCo object type, a value type's words and
// size, and three mjtNum as a vector.
#pragma once

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <cstddef>
#include <string_view>

#include "contract/signal_binding.h"
#include "openplx/runtime/signals.h"

namespace openplx::runtime {

inline mjtObj object_type(mjcf::MjObject object) {
  switch (object) {
    case mjcf::MjObject::Actuator:
      return mjOBJ_ACTUATOR;
    case mjcf::MjObject::Joint:
      return mjOBJ_JOINT;
    case mjcf::MjObject::Body:
      return mjOBJ_BODY;
    case mjcf::MjObject::Site:
      return mjOBJ_SITE;
    case mjcf::MjObject::Equality:
      return mjOBJ_EQUALITY;
    case mjcf::MjObject::Tendon:
      return mjOBJ_TENDON;
    case mjcf::MjObject::Sensor:
      return mjOBJ_SENSOR;
    case mjcf::MjObject::None:
      break;
  }
  return mjOBJ_UNKNOWN;
}

inline std::string_view type_name(ValueType type) {
  switch (type) {
    case ValueType::Real:
      return "a Real";
    case ValueType::Bool:
      return "a Bool";
    case ValueType::Int:
      return "an Int";
    case ValueType::Vec2:
      return "a Vec2";
    case ValueType::Vec3:
      return "a Vec3";
    case ValueType::Vector:
      return "a vector";
  }
  return "a value";
}

inline size_t value_count(ValueType type) {
  return type == ValueType::Vec2 ? 2 : type == ValueType::Vec3 ? 3 : 1;
}

inline Eigen::Vector3d vec(const mjtNum* v) {
  return {v[0], v[1], v[2]};
}

}  // namespace openplx::runtime
