// Lowering pass, velocity motors as constraints (docs/mapping.md "Velocity motors"). AGX solves a velocity
// motor as a 1-D velocity constraint whose force stays within the effort range, solved with every other row.
// The runtime does the same inside MuJoCo's solver (runtime/constraint_rows.h, RuntimeLaw::VelocityMotor):
// the fixed tendon of the motor's name (its joint alone) gets a friction row whose reference is the target
// speed, bounded by the band's half width about its centre. The MJCF alone carries the nearest element
// MuJoCo has: a <velocity> servo on the joint within the effort range, as stiff as explicit Euler keeps
// stable (finish_velocity_motors).
#include <cmath>
#include <string_view>

#include "mjcf_emitter/lowering.h"

namespace openplx::mjcf {

void Lowering::emit_velocity_motor(Element& root, const sn::Interaction1D& i, const std::string& joint,
                                   double inertia) {
  const double h = options_.timestep;
  const std::string motor = name(i.path);
  if (i.gain && inertia > 0 && *i.gain * h < inertia) {
    warn(i.where, "`" + i.path + ".gain` " + number(*i.gain) +
                      " makes a motor slower than one time step, which MuJoCo's motor constraint cannot "
                      "express; the motor was emitted rigid (it reaches its target within a step)");
  }
  auto [lo, hi] = effort_range(i);
  const bool open_below = lo <= -kNoEffortLimit, open_above = hi >= kNoEffortLimit;
  if (open_below != open_above) {
    // A band open on one side is centred ~5e9 away from the force it carries, which the row's force
    // resolves only to about 1e-6 of; the open side is closed instead, as wide again as the closed side is
    // far from 0.
    const double finite = open_below ? hi : lo, width = 2 * std::max(std::abs(finite), 1.0);
    (open_below ? lo : hi) = open_below ? hi - width : lo + width;
    warn(i.where,
         "`" + i.path + (open_below ? ".min_effort" : ".max_effort") +
             "` is unlimited while the other side is limited, which MuJoCo's motor constraint cannot "
             "express; it was limited at " +
             number(open_below ? lo : hi));
  }
  const int k = index_in(view_.interactions, i);
  effort_ranges_[k] = {lo, hi};
  Element* tendons = root.child("tendon");
  if (!tendons) tendons = &root.add("tendon");
  Element& tendon = tendons->add("fixed");
  tendon.set("name", motor);  // no friction loss: the runtime gives it the row
  tendon.add("joint").set("joint", joint).set("coef", 1.0);

  // The stand-in; its kv is set from the draft model's inertia (finish_velocity_motors).
  Element& actuators = *root.child("actuator");
  Element& drive = actuators.add("velocity");
  drive.set("name", motor)
      .set("joint", joint)
      .set("kv", inertia > 0 ? inertia / h : 1.0)
      .set("forcelimited", "true")
      .set("forcerange", number(lo) + " " + number(hi));
  if (!i.enabled) drive.set("gear", "0");  // pushes with nothing until its enable input restores the gear
  speed_limit(drive, i);
  actuator_ctrl_[k] = {static_cast<int>(actuator_count_++),
                       i.target_speed.value_or(i.shaft >= 0 ? 1.0 : 0.0)};
  velocity_motors_[k] = motor;
  velocity_servos_.push_back({&drive, joint});
  RuntimeLaw law;
  law.kind = RuntimeLaw::Kind::VelocityMotor;
  law.path = i.path;
  law.actuators = {motor};
  laws_.push_back(std::move(law));
}

// The stand-in servos' gains from the draft model's mass matrix at the initial pose. Explicit Euler moves
// the velocities by -h M^-1 K v per step (K the servos' gains): stable while h M^-1 K's eigenvalues stay
// below
// 2. They are real, not negative, and sum to its trace, sum_j h kv_j (M^-1)_jj; giving each of the n servos
// in a kinematic tree kv_j = 1 / (n h (M^-1)_jj) makes that trace 1, so no eigenvalue exceeds 1 however the
// chain couples them. A single servo then reaches its target in one step, as the motor does.
void Lowering::finish_velocity_motors(const DraftModel& draft) {
  if (velocity_servos_.empty() || !draft.model()) return;
  const mjModel& m = *draft.model();
  std::vector<std::string> joints;
  for (const VelocityServo& s : velocity_servos_) joints.push_back(s.joint);
  const std::vector<double> mobility = draft.mobilities(joints);
  auto tree = [&](const std::string& joint) {
    const int j = draft.joint_id(joint);
    return j < 0 ? -1 : m.body_rootid[m.jnt_bodyid[j]];
  };
  std::map<int, int> servos_in_tree;
  for (const std::string& joint : joints) ++servos_in_tree[tree(joint)];
  const double h = options_.timestep;
  for (size_t k = 0; k < joints.size(); ++k) {
    if (mobility[k] > 0)
      velocity_servos_[k].drive->set("kv", 1 / (servos_in_tree[tree(joints[k])] * h * mobility[k]));
  }
}

bool Lowering::has_range_input(int interaction) const {
  return std::any_of(view_.signals.begin(), view_.signals.end(), [&](const sn::Signal& s) {
    return s.input && s.source_kind == sn::SignalSource::Interaction && s.source == interaction &&
           any_of(signal_stem(s.type), {"TorqueRange", "ForceRange"});
  });
}

}  // namespace openplx::mjcf
