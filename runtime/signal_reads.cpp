// Reading an output: from the MuJoCo data (or what a step kept) into the caller's values.
#include <Eigen/Geometry>
#include <string>

#include "contract/steering_linkage.h"
#include "mujoco_support/mujoco_compat.h"
#include "runtime/rotation.h"
#include "runtime/sensor_noise.h"
#include "runtime/signal_conversions.h"
#include "runtime/simulation_state.h"

namespace openplx::runtime {

using mjcf::MjObject;
using mjcf::Quantity;

namespace {

// World velocities of a point fixed in body `b`. MuJoCo's cvel holds (angular, linear) with the linear part
// taken at the subtree centre of mass of b's root; moving it to the point is one cross product (cheaper than
// mj_objectVelocity, which also rotates into a local frame).
Eigen::Vector3d angular_velocity(const mjData* d, int b) {
  return vec(d->cvel + 6 * b);
}
Eigen::Vector3d linear_velocity(const mjModel* m, const mjData* d, int b, const mjtNum* point) {
  const Eigen::Vector3d w = vec(d->cvel + 6 * b), v = vec(d->cvel + 6 * b + 3);
  const Eigen::Vector3d c = vec(d->subtree_com + 3 * m->body_rootid[b]);
  return v + w.cross(vec(point) - c);
}

}  // namespace

// MuJoCo gives mocap bodies (and so everything hanging from them) no velocity of their own: a point of body
// b adds the rigid motion of the kinematic body at the root of b's tree, as its velocity inputs set it.
Eigen::Vector3d SimulationState::carried_linear(int b, const mjtNum* point) const {
  const int root = m->body_rootid[b], k = m->body_mocapid[root];
  if (k < 0) return Eigen::Vector3d::Zero();
  const size_t at = static_cast<size_t>(k);
  return kinematic_linear[at] + kinematic_angular[at].cross(vec(point) - vec(d->xpos + 3 * root));
}

Eigen::Vector3d SimulationState::carried_angular(int b) const {
  const int k = m->body_mocapid[m->body_rootid[b]];
  return k < 0 ? Eigen::Vector3d::Zero() : kinematic_angular[static_cast<size_t>(k)];
}

FrameMotion SimulationState::motion(int id, bool body, bool acceleration) const {
  FrameMotion f;
  const int b = body ? id : m->site_bodyid[id];
  const mjtNum* p = body ? d->xpos + 3 * id : d->site_xpos + 3 * id;
  f.p = vec(p);
  f.R = Eigen::Map<const Eigen::Matrix<mjtNum, 3, 3, Eigen::RowMajor>>(body ? d->xmat + 9 * id
                                                                            : d->site_xmat + 9 * id);
  f.v = linear_velocity(m, d, b, p) + carried_linear(b, p);
  f.w = angular_velocity(d, b) + carried_angular(b);
  if (acceleration) {
    // MuJoCo's own (framelinacc's) proper acceleration; adding gravity makes it d2p/dt2.
    mjtNum res[6];
    mj_objectAcceleration(m, d, body ? mjOBJ_XBODY : mjOBJ_SITE, id, res, 0);
    f.alpha = vec(res);
    f.a = vec(res + 3);
    if (!(m->opt.disableflags & mjDSBL_GRAVITY)) f.a += vec(m->opt.gravity);
  }
  return f;
}

void SimulationState::read(int index, double* out, int count, ValueType wanted) const {
  const ResolvedSignal& s = signals[static_cast<size_t>(index)];
  const mjcf::SignalBinding& b = s.binding;
  if (b.quantity == Quantity::Affine && wanted == ValueType::Real && !s.parts.empty() && !b.input) {
    read(s.parts.front(), out, 1, ValueType::Real);
    out[0] = b.low * out[0] + b.high;
    return;
  }
  if (b.quantity == Quantity::Composite && wanted == ValueType::Vector) {
    int at = 0;
    for (int p : s.parts) {
      const ValueType part = signals[static_cast<size_t>(p)].info.value;
      const int n = static_cast<int>(value_count(part));
      if (at + n > count) break;
      read(p, out + at, n, part);
      at += n;
    }
    return;
  }
  const bool fits = s.info.value == wanted || (wanted == ValueType::Real && s.info.value == ValueType::Int);
  if (!fits) {
    throw SignalError("output `" + s.info.name + "` is " + std::string(type_name(s.info.value)) + ", not " +
                      std::string(type_name(wanted)));
  }
  if (derived_state_behind && reads_derived_state(b.quantity)) bring_current();
  const int id = s.ids.empty() ? -1 : s.ids.front();
  auto put = [&](const Eigen::Vector3d& v) {
    for (int i = 0; i < count && i < 3; ++i) out[i] = v[i];
  };
  switch (b.quantity) {
    case Quantity::Ctrl:
      out[0] = d->ctrl[id];
      return;
    case Quantity::ForceRange:
    case Quantity::MotorForceRange:
      out[0] = switches.at({object_type(b.object), id}).low;
      out[1] = switches.at({object_type(b.object), id}).high;
      return;
    case Quantity::InteractionEnabled:
      out[0] = switches.at({object_type(b.object), id}).enabled ? 1 : 0;
      return;
    case Quantity::EngagementFraction:
      out[0] = b.high > 0 ? m->tendon_frictionloss[id] / b.high : 0.0;
      return;
    case Quantity::Engaged:
      out[0] = engagements.at(id).engaged ? 1 : 0;
      return;
    case Quantity::TendonVelocity:
      out[0] = d->ten_velocity[id];
      return;
    case Quantity::EqualityActive:
      out[0] = equality_active(m, d, id) ? 1 : 0;
      return;
    case Quantity::JointPosition:
      out[0] = b.sign * (b.low < b.high  // a steering column's output: its input within the reach
                             ? mjcf::steering_input_for(b.initial_vector, d->qpos[s.address], b.low, b.high)
                             : mjcf::steering_polynomial_inverse(b.initial_vector, d->qpos[s.address]));
      return;
    case Quantity::JointVelocity:
      out[0] = b.sign * d->qvel[s.dof];
      return;
    case Quantity::ActuatorForce:  // on the joint: a disabled actuator's gear is 0
      out[0] = d->actuator_force[id] * m->actuator_gear[6 * id];
      return;
    case Quantity::JointLimitForce:
    case Quantity::MotorForce:
    case Quantity::EqualityForce:
    case Quantity::TendonLimitForce:
      out[0] = constraint_forces[static_cast<size_t>(index)];
      return;
    case Quantity::GearRatio:  // a gearbox in neutral has none
      out[0] = equality_active(m, d, id) ? 1.0 / m->eq_data[id * mjNEQDATA + 1] : 0.0;
      return;
    case Quantity::GearSelect:
      out[0] = gearboxes.at(id).gear;
      return;
    case Quantity::DistanceTarget:
      out[0] = m->eq_data[id * mjNEQDATA] + m->tendon_length0[m->eq_obj1id[id]];
      return;
    case Quantity::EqualityTarget: {
      const double held = m->eq_data[id * mjNEQDATA] + m->qpos0[m->jnt_qposadr[m->eq_obj1id[id]]];
      out[0] = b.low < b.high ? mjcf::steering_input_for(b.initial_vector, held, b.low, b.high)
                              : mjcf::steering_polynomial_inverse(b.initial_vector, held);
      return;
    }
    case Quantity::TendonLength:
      out[0] = d->ten_length[id];
      return;
    case Quantity::SensorFields:
      for (size_t k = 0; k < s.ids.size() && k < static_cast<size_t>(count); ++k)
        out[k] = d->sensordata[m->sensor_adr[s.ids[k]] + static_cast<int>(b.initial_vector[k])];
      add_sensor_noise(noise, b, m, s.ids, d->time, out, count);
      return;
    case Quantity::TendonSpringForce:
      out[0] = -(m->tendon_stiffness[id] * (d->ten_length[id] - tendon_rest_length(m, d, id)) +
                 m->tendon_damping[id] * d->ten_velocity[id]);
      return;
    case Quantity::EngageDuration:
    case Quantity::DisengageDuration: {
      auto e = engagements.find(id);
      if (e == engagements.end())
        throw SignalError("output `" + s.info.name + "`: its clutch has no engage input");
      out[0] = b.quantity == Quantity::EngageDuration ? e->second.engage_time : e->second.disengage_time;
      return;
    }
    case Quantity::BodyPosition:
      put(vec(d->xpos + 3 * id));
      return;
    case Quantity::BodyRPY:
      put(rpy_from_quat(d->xquat + 4 * id));
      return;
    case Quantity::BodyLinearVelocity:
      put(linear_velocity(m, d, id, d->xpos + 3 * id) + carried_linear(id, d->xpos + 3 * id));
      return;
    case Quantity::BodyAngularVelocity:
      put(angular_velocity(d, id) + carried_angular(id));
      return;

    case Quantity::SitePosition:
      put(vec(d->site_xpos + 3 * id));
      return;
    case Quantity::SiteRPY:
      put(rpy_from_matrix(d->site_xmat + 9 * id));
      return;
    case Quantity::SiteLinearVelocity:
      put(linear_velocity(m, d, m->site_bodyid[id], d->site_xpos + 3 * id) +
          carried_linear(m->site_bodyid[id], d->site_xpos + 3 * id));
      return;
    case Quantity::SiteAngularVelocity:
      put(angular_velocity(d, m->site_bodyid[id]) + carried_angular(m->site_bodyid[id]));
      return;
    case Quantity::SiteRelativePosition:
      put(relative_position(motion(id, false, false), motion(s.ids[1], false, false)));
      return;
    case Quantity::SiteRelativeRPY: {
      const Eigen::Matrix<mjtNum, 3, 3, Eigen::RowMajor> r =
          relative_rotation(motion(id, false, false), motion(s.ids[1], false, false));
      put(rpy_from_matrix(r.data()));
      return;
    }
    case Quantity::SiteRelativeLinearVelocity:
      put(relative_linear_velocity(motion(id, false, false), motion(s.ids[1], false, false)));
      return;
    case Quantity::SiteRelativeAngularVelocity:
      put(relative_angular_velocity(motion(id, false, false), motion(s.ids[1], false, false)));
      return;
    case Quantity::BodyLinearAcceleration:
    case Quantity::SiteLinearAcceleration:
    case Quantity::SiteAngularAcceleration:
    case Quantity::SiteRelativeLinearAcceleration:
    case Quantity::SiteRelativeAngularAcceleration:
    case Quantity::MateForceInFrame:
    case Quantity::MateTorqueInFrame:
    case Quantity::MateForce:
    case Quantity::MateTorque: {
      // Computed after each step (request_output), in the frame of the step that produced it; the sensor
      // holds the same force in site axes, but the site has moved on by the time a caller reads it.
      put(post_step[static_cast<size_t>(index)]);
      return;
    }
    case Quantity::Constant:
      out[0] = b.initial;
      return;
    default:
      throw SignalError("output `" + s.info.name + "` has no MuJoCo counterpart: " + b.reason);
  }
}

}  // namespace openplx::runtime
