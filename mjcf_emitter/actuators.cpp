// Lowering pass, actuators: ranges as joint limits, springs (springs.cpp), velocity motors as motor
// constraints (velocity_motors.cpp), force motors as <motor>s, all with their effort limits.
#include "mjcf_emitter/lowering.h"

#include <cmath>

namespace openplx::mjcf {

// A range is a hard row in AGX. MuJoCo's limit row under a push a0 (the acceleration the push alone would
// give) rests (1 - d)/d a0/k past the limit, k = 1 / (d tc)^2: with MuJoCo's stiffest impedance d = 0.9999
// and the shortest critically damped time constant an explicit step keeps stable, tc = 2h, that is
// 4e-4 h^2 a0 (4.8e-6 rad for 5,000 N m on 1.67 kg m^2 at h = 0.002). MuJoCo's default (0.02 s, d 0.95)
// left 0.06 rad there. A limit acts once violated, so a joint arriving at speed v also enters by up to
// v h + a0 h^2 in its last free step, which the row takes back critically damped (no bounce).
namespace {

void hard_stop(Element& limited, double h) {
  limited.set("solreflimit", number(2 * h) + " 1")
      .set("solimplimit", number(kRigidImpedance) + " " + number(kRigidImpedance) + " 0.001 0.5 2");
}

}  // namespace

void Lowering::emit_actuators(Element& root) {
  Element& actuators = root.add("actuator");
  using K = sn::Interaction1D::Kind;
  // Ranges are joint limits: several on one joint intersect.
  std::map<Element*, std::pair<double, double>> ranges;
  std::map<Element*, double> dampings;
  for (const sn::JointProperties& p : system_.joint_properties) {
    if (p.mate >= 0) joint_properties_[p.mate] = &p;
  }
  for (const sn::Interaction1D& i : system_.interactions) {
    if (i.shaft >= 0) {
      emit_shaft_motor(root, i);
      continue;
    }
    if (i.kind == K::DistanceRange || i.kind == K::DistanceMotor) {
      emit_distance_interaction(root, actuators, i);
      continue;
    }
    if (i.kind == K::Steering) {
      emit_steering(root, i);
      continue;
    }
    if ((i.kind == K::LinearRange || i.kind == K::RotationalRange) && i.start == -sn::kInf &&
        i.end == sn::kInf)
      continue;  // no limit either way: nothing to express
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
      warn(i.where, "`" + i.path + "` acts on `" + system_.mates[i.mate].path + "`, whose joint has no " +
                        (rotational ? "rotational" : "linear") + " degree of freedom; it was left out");
      continue;
    }
    const std::string joint_name = *joint->get("name");
    switch (i.kind) {
      case K::LinearRange:
      case K::RotationalRange: {
        const double lo = i.start, hi = i.end;
        range_joints_[index_in(system_.interactions, i)] = joint_name;
        hard_stop(*joint, options_.timestep);  // also while disabled: its enable input switches the limit on
        if (!i.enabled) break;                 // its enable input sets the limit
        auto [it, fresh] = ranges.try_emplace(joint, lo, hi);
        if (!fresh) it->second = {std::max(it->second.first, lo), std::min(it->second.second, hi)};
        break;
      }
      case K::LinearSpring:
      case K::TorsionSpring:
        emit_spring(root, actuators, i, *joint, dampings);  // springs.cpp
        break;
      case K::LinearVelocityMotor:
      case K::RotationalVelocityMotor: {
        emit_velocity_motor(root, i, joint_name, effective_inertia(*joint));
        break;
      }
      case K::ForceMotor:
      case K::TorqueMotor:
        emit_effort_motor(actuators, i, joint_name);
        break;
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
  for (auto& [joint, damping] : dampings) {
    if (damping > 0) joint->set("damping", damping);
  }
  emit_drive_actuators(actuators);
}

// A force or torque motor: a <motor> pushing its control (the default effort at first) within its effort
// range.
void Lowering::emit_effort_motor(Element& actuators, const sn::Interaction1D& i, const std::string& joint) {
  Element& a = actuators.add("motor");
  a.set("name", name(i.path)).set("joint", joint).set("gear", "1");
  effort_limits(a, i);
  if (!i.enabled) a.set("gear", "0");  // transmits nothing until its enable input restores the gear
  const int index = index_in(system_.interactions, i);
  effort_ranges_[index] = effort_range(i);
  actuator_ctrl_[index] = {static_cast<int>(actuator_count_++), i.default_effort};
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

// The effort range of a motor or spring: its own limits, narrowed by its URDF joint's effort limit (which
// bounds every motor on the joint, as the robot's actuator would); +-1e10 stands for no limit.
std::pair<double, double> Lowering::effort_range(const sn::Interaction1D& i) {
  double lo = i.min_effort, hi = i.max_effort;
  if (auto it = joint_properties_.find(i.mate); it != joint_properties_.end() && it->second->effort > 0) {
    lo = std::max(lo, -it->second->effort);
    hi = std::min(hi, it->second->effort);
  }
  return {std::isfinite(lo) ? lo : -kNoEffortLimit, std::isfinite(hi) ? hi : kNoEffortLimit};
}

void Lowering::effort_limits(Element& actuator, const sn::Interaction1D& i) {
  // Always limited: every motor model has a range input, and the runtime can tighten only a limited actuator.
  const auto [lo, hi] = effort_range(i);
  actuator.set("forcelimited", "true").set("forcerange", number(lo) + " " + number(hi));
}

// A URDF velocity limit bounds the speed a velocity motor may be asked for (its control range).
void Lowering::speed_limit(Element& actuator, const sn::Interaction1D& i) {
  auto it = joint_properties_.find(i.mate);
  if (it == joint_properties_.end() || it->second->velocity <= 0) return;
  const double v = it->second->velocity;
  actuator.set("ctrllimited", "true").set("ctrlrange", number(-v) + " " + number(v));
}

}  // namespace openplx::mjcf

namespace openplx::mjcf {

// A DistanceRange keeps two connectors' distance within [start, end]: a spatial tendon between sites at them
// with that length range, MuJoCo's tendon limit. A DistanceMotor drives that distance's rate: MuJoCo cannot
// bound a velocity constraint on a spatial tendon, so it is a velocity servo on the tendon (gain half the
// distance's effective mass per step: half the way to the target each step, stable for masses off by 4x)
// within its effort range, with a warning.
void Lowering::emit_distance_interaction(Element& root, Element& actuators, const sn::Interaction1D& i) {
  const int a = i.connectors[0], b = i.connectors[1];
  if (a < 0 || b < 0 || vertex_of_connector(a) == vertex_of_connector(b)) {
    warn(i.where, "`" + i.path + "` needs two connectors on different bodies; it was left out");
    return;
  }
  // A connector of a nested system (a composite's end nobody bound, e.g. an actuator's) belongs to no body:
  // MuJoCo holds it in the world, which is rarely what was meant.
  for (const int c : {a, b}) {
    const int owner = system_.connectors[c].owner;
    if (owner >= 0 && owner != system_.root && !is_body(owner)) {
      warn(i.where, "`" + i.path + "` acts on `" + system_.connectors[c].path + "`, which belongs to `" +
                        system_.nodes[owner].path +
                        "`, not to a body: that end is fixed in the world (bind it to a body's connector)");
    }
  }
  const bool range = i.kind == sn::Interaction1D::Kind::DistanceRange;
  if (range && (!(i.end > i.start) || i.start < 0)) {
    warn(i.where, "`" + i.path + "` has no distance range (start " + number(i.start) + ", end " +
                      number(i.end) + "); it was left out");
    return;
  }
  Element* tendons = root.child("tendon");
  if (!tendons) tendons = &root.add("tendon");
  Element& tendon = tendons->add("spatial");
  tendon.set("name", name(i.path));
  if (range) {
    tendon.set("limited", i.enabled ? "true" : "false").set("range", number(i.start) + " " + number(i.end));
    hard_stop(tendon, options_.timestep);
  }
  tendon.add("site").set("site", site_for(a));
  tendon.add("site").set("site", site_for(b));
  const int index = index_in(system_.interactions, i);
  distance_tendons_[index] = name(i.path);
  if (range) return;
  double inverse_mass = 0;  // of the distance: both bodies' (the world's is zero)
  for (int c : {a, b}) {
    const int n = vertex_of_connector(c);
    if (n >= 0 && !is_static(n))
      inverse_mass += 1 / std::max(body_mass_.count(n) ? body_mass_.at(n).mass : 1.0, 1e-9);
  }
  const double kv = inverse_mass > 0 ? 0.5 / (inverse_mass * options_.timestep) : 0.0;
  if (kv == 0) warn(i.where, "`" + i.path + "` joins two ends neither of which can move: it drives nothing");
  Element& motor = actuators.add("general");
  motor.set("name", name(i.path))
      .set("tendon", name(i.path))
      .set("gainprm", kv)
      .set("biastype", "affine")
      .set("biasprm", "0 0 " + number(-kv));
  effort_limits(motor, i);
  if (!i.enabled) motor.set("gear", "0");
  effort_ranges_[index] = effort_range(i);
  actuator_ctrl_[index] = {static_cast<int>(actuator_count_++), i.target_speed.value_or(0.0)};
  warn(i.where, "`" + i.path +
                    "` is a velocity servo here (MuJoCo has no force-limited velocity constraint on a "
                    "distance): it closes half its speed error each step instead of meeting it at once");
}

}  // namespace openplx::mjcf
