// Writing an input: checked against its type and range, then into the MuJoCo model or data it maps to.
#include <algorithm>
#include <cmath>
#include <string>

#include "contract/numbers.h"
#include "contract/steering_linkage.h"
#include "mujoco_support/mujoco_compat.h"
#include "runtime/signal_conversions.h"
#include "runtime/simulation_state.h"

namespace openplx::runtime {

using mjcf::MjObject;
using mjcf::Quantity;

namespace {

// The vector inputs written straight into the motion of a body.
bool is_motion_vector(Quantity q) {
  return q == Quantity::KinematicLinearVelocity || q == Quantity::KinematicAngularVelocity ||
         q == Quantity::FreeLinearVelocity || q == Quantity::FreeAngularVelocity || q == Quantity::BodyTorque;
}

}  // namespace

void SimulationState::write(int index, const double* values, int count, ValueType given) {
  ResolvedSignal& s = signals[static_cast<size_t>(index)];
  const mjcf::SignalBinding& b = s.binding;
  if (b.quantity == Quantity::Broadcast) {  // the same value to every target, each checking it
    for (int p : s.parts) write(p, values, count, given);
    return;
  }
  if (b.quantity == Quantity::Affine && given == ValueType::Real && count == 1 && !s.parts.empty()) {
    const double value = b.low * values[0] + b.high;
    write(s.parts.front(), &value, 1, ValueType::Real);
    return;
  }
  if (b.quantity == Quantity::Composite && given == ValueType::Vector) {
    if (static_cast<size_t>(count) != s.parts.size()) {
      throw SignalError("input `" + s.info.name + "` takes " + std::to_string(s.parts.size()) +
                        " values, one per target, not " + std::to_string(count));
    }
    for (int i = 0; i < count; ++i) {
      if (!std::isfinite(values[i])) throw SignalError("input `" + s.info.name + "` got a non-finite value");
    }
    for (size_t k = 0; k < s.parts.size(); ++k) {  // each target by its own type (Bool: non-zero is true)
      const ValueType part = signals[static_cast<size_t>(s.parts[k])].info.value;
      const double value = part == ValueType::Bool ? (values[k] != 0 ? 1.0 : 0.0) : values[k];
      write(s.parts[k], &value, 1, part);
    }
    return;
  }
  const bool fits = s.info.value == given || (s.info.value == ValueType::Int && given == ValueType::Real &&
                                              std::floor(values[0]) == values[0]);
  if (!fits) {
    throw SignalError("input `" + s.info.name + "` takes " + std::string(type_name(s.info.value)) + ", not " +
                      std::string(type_name(given)));
  }
  for (int i = 0; i < count; ++i) {
    if (!std::isfinite(values[i])) throw SignalError("input `" + s.info.name + "` got a non-finite value");
  }
  double clamped = 0;
  if (count == 1 && (values[0] < s.low || values[0] > s.high)) {  // beyond what the model allows
    clamped = std::clamp(values[0], s.low, s.high);
    if (!s.clamp_said) {
      s.clamp_said = true;
      const bool own = s.low > -mjMAXVAL || s.high < mjMAXVAL;  // else MuJoCo's largest sound value
      warn(source + ": warning: input `" + s.info.name + "` got " + mjcf::number(values[0]) + ", outside " +
           (own ? "its range [" + mjcf::number(s.low) + ", " + mjcf::number(s.high) + "]"
                : "the values MuJoCo takes (magnitude up to " + mjcf::number(mjMAXVAL) + ")") +
           ": clamped to " + mjcf::number(clamped) + " (said once per input)\n");
    }
    values = &clamped;
  }
  if (count > 1 && is_motion_vector(b.quantity)) {
    // A velocity or torque beyond mjMAXVAL is one MuJoCo flags as diverged and resets (a velocity of 1e308
    // read back as {1e308, nan, nan}); clamping a component would turn the vector, so it is refused.
    for (int i = 0; i < count; ++i) {
      if (std::abs(values[i]) > mjMAXVAL) {
        throw SignalError("input `" + s.info.name + "` got " + mjcf::number(values[i]) +
                          ", beyond the values MuJoCo takes (magnitude up to " + mjcf::number(mjMAXVAL) +
                          ")");
      }
    }
  }
  const int id = s.ids.empty() ? -1 : s.ids.front();
  switch (b.quantity) {
    case Quantity::Ctrl:
      d->ctrl[id] = values[0];
      return;
    case Quantity::ForceRange:
    case Quantity::MotorForceRange: {
      if (values[0] > values[1]) {
        throw SignalError("input `" + s.info.name + "` got a range whose minimum exceeds its maximum");
      }
      EffortSwitch& e = effort_switch(s);
      e.low = values[0];
      e.high = values[1];
      apply(s);
      return;
    }
    case Quantity::InteractionEnabled:
      effort_switch(s).enabled = values[0] != 0;
      apply(s);
      return;
    case Quantity::EngagementFraction:
      m->tendon_frictionloss[id] = b.high * std::clamp(values[0], 0.0, 1.0);
      stale = true;  // friction rows are built in mj_step1
      return;
    case Quantity::Engaged:
      engagements.at(id).engaged = values[0] != 0;  // ramped from the next step on (resolve made it)
      return;
    case Quantity::EngageDuration:
    case Quantity::DisengageDuration: {
      if (values[0] < 0) throw SignalError("input `" + s.info.name + "` got a negative duration");
      auto e = engagements.find(id);
      if (e == engagements.end())
        throw SignalError("input `" + s.info.name + "`: its clutch has no engage input");
      (b.quantity == Quantity::EngageDuration ? e->second.engage_time : e->second.disengage_time) = values[0];
      return;
    }
    case Quantity::GearSelect:
      if (!(std::abs(values[0]) <= 1e9)) {  // no gearbox has as many; and an int holds it
        throw SignalError("input `" + s.info.name + "`: gear " + mjcf::number(values[0]) +
                          " is not one of its " + std::to_string(gearboxes.at(id).forward.size()) +
                          " forward and " + std::to_string(gearboxes.at(id).reverse.size()) +
                          " reverse gears");
      }
      select_gear(s, static_cast<int>(values[0]));
      return;
    case Quantity::DistanceTarget:
      m->eq_data[id * mjNEQDATA] = values[0] - m->tendon_length0[m->eq_obj1id[id]];
      stale = true;  // equality rows are built in mj_step1
      return;
    case Quantity::EqualityTarget:  // a steering column holds the left wheel at poly(input)
      m->eq_data[id * mjNEQDATA] =
          (b.initial_vector.empty() ? values[0] : mjcf::steering_polynomial(b.initial_vector, values[0])) -
          m->qpos0[m->jnt_qposadr[m->eq_obj1id[id]]];
      stale = true;
      return;
    case Quantity::GearRatio: {
      if (values[0] == 0) throw SignalError("input `" + s.info.name + "` got a zero gear ratio");
      reanchor_gear(id, values[0]);
      stale = true;  // equality rows are built in mj_step1
      return;
    }
    case Quantity::EqualityActive:
      for (int e : s.ids) equality_active(m, d, e) = values[0] != 0;
      stale = true;  // constraint rows are built in mj_step1
      return;
    case Quantity::KinematicLinearVelocity:
    case Quantity::KinematicAngularVelocity: {
      auto& target = b.quantity == Quantity::KinematicLinearVelocity ? kinematic_linear : kinematic_angular;
      target[static_cast<size_t>(s.address)] = Eigen::Vector3d(values[0], values[1], values[2]);
      kinematic = true;
      return;
    }
    case Quantity::FreeLinearVelocity:
      for (int i = 0; i < 3; ++i) d->qvel[s.dof + i] = values[i];
      stale = true;
      return;
    case Quantity::FreeAngularVelocity: {
      mjtNum r[9], world[3] = {values[0], values[1], values[2]};
      mju_quat2Mat(r, d->xquat + 4 * m->jnt_bodyid[id]);
      mju_mulMatTVec(d->qvel + s.dof + 3, r, world, 3, 3);  // MuJoCo keeps it in body axes
      stale = true;
      return;
    }
    case Quantity::BodyTorque:  // a couple: the same about the centre of mass MuJoCo applies it at
      for (int i = 0; i < 3; ++i) d->xfrc_applied[6 * id + 3 + i] = values[i];
      return;
    default:
      throw SignalError("input `" + s.info.name + "` has no MuJoCo counterpart: " + b.reason);
  }
}

// A gearbox's gear: neutral switches its equality off; a gear sets the equality's ratio (negated in reverse),
// re-anchored like a gear's ratio input so that the shafts keep their positions.
void SimulationState::select_gear(const ResolvedSignal& s, int gear) {
  const int id = s.ids.front();
  GearBox& g = gearboxes.at(id);
  const mjcf::GearSelection selection = mjcf::gearbox_ratio(g.forward, g.reverse, g.neutral, gear);
  if (!selection.valid) {
    throw SignalError("input `" + s.info.name + "`: gear " + std::to_string(gear) + " is not one of its " +
                      std::to_string(g.forward.size()) + " forward and " + std::to_string(g.reverse.size()) +
                      " reverse gears");
  }
  g.gear = gear;
  equality_active(m, d, id) = selection.ratio != 0;
  if (selection.ratio != 0) reanchor_gear(id, selection.ratio);
  stale = true;  // equality rows are built in mj_step1
}

// MuJoCo holds q1 - q1_0 = c0 + c1 (q2 - q2_0): a new c1 with c0 chosen so that it holds now keeps the shafts
// where they are; from here on their speeds keep the new ratio.
void SimulationState::reanchor_gear(int id, double ratio) {
  const int a1 = m->jnt_qposadr[m->eq_obj1id[id]], a2 = m->jnt_qposadr[m->eq_obj2id[id]];
  mjtNum* poly = m->eq_data + id * mjNEQDATA;
  poly[1] = 1.0 / ratio;
  poly[0] = (d->qpos[a1] - m->qpos0[a1]) - poly[1] * (d->qpos[a2] - m->qpos0[a2]);
}

}  // namespace openplx::runtime
