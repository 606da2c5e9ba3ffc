#include "runtime/simulation_state.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "mjcf_emitter/steering_linkage.h"
#include "mjcf_emitter/xml.h"
#include "runtime/mujoco_compat.h"
#include "runtime/name_suggestions.h"
#include "runtime/rotation.h"

namespace openplx::runtime {

using mjcf::MjObject;
using mjcf::Quantity;

namespace {

mjtObj object_type(MjObject object) {
  switch (object) {
    case MjObject::Actuator:
      return mjOBJ_ACTUATOR;
    case MjObject::Joint:
      return mjOBJ_JOINT;
    case MjObject::Body:
      return mjOBJ_BODY;
    case MjObject::Site:
      return mjOBJ_SITE;
    case MjObject::Equality:
      return mjOBJ_EQUALITY;
    case MjObject::Tendon:
      return mjOBJ_TENDON;
    case MjObject::Sensor:
      return mjOBJ_SENSOR;
    case MjObject::None:
      break;
  }
  return mjOBJ_UNKNOWN;
}

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

std::string_view type_name(ValueType type) {
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

Eigen::Vector3d vec(const mjtNum* v) {
  return {v[0], v[1], v[2]};
}

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
  if (!owns) return;
  if (d) mj_deleteData(d);
  if (m) mj_deleteModel(m);
}

void SimulationState::resolve(std::vector<mjcf::SignalBinding> bindings,
                              const std::vector<mjcf::RuntimeLaw>& drive_laws) {
  laws.resolve(m, drive_laws, owns);  // a Simulation steps mj_step1, laws, mj_step2; a bridge does not
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
    if (b.quantity == Quantity::MotorForce)
      s.bias = mj_name2id(m, mjOBJ_ACTUATOR, mjcf::motor_bias_name(b.names.front()).c_str());
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

static size_t value_count(ValueType type) {
  return type == ValueType::Vec2 ? 2 : type == ValueType::Vec3 ? 3 : 1;
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

void SimulationState::step() {
  // mj_step = mj_step1 + mj_step2 under Euler. Running step1 of the next state right after step2 leaves
  // positions and velocities (and the outputs computed from them) current after every step, at no extra cost.
  begin_watch();
  std::string error;
  if (stale) {
    if (!call_mujoco(
            d, [this] { mj_step1(m, d); }, error))
      mujoco_failed(error);
    stale = false;
  }
  before_step();
  if (!call_mujoco(
          d, [this] { mj_step2(m, d); }, error))
    mujoco_failed(error);
  after_step();
  if (!call_mujoco(
          d, [this] { mj_step1(m, d); }, error))
    mujoco_failed(error);
  end_watch();
}

void SimulationState::begin_watch() {
  counts_before = mjcf::WarningCounts::of(d);
  time_before = d->time;
  seen.clear();
  current_sink() = this;
}

void SimulationState::end_watch() {
  if (current_sink() == this) current_sink() = nullptr;
  const bool back = d->time < time_before;
  bool risen = back;
  for (int k = 0; k < mjNWARNING; ++k) risen |= d->warning[k].number != counts_before.number[k];
  if (risen) {
    check_warnings(back);
  } else if (!seen_texts.empty()) {  // a message MuJoCo counts nowhere
    for (const std::string& text : seen_texts) warn(source + ": warning: MuJoCo: " + text + "\n");
    seen_texts.clear();
  }
}

// MuJoCo's warning callback runs before mj_checkPos/Vel/Acc reset the data: the state it saw is kept for the
// message (only the first of a step; a warning is the rare path).
void SimulationState::mujoco_warning(const char* text) {
  seen.capture(m, d);
  if (seen_texts.size() < 8) seen_texts.emplace_back(text);
}

void SimulationState::check_warnings(bool time_went_back) {
  std::string wrong;
  int first = -1;
  for (int w : counts_before.risen(d, time_went_back)) {
    const mjcf::WarningSeverity severity = mjcf::warning_severity(w);
    if (severity == mjcf::WarningSeverity::Ignore) continue;
    mjcf::WarningFacts facts = seen.facts(d, w, time_before);
    facts.emitted_timestep = emitted_timestep;
    facts.prefix = prefix;
    const std::string text = mjcf::describe_warning(m, facts);
    d->warning[w].number = 0;  // the next one is counted (and handed to the callback) afresh
    if (severity == mjcf::WarningSeverity::Wrong && on_instability == OnInstability::Throw) {
      wrong += (wrong.empty() ? "" : "\n") + source + ": error: " + text;
      if (first < 0) first = w;
    } else {
      warn(source + ": warning: " + text + "\n");
    }
  }
  const double when = seen.valid ? seen.time : time_before;
  seen.clear();
  seen_texts.clear();
  if (!wrong.empty()) {
    throw SimulationError(wrong + "\n", when, first);
  }
}

void SimulationState::mujoco_failed(const std::string& error) {
  if (current_sink() == this) current_sink() = nullptr;
  seen.clear();
  seen_texts.clear();
  throw SimulationError(source + ": error: at t = " + std::to_string(time_before) +
                            " s MuJoCo stopped on an error: " + error + "\n",
                        time_before, -1);
}

void SimulationState::warn(std::string text) {
  ++run_warnings;
  if (run_warnings < kMaxRunWarnings) {
    warnings.push_back(std::move(text));
  } else if (run_warnings == kMaxRunWarnings) {
    warnings.push_back(source + ": warning: more run warnings followed; they are not kept\n");
  }
}

void SimulationState::before_step() {
  laws.apply(m, d);  // actuator forces come from mj_step2's mj_fwdActuation
}

void SimulationState::after_step() {
  laws.after_step(m, d);
  cache_constraint_forces();
  if (!post_step_signals.empty()) compute_post_step();
  ramp_engagements();
  if (!kinematic) return;
  const mjtNum h = m->opt.timestep;
  for (int k = 0; k < m->nmocap; ++k) {
    const Eigen::Vector3d& v = kinematic_linear[static_cast<size_t>(k)];
    const Eigen::Vector3d& w = kinematic_angular[static_cast<size_t>(k)];
    for (int i = 0; i < 3; ++i) d->mocap_pos[3 * k + i] += h * v[i];
    if (!w.isZero()) {
      mjtNum local[3], world[3] = {w.x(), w.y(), w.z()}, r[9];
      mju_quat2Mat(r, d->mocap_quat + 4 * k);
      mju_mulMatTVec(local, r, world, 3, 3);  // mju_quatIntegrate turns about body axes
      mju_quatIntegrate(d->mocap_quat + 4 * k, local, h);
    }
  }
}

// Automatic clutches and brakes move their engagement toward engaged (1) or not (0) at the rate their
// durations give; the friction rows mj_step1 builds next carry capacity * engagement.
void SimulationState::ramp_engagements() {
  const double h = m->opt.timestep;
  for (auto& [tendon, e] : engagements) {
    const double target = e.engaged ? 1.0 : 0.0, time = e.engaged ? e.engage_time : e.disengage_time;
    const double change = time > 0 ? h / time : 1.0;
    e.fraction =
        target > e.fraction ? std::min(target, e.fraction + change) : std::max(target, e.fraction - change);
    m->tendon_frictionloss[tendon] = e.capacity * e.fraction;
  }
}

// Constraint forces belong to the rows mj_step1 builds; the next mj_step1 rebuilds the rows, so the forces
// of the step just taken are kept here first.
void SimulationState::cache_constraint_forces() {
  for (int index : constraint_signals) {
    const ResolvedSignal& s = signals[static_cast<size_t>(index)];
    const int id = s.ids.front();
    const int type = s.binding.quantity == Quantity::JointLimitForce    ? mjCNSTR_LIMIT_JOINT
                     : s.binding.quantity == Quantity::EqualityForce    ? mjCNSTR_EQUALITY
                     : s.binding.quantity == Quantity::TendonLimitForce ? mjCNSTR_LIMIT_TENDON
                                                                        : mjCNSTR_FRICTION_TENDON;
    double total = 0;
    for (int r = 0; r < d->nefc; ++r) {
      if (d->efc_type[r] == type && d->efc_id[r] == id) total += d->efc_force[r];
    }
    if (s.bias >= 0) total += d->actuator_force[s.bias];
    constraint_forces[static_cast<size_t>(index)] = total;
  }
}

// Mate forces: the interaction force MuJoCo computes between the MuJoCo child and its parent
// (cfrc_int, after mj_rnePostConstraint), at the connector's site, in world axes. Computed only for outputs a
// caller asked for, and between mj_step2 and the next mj_step1, while the constraint forces are current.
void SimulationState::request_output(int index) {
  const mjcf::SignalBinding& b = signals[static_cast<size_t>(index)].binding;
  const bool computed = b.quantity == Quantity::MateForce || b.quantity == Quantity::MateTorque;
  if (!computed ||
      std::find(post_step_signals.begin(), post_step_signals.end(), index) != post_step_signals.end())
    return;
  post_step_signals.push_back(index);
  post_step.resize(signals.size(), Eigen::Vector3d::Zero());
  compute_post_step();  // the state at load (mj_forward) is consistent too
}

void SimulationState::compute_post_step() {
  mj_rnePostConstraint(m, d);
  for (int index : post_step_signals) {
    const ResolvedSignal& s = signals[static_cast<size_t>(index)];
    const int site = s.ids.front(), body = m->site_bodyid[site];
    const Eigen::Vector3d torque = vec(d->cfrc_int + 6 * body), force = vec(d->cfrc_int + 6 * body + 3);
    // cfrc_int's torque is about the subtree centre of mass of the body's root; move it to the site.
    const Eigen::Vector3d lever =
        vec(d->subtree_com + 3 * m->body_rootid[body]) - vec(d->site_xpos + 3 * site);
    const Eigen::Vector3d value =
        s.binding.quantity == Quantity::MateForce ? force : Eigen::Vector3d(torque + lever.cross(force));
    post_step[static_cast<size_t>(index)] = s.binding.sign * value;
  }
}

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
  const int id = s.ids.empty() ? -1 : s.ids.front();
  auto put = [&](const Eigen::Vector3d& v) {
    for (int i = 0; i < count && i < 3; ++i) out[i] = v[i];
  };
  auto from_sensor = [&](const char* what) {
    if (s.sensor < 0) {
      throw SignalError(
          "output `" + s.info.name + "` is " + what +
          ", which MuJoCo measures only with a sensor: enable it in the model (`enabled: true`)");
    }
    return d->sensordata + m->sensor_adr[s.sensor];
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
    case Quantity::BodyLinearAcceleration:
      put(vec(from_sensor("an acceleration")));
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
