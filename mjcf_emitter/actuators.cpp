// Lowering pass, actuators: ranges and springs as joint attributes, <velocity>/<motor> actuators with their
// limits.
#include "mjcf_emitter/lowering.h"

#include <cmath>

namespace openplx::mjcf {

void Lowering::emit_actuators(Element& root) {
  Element& actuators = root.add("actuator");
  using K = sn::Interaction1D::Kind;
  // Ranges and springs are joint attributes; several on one joint intersect (ranges) or add up (springs).
  std::map<Element*, std::pair<double, double>> ranges;
  std::map<Element*, std::pair<double, double>> springs;  // sum k, sum k * rest
  std::map<Element*, double> dampings;
  for (const sn::JointProperties& p : view_.joint_properties) {
    if (p.mate >= 0) joint_properties_[p.mate] = &p;
  }
  for (const sn::Interaction1D& i : view_.interactions) {
    const bool velocity = i.kind == K::LinearVelocityMotor || i.kind == K::RotationalVelocityMotor;
    if (!velocity || i.mate < 0 || !tree_mates_.count(i.mate)) continue;
    if (Element* joint = joint_for(i.mate, i.kind == K::RotationalVelocityMotor)) ++velocity_motors_[joint];
  }
  for (const sn::Interaction1D& i : view_.interactions) {
    if (i.shaft >= 0) {
      emit_shaft_motor(actuators, i);
      continue;
    }
    if (i.mate < 0) {
      warn(i.where, "`" + i.path +
                        "` acts on connectors that no mate joins (or on a drivetrain it cannot "
                        "drive); it was left out");
      continue;
    }
    if (!tree_mates_.count(i.mate)) continue;  // loop mates warned above
    const bool rotational = i.kind == K::TorsionSpring || i.kind == K::RotationalRange ||
                            i.kind == K::RotationalVelocityMotor || i.kind == K::TorqueMotor;
    Element* joint = joint_for(i.mate, rotational);
    if (!joint) {
      warn(i.where, "`" + i.path + "` acts on `" + view_.mates[i.mate].path + "`, whose joint has no " +
                        (rotational ? "rotational" : "linear") + " degree of freedom; it was left out");
      continue;
    }
    const std::string joint_name = *joint->get("name");
    switch (i.kind) {
      case K::LinearRange:
      case K::RotationalRange: {
        const double lo = i.start, hi = i.end;
        range_joints_[index_in(view_.interactions, i)] = joint_name;
        auto [it, fresh] = ranges.try_emplace(joint, lo, hi);
        if (!fresh) it->second = {std::max(it->second.first, lo), std::min(it->second.second, hi)};
        break;
      }
      case K::LinearSpring:
      case K::TorsionSpring: {
        const double k = i.stiffness;
        const double rest = i.rest;
        auto& [sum_k, sum_kr] = springs[joint];
        sum_k += k;
        sum_kr += k * rest;
        springs_[index_in(view_.interactions, i)] = {joint_name, k, rest, 0.0};
        dampings[joint] += spring_damping(i, k);
        if (std::isfinite(i.min_effort) || std::isfinite(i.max_effort)) {
          warn(i.where, "`" + i.path +
                            ".min_effort`/`max_effort`: a MuJoCo joint spring has no force limit; the "
                            "spring was emitted without one");
        }
        break;
      }
      case K::LinearVelocityMotor:
      case K::RotationalVelocityMotor: {
        // f = kv (ctrl - qdot); kv is bounded by the motor's gain and by what explicit Euler keeps stable.
        const double gain = i.gain.value_or(1e8);
        Element& a = actuators.add("velocity");
        a.set("name", name(i.path)).set("joint", joint_name).set("kv", velocity_gain(gain, *joint, i));
        effort_limits(a, i);
        speed_limit(a, i);
        actuator_ctrl_[index_in(view_.interactions, i)] = {static_cast<int>(actuator_count_++),
                                                           i.target_speed.value_or(0.0)};
        break;
      }
      case K::ForceMotor:
      case K::TorqueMotor: {
        Element& a = actuators.add("motor");
        a.set("name", name(i.path)).set("joint", joint_name).set("gear", "1");
        effort_limits(a, i);
        actuator_ctrl_[index_in(view_.interactions, i)] = {static_cast<int>(actuator_count_++),
                                                           i.default_effort};
        break;
      }
      default:
        warn(i.where, "`" + i.path + "` has no MuJoCo mapping yet; it was left out");
        break;
    }
  }
  apply_joint_properties(dampings);
  for (auto& [joint, range] : ranges) {
    if (range.first > range.second) {
      warn({}, "the ranges on joint " + *joint->get("name") + " do not overlap; the joint is locked at " +
                   number(range.first));
      range.second = range.first;
    }
    joint->set("limited", "true").set("range", number(range.first) + " " + number(range.second));
  }
  for (auto& [joint, spring] : springs) {
    joint->set("stiffness", spring.first);
    const double rest = spring.first > 0 ? spring.second / spring.first : 0.0;
    if (rest != 0) joint->set("springref", rest);
    for (auto& [interaction, info] : springs_) {
      if (info.joint == *joint->get("name")) info.joint_rest = rest;
    }
  }
  for (auto& [joint, damping] : dampings) {
    if (damping > 0) joint->set("damping", damping);
  }
}

// Viscous damping of a spring: MechanicalDamping gives it, ConstraintRelaxationTimeDamping gives the time
// (b = t k); the default is AGX's: a relaxation time of two time steps.
double Lowering::spring_damping(const sn::Interaction1D& i, double k) {
  const sn::Damping& d = i.damping;
  if (!d.given) return 0.0;
  if (d.damping_constant) return *d.damping_constant;
  if (d.relaxation_time) return *d.relaxation_time * k;
  return 2 * options_.timestep * k;
}

// MuJoCo's velocity actuator pushes explicitly: stable under Euler only while kv h / I_eff < 2. Half of the
// limit keeps tracking fast (the velocity error halves every step) with margin.
double Lowering::velocity_gain(double gain, Element& joint, const sn::Interaction1D& motor) {
  const double inertia = effective_inertia(joint);
  if (!(inertia > 0)) return gain;
  // The limit holds for the sum of the gains on one joint: share it among its velocity motors.
  const double stable = 0.5 * inertia / options_.timestep / std::max(1, velocity_motors_[&joint]);
  if (gain > stable) {
    note_capped_gain(motor, gain, stable);
    return stable;
  }
  return gain;
}

void Lowering::note_capped_gain(const sn::Interaction1D& motor, double gain, double stable) {
  warn(motor.where, "`" + motor.path + ".gain` " + number(gain) +
                        " would make MuJoCo's explicit velocity motor " +
                        "unstable; emitted kv = " + number(stable) +
                        " (half the stability limit I/h, shared by the joint's velocity motors)");
}

// The inertia the joint drives at the initial pose: the subtree below it, about the joint axis (rotation)
// or its mass (translation).
double Lowering::effective_inertia(Element& joint) {
  const JointInfo& info = joint_info_.at(&joint);
  const sn::Transform& child = snap_.node_world[info.node];
  const Eigen::Vector3d axis = child.rotation * info.axis;
  const Eigen::Vector3d point = child.rotation * info.pos + child.position;
  double total = 0.0;
  std::vector<int> todo{info.node};
  while (!todo.empty()) {
    const int b = todo.back();
    todo.pop_back();
    for (int c : tree_children_[b]) todo.push_back(c);
    auto it = body_mass_.find(b);
    if (it == body_mass_.end()) continue;
    const MassProperties& p = it->second;
    if (!info.rotational) {
      total += p.mass;
      continue;
    }
    const Eigen::Matrix3d r = snap_.node_world[b].rotation.toRotationMatrix();
    const Eigen::Vector3d com = r * p.com + snap_.node_world[b].position;
    total +=
        axis.dot(r * p.inertia * r.transpose() * axis) + p.mass * (com - point).cross(axis).squaredNorm();
  }
  return total;
}

void Lowering::effort_limits(Element& actuator, const sn::Interaction1D& i) {
  double lo = i.min_effort, hi = i.max_effort;
  // A URDF effort limit bounds every motor on its joint, as the robot's actuator would.
  if (auto it = joint_properties_.find(i.mate); it != joint_properties_.end() && it->second->effort > 0) {
    lo = std::max(lo, -it->second->effort);
    hi = std::min(hi, it->second->effort);
  }
  // Always limited (±1e10 when the model gives no limit): every motor model has a range input, and the
  // runtime can tighten only a limited actuator.
  actuator.set("forcelimited", "true")
      .set("forcerange",
           number(std::isfinite(lo) ? lo : -1e10) + " " + number(std::isfinite(hi) ? hi : 1e10));
}

// A URDF velocity limit bounds the speed a velocity motor may be asked for (its control range).
void Lowering::speed_limit(Element& actuator, const sn::Interaction1D& i) {
  auto it = joint_properties_.find(i.mate);
  if (it == joint_properties_.end() || it->second->velocity <= 0) return;
  const double v = it->second->velocity;
  actuator.set("ctrllimited", "true").set("ctrlrange", number(-v) + " " + number(v));
}

}  // namespace openplx::mjcf
