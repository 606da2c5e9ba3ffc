#include "runtime/simulation_state.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "contract/numbers.h"
#include "mujoco_support/mujoco_compat.h"
#include "runtime/name_suggestions.h"
#include "runtime/row_hook.h"
#include "runtime/signal_conversions.h"

namespace openplx::runtime {

using mjcf::MjObject;
using mjcf::Quantity;

namespace {

ValueType value_type(mjcf::SignalValue value) {
  switch (value) {
    case mjcf::SignalValue::Real:
      return ValueType::Real;
    case mjcf::SignalValue::Bool:
      return ValueType::Bool;
    case mjcf::SignalValue::Int:
      return ValueType::Int;
    case mjcf::SignalValue::Vec2:
      return ValueType::Vec2;
    case mjcf::SignalValue::Vec3:
      return ValueType::Vec3;
    case mjcf::SignalValue::Vector:
      return ValueType::Vector;
  }
  return ValueType::Real;
}

// A signal made of other signals (Robotics composites, Control's virtual signals): its names are its parts'
// OpenPLX paths, not MuJoCo elements.
bool composed(Quantity q) {
  return q == Quantity::Composite || q == Quantity::Broadcast || q == Quantity::Affine;
}

std::string describe(const mjcf::SignalBinding& b) {
  if (b.quantity == Quantity::None) return "not mapped: " + b.reason;
  if (composed(b.quantity)) {
    std::string text = std::string(to_string(b.quantity)) + " of";
    for (const std::string& name : b.names) text += " " + name;
    return text;
  }
  std::string text(to_string(b.object));
  for (const std::string& name : b.names) text += " " + name;
  return text + ": " + std::string(to_string(b.quantity));
}

// What makes the element a binding names unfit for its quantity (a manifest that does not fit the model);
// "" when it fits. The names exist (resolve looked them up).
std::string element_problem(const mjModel* m, const mjcf::SignalBinding& b, const std::vector<int>& ids) {
  const int id = ids.front();
  const std::string name = "`" + b.names.front() + "`";
  switch (b.quantity) {
    case Quantity::KinematicLinearVelocity:
    case Quantity::KinematicAngularVelocity:
      return m->body_mocapid[id] < 0 ? "body " + name + " is not a mocap body" : "";
    case Quantity::FreeLinearVelocity:
    case Quantity::FreeAngularVelocity:
      return m->jnt_type[id] != mjJNT_FREE ? "joint " + name + " is not a free joint" : "";
    case Quantity::BodyTorque:
      return m->body_mocapid[id] >= 0 || m->body_weldid[id] == 0
                 ? "body " + name + " has no degrees of freedom of its own (a torque moves nothing)"
                 : "";
    case Quantity::GearRatio:
    case Quantity::GearSelect:
      return m->eq_type[id] != mjEQ_JOINT || m->eq_obj2id[id] < 0
                 ? "equality " + name + " does not couple two joints"
                 : "";
    case Quantity::EqualityTarget:
      return m->eq_type[id] != mjEQ_JOINT ? "equality " + name + " is not a joint equality" : "";
    case Quantity::DistanceTarget:
      return m->eq_type[id] != mjEQ_TENDON ? "equality " + name + " is not a tendon equality" : "";
    case Quantity::SensorFields:
      for (size_t k = 0; k < ids.size(); ++k) {
        const double field = k < b.initial_vector.size() ? b.initial_vector[k] : -1;
        if (!(field >= 0 && field < m->sensor_dim[ids[k]]) || std::floor(field) != field)
          return "sensor `" + b.names[k] + "` has no field " + mjcf::number(field);
      }
      return "";
    default:
      return "";
  }
}

}  // namespace

SimulationState::~SimulationState() {
  if (current_sink() == this) current_sink() = nullptr;
  if (rows_hooked) row_hook::detach(d, &rows);
  rows.release();  // before a Simulation deletes the model
  if (!owns) return;
  if (d) mj_deleteData(d);
  if (m) mj_deleteModel(m);
}

void SimulationState::resolve(std::vector<mjcf::SignalBinding> bindings,
                              const std::vector<mjcf::RuntimeLaw>& drive_laws) {
  laws.resolve(m, drive_laws);
  row_problems = rows.resolve(m, drive_laws);
  mismatches = row_problems;
  kinematic_linear.assign(static_cast<size_t>(m->nmocap), Eigen::Vector3d::Zero());
  kinematic_angular.assign(static_cast<size_t>(m->nmocap), Eigen::Vector3d::Zero());
  for (mjcf::SignalBinding& b : bindings) {
    ResolvedSignal s;
    s.info.name = b.path;
    s.info.type = b.type;
    s.info.value = value_type(b.value);
    s.info.unit = b.unit;
    s.info.enabled = b.enabled;
    s.info.mapped = b.quantity != Quantity::None;
    s.info.mujoco = describe(b);
    for (const std::string& name : b.names) {
      if (composed(b.quantity)) break;
      const int id = mj_name2id(m, object_type(b.object), name.c_str());
      if (id < 0) {  // the emitter promised it: a mismatch is a bug, so the signal is refused, not misread
        s.info.mapped = false;
        s.info.mujoco = "not mapped: MuJoCo has no " + std::string(to_string(b.object)) + " named " + name;
        if (b.quantity != Quantity::None)
          mismatches.push_back("`" + b.path + "`: " + s.info.mujoco.substr(12));
        b.quantity = Quantity::None;
        b.reason = s.info.mujoco;
      }
      s.ids.push_back(id);
    }
    if (b.quantity != Quantity::None && !composed(b.quantity) && !s.ids.empty()) {
      if (const std::string problem = element_problem(m, b, s.ids); !problem.empty()) {
        s.info.mapped = false;
        s.info.mujoco = "not mapped: " + problem;
        mismatches.push_back("`" + b.path + "`: " + problem);
        b.quantity = Quantity::None;
        b.reason = s.info.mujoco;
      }
    }
    if (!b.sensor.empty()) s.sensor = mj_name2id(m, mjOBJ_SENSOR, b.sensor.c_str());
    if (b.quantity != Quantity::None && !s.ids.empty()) {
      const int id = s.ids.front();
      if (b.object == MjObject::Joint) {
        s.address = m->jnt_qposadr[id];
        s.dof = m->jnt_dofadr[id];
      } else if (b.object == MjObject::Body) {
        s.address = m->body_mocapid[id];
      }
      if (b.quantity == Quantity::Ctrl && b.input) d->ctrl[id] = b.initial;  // the keyframe has it too
      const bool kinematic_input =
          b.quantity == Quantity::KinematicLinearVelocity || b.quantity == Quantity::KinematicAngularVelocity;
      if (kinematic_input && b.initial_vector.size() == 3 && s.address >= 0) {  // MJCF has no mocap velocity
        auto& target = b.quantity == Quantity::KinematicLinearVelocity ? kinematic_linear : kinematic_angular;
        target[static_cast<size_t>(s.address)] =
            Eigen::Vector3d(b.initial_vector[0], b.initial_vector[1], b.initial_vector[2]);
        kinematic = kinematic || !target[static_cast<size_t>(s.address)].isZero();
      }
      if (b.input && b.quantity == Quantity::Ctrl && m->actuator_ctrllimited[id]) {
        s.low = m->actuator_ctrlrange[2 * id];
        s.high = m->actuator_ctrlrange[2 * id + 1];
      } else if (b.input && b.quantity == Quantity::EngagementFraction) {
        s.low = 0;
        s.high = 1;
      } else if (b.input && b.quantity == Quantity::EqualityTarget &&
                 (b.low < b.high || (b.low == b.high && !b.initial_vector.empty()))) {
        s.low = b.low;  // a kinematic steering's reach (its linkage's dead points; 0 when it cannot close)
        s.high = b.high;
      } else if (b.input && b.quantity == Quantity::EqualityTarget && b.initial_vector.empty() &&
                 m->jnt_limited[m->eq_obj1id[id]]) {  // a kinematic steering joint's travel
        s.low = m->jnt_range[2 * m->eq_obj1id[id]];
        s.high = m->jnt_range[2 * m->eq_obj1id[id] + 1];
      }
      if (s.info.value == ValueType::Real) {  // the inlined fast path of Input::set and Output::real
        if (b.quantity == Quantity::Ctrl) s.direct = d->ctrl + id;
        if (!b.input && b.quantity == Quantity::JointPosition && b.initial_vector.empty())
          s.direct = d->qpos + s.address;
        if (!b.input && b.quantity == Quantity::JointVelocity) s.direct = d->qvel + s.dof;
        s.scale = b.sign;
      }
      const int moved_by = b.object == MjObject::Body   ? id
                           : b.object == MjObject::Site ? m->site_bodyid[id]
                                                        : 0;
      const bool carried = m->body_mocapid[m->body_rootid[moved_by]] >= 0;  // velocities need the mocap's
      if (!b.input && s.info.value == ValueType::Vec3 && !carried) {  // the inlined fast path of Output::vec3
        if (b.quantity == Quantity::BodyPosition) s.direct3 = d->xpos + 3 * id;
        if (b.quantity == Quantity::SitePosition) s.direct3 = d->site_xpos + 3 * id;
        if (b.quantity == Quantity::BodyAngularVelocity) s.direct3 = d->cvel + 6 * id;
        if (b.quantity == Quantity::SiteAngularVelocity) s.direct3 = d->cvel + 6 * m->site_bodyid[id];
      }
    }
    if (b.quantity == Quantity::Engaged && !s.ids.empty() && s.ids.front() >= 0 &&
        b.initial_vector.size() == 1) {
      Engagement& e = engagements[s.ids.front()];
      e.engaged = b.initial != 0;
      e.fraction = e.engaged ? 1.0 : 0.0;
      e.capacity = b.initial_vector[0];
      e.engage_time = b.low;
      e.disengage_time = b.high;
    }
    if (b.quantity == Quantity::GearSelect && !s.ids.empty() && s.ids.front() >= 0) {
      const size_t forward = static_cast<size_t>(std::clamp(b.low, 0.0, double(b.initial_vector.size())));
      GearBox& g = gearboxes[s.ids.front()];
      g.forward.assign(b.initial_vector.begin(), b.initial_vector.begin() + static_cast<long>(forward));
      g.reverse.assign(b.initial_vector.begin() + static_cast<long>(forward), b.initial_vector.end());
      g.neutral = b.high != 0;
      g.gear = static_cast<int>(b.initial);
    }
    if (b.quantity == Quantity::MotorForce) {  // the velocity motor's stand-in (format 1: its bias actuator)
      s.bias = mj_name2id(m, mjOBJ_ACTUATOR, mjcf::motor_bias_name(b.names.front()).c_str());
      if (s.bias < 0) s.bias = mj_name2id(m, mjOBJ_ACTUATOR, b.names.front().c_str());
    }
    s.binding = std::move(b);
    if (s.binding.quantity == Quantity::JointLimitForce || s.binding.quantity == Quantity::MotorForce ||
        s.binding.quantity == Quantity::EqualityForce || s.binding.quantity == Quantity::TendonLimitForce)
      constraint_signals.push_back(static_cast<int>(signals.size()));
    by_name.emplace(s.info.name, static_cast<int>(signals.size()));
    signals.push_back(std::move(s));
  }
  constraint_forces.assign(signals.size(), 0.0);
  init_switches();
  resolve_composites();
}

// A composite's parts by path, and its size; one with a part that did not resolve is not mapped.
void SimulationState::resolve_composites() {
  for (ResolvedSignal& s : signals) {
    const Quantity q = s.binding.quantity;
    if (!composed(q)) continue;
    s.info.size = 0;
    for (const std::string& path : s.binding.names) {
      auto it = by_name.find(path);
      if (it == by_name.end() || !signals[static_cast<size_t>(it->second)].info.mapped) {
        s.info.mapped = false;
        s.info.mujoco = "not mapped: its part `" + path + "` is not mapped";
        s.binding.quantity = Quantity::None;
        s.parts.clear();
        break;
      }
      s.parts.push_back(it->second);
      s.info.size += value_count(signals[static_cast<size_t>(it->second)].info.value);
    }
    if (q != Quantity::Composite && !s.parts.empty()) s.info.size = value_count(s.info.value);
  }
  for (ResolvedSignal& s : signals) {
    if (s.binding.quantity == Quantity::SensorFields) s.info.size = s.ids.size();
  }
  // A signal made of itself, or nested deeper than any model writes, would recurse without end.
  auto depth = [&](auto& self, int index, int level) -> int {
    const ResolvedSignal& s = signals[static_cast<size_t>(index)];
    if (level > 16) return level;
    int deepest = level;
    for (int p : s.parts) deepest = std::max(deepest, self(self, p, level + 1));
    return deepest;
  };
  for (size_t k = 0; k < signals.size(); ++k) {
    ResolvedSignal& s = signals[k];
    if (s.parts.empty() || depth(depth, static_cast<int>(k), 0) <= 16) continue;
    mismatches.push_back("`" + s.info.name + "`: its parts contain itself");
    s.info.mapped = false;
    s.info.mujoco = "not mapped: its parts contain itself";
    s.binding.quantity = Quantity::None;
  }
  for (ResolvedSignal& s : signals) {
    if (s.binding.quantity == Quantity::None) s.parts.clear();
  }
}

// Enabled states and effort ranges: from the enable bindings (which carry the range when enabled), else from
// the model as emitted.
void SimulationState::init_switches() {
  for (const ResolvedSignal& s : signals) {
    const mjcf::SignalBinding& b = s.binding;
    if (b.quantity != Quantity::InteractionEnabled) continue;
    const int id = s.ids.front();
    EffortSwitch& e = switches[{object_type(b.object), id}];
    e = {b.initial != 0, b.low, b.high, -1};
    if (b.object == MjObject::Tendon)
      e.bias = mj_name2id(m, mjOBJ_ACTUATOR, mjcf::motor_bias_name(b.names.front()).c_str());
  }
  for (const ResolvedSignal& s : signals) {
    const mjcf::SignalBinding& b = s.binding;
    const int id = s.ids.empty() ? -1 : s.ids.front();
    auto [it, fresh] = switches.try_emplace({object_type(b.object), id});
    if (!fresh) continue;
    EffortSwitch& e = it->second;
    if (b.quantity == Quantity::ForceRange) {
      e = {true, m->actuator_forcerange[2 * id], m->actuator_forcerange[2 * id + 1], -1};
    } else if (b.quantity == Quantity::MotorForceRange) {
      e.bias = mj_name2id(m, mjOBJ_ACTUATOR, mjcf::motor_bias_name(b.names.front()).c_str());
      const double band = m->tendon_frictionloss[id],
                   centre = e.bias >= 0 ? m->actuator_biasprm[e.bias * mjNBIAS] : 0;
      e = {true, centre - band, centre + band, e.bias};
    } else {
      switches.erase(it);
    }
  }
}

EffortSwitch& SimulationState::effort_switch(const ResolvedSignal& s) {
  return switches.at({object_type(s.binding.object), s.ids.front()});
}

// Writes an interaction's enabled state and effort range into the model.
void SimulationState::apply(const ResolvedSignal& s) {
  const EffortSwitch& e = effort_switch(s);
  const int id = s.ids.front();
  const double low = e.enabled ? e.low : 0.0, high = e.enabled ? e.high : 0.0;
  switch (s.binding.object) {
    case MjObject::Tendon:
      if (e.bias < 0 && low + high != 0)
        throw SignalError("input `" + s.info.name + "`: this motor's effort range must stay centred on 0");
      m->tendon_frictionloss[id] = (high - low) / 2;
      if (e.bias >= 0) m->actuator_biasprm[e.bias * mjNBIAS] = (high + low) / 2;
      stale = true;  // friction rows are built in mj_step1
      return;
    case MjObject::Actuator:  // off: it transmits nothing (gear 0), as the emitter writes a disabled one
      m->actuator_gear[6 * id] = e.enabled ? 1.0 : 0.0;
      m->actuator_forcelimited[id] = 1;
      m->actuator_forcerange[2 * id] = e.low;
      m->actuator_forcerange[2 * id + 1] = e.high;
      stale = true;  // actuator lengths (a spring's bias) come from mj_step1's transmission
      return;
    case MjObject::Joint:
      m->jnt_limited[id] = e.enabled;
      m->jnt_range[2 * id] = e.low;
      m->jnt_range[2 * id + 1] = e.high;
      stale = true;  // limit rows are built in mj_step1
      return;
    default:
      return;
  }
}

int SimulationState::find(std::string_view name, bool input) const {
  auto lookup = [&](std::string_view key) {
    auto it = by_name.find(std::string(key));
    return it != by_name.end() && signals[it->second].binding.input == input ? it->second : -1;
  };
  int index = lookup(name);
  if (index < 0 && name.size() > root.size() + 1 && name.substr(0, root.size()) == root &&
      name[root.size()] == '.') {
    index = lookup(name.substr(root.size() + 1));
  }
  if (index >= 0) return index;
  std::vector<std::string> candidates;
  for (const ResolvedSignal& s : signals) {
    if (s.binding.input == input) candidates.push_back(s.info.name);
  }
  throw SignalError(std::string(input ? "no input" : "no output") + " named `" + std::string(name) + "`" +
                    suggestion_text(name, candidates));
}

}  // namespace openplx::runtime
