// A step: mj_step2 then mj_step1 with the drive laws between, MuJoCo's warnings turned into located
// diagnostics, and what is kept of each step (constraint forces, mate forces, clutch ramps, mocap motion).
#include <Eigen/Geometry>
#include <algorithm>
#include <string>

#include "mujoco_support/mujoco_compat.h"
#include "runtime/signal_conversions.h"
#include "runtime/simulation_state.h"

namespace openplx::runtime {

using mjcf::MjObject;
using mjcf::Quantity;

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
  // The rows mj_step1 built get AGX's law here, after the inputs and drive laws of this step (a bridge's come
  // through mjcb_control inside the user's mj_step instead).
  if (!call_mujoco(
          d,
          [this] {
            rows.control(m, d);
            mj_step2(m, d);
          },
          error))
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
  rows.after_step(m, d);
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

namespace {
bool computed_after_step(Quantity q) {
  switch (q) {
    case Quantity::MateForce:
    case Quantity::MateTorque:
    case Quantity::MateForceInFrame:
    case Quantity::MateTorqueInFrame:
    case Quantity::BodyLinearAcceleration:
    case Quantity::SiteLinearAcceleration:
    case Quantity::SiteAngularAcceleration:
    case Quantity::SiteRelativeLinearAcceleration:
    case Quantity::SiteRelativeAngularAcceleration:
      return true;
    default:
      return false;
  }
}
}  // namespace

// Mate forces: the interaction force MuJoCo computes between the MuJoCo child and its parent
// (cfrc_int, after mj_rnePostConstraint), at the connector's site, in world axes (or a fixed frame's), and
// accelerations. Computed only for outputs a caller asked for, and between mj_step2 and the next mj_step1,
// while the constraint forces are current.
void SimulationState::request_output(int index) {
  const mjcf::SignalBinding& b = signals[static_cast<size_t>(index)].binding;
  const bool computed = computed_after_step(b.quantity);
  if (!computed ||
      std::find(post_step_signals.begin(), post_step_signals.end(), index) != post_step_signals.end())
    return;
  post_step_signals.push_back(index);
  post_step.resize(signals.size(), Eigen::Vector3d::Zero());
  compute_post_step();  // the state at load (mj_forward) is consistent too
}

// Accelerations and mate forces (MuJoCo's cacc and cfrc_int) are computed only for outputs a caller asked
// for, between mj_step2 and the next mj_step1: positions, velocities and accelerations are then all of the
// state the step started from.
void SimulationState::compute_post_step() {
  mj_rnePostConstraint(m, d);
  for (int index : post_step_signals) {
    const ResolvedSignal& s = signals[static_cast<size_t>(index)];
    const Quantity q = s.binding.quantity;
    const int id = s.ids.front();
    Eigen::Vector3d value;
    switch (q) {
      case Quantity::BodyLinearAcceleration:
        value = motion(id, true, true).a;
        break;
      case Quantity::SiteLinearAcceleration:
        value = motion(id, false, true).a;
        break;
      case Quantity::SiteAngularAcceleration:
        value = motion(id, false, true).alpha;
        break;
      case Quantity::SiteRelativeLinearAcceleration:
        value = relative_linear_acceleration(motion(id, false, true), motion(s.ids[1], false, true));
        break;
      case Quantity::SiteRelativeAngularAcceleration:
        value = relative_angular_acceleration(motion(id, false, true), motion(s.ids[1], false, true));
        break;
      default: {  // a mate force or torque
        const int body = m->site_bodyid[id];
        const Eigen::Vector3d torque = vec(d->cfrc_int + 6 * body), force = vec(d->cfrc_int + 6 * body + 3);
        // cfrc_int's torque is about the subtree centre of mass of the body's root; move it to the site.
        const Eigen::Vector3d lever =
            vec(d->subtree_com + 3 * m->body_rootid[body]) - vec(d->site_xpos + 3 * id);
        const bool is_force = q == Quantity::MateForce || q == Quantity::MateForceInFrame;
        value = s.binding.sign * (is_force ? force : Eigen::Vector3d(torque + lever.cross(force)));
        if (q == Quantity::MateForceInFrame || q == Quantity::MateTorqueInFrame) {
          const std::vector<double>& r = s.binding.initial_vector;  // w, x, y, z: world from the frame
          value = Eigen::Quaterniond(r[0], r[1], r[2], r[3]).normalized().conjugate() * value;
        }
      }
    }
    post_step[static_cast<size_t>(index)] = value;
  }
}

}  // namespace openplx::runtime
