// Lowering pass, velocity motors as constraints (docs/mapping.md "Velocity motors"). AGX solves a velocity
// motor as a 1-D velocity constraint whose force stays within the effort range, solved with every other row.
// The runtime does the same inside MuJoCo's solver (runtime/constraint_rows.h, RuntimeLaw::VelocityMotor):
// the fixed tendon of the motor's name (its joint alone) gets a friction row whose reference is the target
// speed, bounded by the band's half width about its centre. The MJCF alone carries a stand-in, one of two
// (finish_velocity_stand_ins):
// - a damper b = I / h on the joint (Euler integrates joint damping implicitly, stable at any step) and an
//   actuator pushing b * target: the joint is driven by b (target - v), which holds a chain of motors (a
//   7-link arm sags 0.4 rad in 5 s where a bounded servo lets it fall), but its force is not bounded by the
//   effort band. Taken when the model has no equality: Euler's implicit damping scales a damped joint's share
//   of an equality's correction down, so a gear behind such a motor came apart by half the step's change and
//   a differential diverged.
// - else a <velocity> servo within the effort band, its kv as stiff as explicit Euler keeps stable in any
//   chain: kv_j = 1 / (n h (M^-1)_jj) for the n servos of a kinematic tree (h M^-1 K then has eigenvalues in
//   [0, 1]); a lone motor reaches its target in one step, a chain is held loosely.
#include <cmath>
#include <string>

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
  const int k = index_in(system_.interactions, i);
  effort_ranges_[k] = {lo, hi};
  Element* tendons = root.child("tendon");
  if (!tendons) tendons = &root.add("tendon");
  Element& tendon = tendons->add("fixed");
  tendon.set("name", motor);  // no friction loss: the runtime gives it the row
  tendon.add("joint").set("joint", joint).set("coef", 1.0);

  // The stand-in, completed by finish_velocity_stand_ins. Its force range carries the effort band for the
  // runtime's row (and range inputs) either way.
  Element& actuators = *root.child("actuator");
  Element& drive = actuators.add("general");
  drive.set("name", motor).set("joint", joint).set("forcerange", number(lo) + " " + number(hi));
  if (!i.enabled) drive.set("gear", "0");  // pushes with nothing until its enable input restores the gear
  speed_limit(drive, i);
  actuator_ctrl_[k] = {static_cast<int>(actuator_count_++),
                       i.target_speed.value_or(i.shaft >= 0 ? 1.0 : 0.0)};
  velocity_motors_[k] = motor;
  RuntimeLaw law;
  law.kind = RuntimeLaw::Kind::VelocityMotor;
  law.path = i.path;
  law.actuators = {motor};
  stand_ins_.push_back({&drive, joint, inertia > 0 ? inertia : 1.0, laws_.size()});
  laws_.push_back(std::move(law));
}

// Chooses the stand-ins (see the top of this file): dampers when the model has no equality, else servos,
// whose gains finish_servo_gains sets from the draft model.
void Lowering::finish_velocity_stand_ins(Element& root) {
  if (stand_ins_.empty()) return;
  const Element* equality = root.child("equality");
  stand_in_servos_ = equality && !equality->children().empty();
  const double h = options_.timestep;
  std::map<std::string, double> dampers;
  for (const VelocityStandIn& s : stand_ins_) {
    const double gain = s.inertia / h;
    s.drive->set("gainprm", gain).set("biastype", "affine");
    if (stand_in_servos_) {
      s.drive->set("biasprm", "0 0 " + number(-gain)).set("forcelimited", "true");
      continue;
    }
    s.drive->set("biasprm", "0 0 0").set("forcelimited", "false");  // limited, it would clamp b * target
    dampers[s.joint] += gain;
    laws_[s.law].joint_damping = gain;
  }
  if (dampers.empty()) return;
  for_each_joint(root, [&](Element& joint) {
    auto it = dampers.find(*joint.get("name"));
    if (it == dampers.end()) return;
    const std::string* had = joint.get("damping");  // URDF damping, a spring's damper
    joint.set("damping", (had ? std::stod(*had) : 0.0) + it->second);
  });
}

// The servos' gains from the draft model's mass matrix at the initial pose. Explicit Euler moves the
// velocities by -h M^-1 K v per step (K the servos' gains): stable while h M^-1 K's eigenvalues stay below 2.
// They are real, not negative, and sum to its trace, sum_j h kv_j (M^-1)_jj; kv_j = 1 / (n h (M^-1)_jj) for
// the n servos in a kinematic tree makes that trace 1.
void Lowering::finish_servo_gains(const DraftModel& draft) {
  if (!stand_in_servos_ || !draft.model()) return;
  const mjModel& m = *draft.model();
  std::vector<std::string> joints;
  for (const VelocityStandIn& s : stand_ins_) joints.push_back(s.joint);
  const std::vector<double> mobility = draft.mobilities(joints);
  auto tree = [&](const std::string& joint) {
    const int j = draft.joint_id(joint);
    return j < 0 ? -1 : m.body_rootid[m.jnt_bodyid[j]];
  };
  std::map<int, int> servos_in_tree;
  for (const std::string& joint : joints) ++servos_in_tree[tree(joint)];
  const double h = options_.timestep;
  for (size_t k = 0; k < joints.size(); ++k) {
    if (!(mobility[k] > 0)) continue;
    const double kv = 1 / (servos_in_tree[tree(joints[k])] * h * mobility[k]);
    stand_ins_[k].drive->set("gainprm", kv).set("biasprm", "0 0 " + number(-kv));
  }
}

bool Lowering::has_range_input(int interaction) const {
  return std::any_of(system_.signals.begin(), system_.signals.end(), [&](const sn::Signal& s) {
    return s.input && s.source_kind == sn::SignalSource::Interaction && s.source == interaction &&
           any_of(signal_stem(s.type), {"TorqueRange", "ForceRange"});
  });
}

}  // namespace openplx::mjcf
