// Lowering pass, velocity motors as constraints (docs/mapping.md "Velocity motors"). AGX solves a velocity
// motor as a 1-D velocity constraint whose force stays within the effort range. MuJoCo 2.2.2 has one
// force-bounded velocity constraint: friction loss, which holds a velocity at zero. So each motor gets a
// reference joint that turns at the target speed, and a fixed tendon (motor joint minus reference) whose
// friction loss holds the two together with at most (max - min)/2; a constant force (max + min)/2 on the
// motor joint centres that band on [min, max].
#include <cmath>
#include <string_view>

#include "mjcf_emitter/lowering.h"

namespace openplx::mjcf {

namespace {

// The reference joint outweighs what the motor drives by this factor, so the motor's reaction tau turns it
// by tau h / (1e9 I) before its servo takes that back in the next step: with noslip (emitter.cpp) making the
// friction row exact, that is the motor's whole tracking error (a motor reaching its target in one step
// is 1e-9 short of it; 1e-6 at a ratio of 1e6). The reference joints dominate MuJoCo's mean inertia, by
// which its solver divides its stopping test: emitter.cpp tightens the tolerance to match.
constexpr double kReferenceInertiaRatio = 1e9;

}  // namespace

void Lowering::emit_velocity_motor(Element& root, const sn::Interaction1D& i, const std::string& joint,
                                   double inertia) {
  const double h = options_.timestep;
  const std::string motor = name(i.path);
  if (i.gain && inertia > 0 && *i.gain * h < inertia) {
    warn(i.where, "`" + i.path + ".gain` " + number(*i.gain) +
                      " makes a motor slower than one time step, which MuJoCo's motor constraint cannot "
                      "express; the motor was emitted rigid (it reaches its target within a step)");
  }
  const double armature = kReferenceInertiaRatio * (inertia > 0 ? inertia : 1.0);
  Element& body = world_->add("body");
  body.set("name", motor + "/reference").set("pos", "0 0 0");
  body.add("joint")
      .set("name", motor + "/reference")
      .set("type", "hinge")
      .set("axis", "0 0 1")
      .set("armature", armature);
  body.add("inertial").set("pos", "0 0 0").set("mass", 1.0).set("diaginertia", "1 1 1");

  auto [lo, hi] = effort_range(i);
  const bool open_below = lo <= -kNoEffortLimit, open_above = hi >= kNoEffortLimit;
  if (open_below != open_above) {
    // A band open on one side would need an enormous centring force, which the friction row's softness
    // turns into creep; the open side is closed instead, as wide again as the closed side is far from 0.
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
  // A disabled motor pushes with nothing until its enable input restores the band.
  const double band = i.enabled ? (hi - lo) / 2 : 0.0, centre = i.enabled ? (hi + lo) / 2 : 0.0;
  Element* tendons = root.child("tendon");
  if (!tendons) tendons = &root.add("tendon");
  Element& tendon = tendons->add("fixed");
  tendon.set("name", motor)
      .set("frictionloss", band)
      .set("solreffriction", rigid_solref())  // a load a0 on the joint leaves a creep of h (1 - d) a0
      .set("solimpfriction", rigid_solimp());
  tendon.add("joint").set("joint", joint).set("coef", 1.0);
  tendon.add("joint").set("joint", motor + "/reference").set("coef", -1.0);

  // The reference follows its control in one explicit step: kv h / (armature + its body's 1 kg m^2) = 1.
  Element& actuators = *root.child("actuator");
  Element& drive = actuators.add("velocity");
  drive.set("name", motor).set("joint", motor + "/reference").set("kv", (armature + 1) / h);  // + its body
  speed_limit(drive, i);
  actuator_ctrl_[k] = {static_cast<int>(actuator_count_++),
                       i.target_speed.value_or(i.shaft >= 0 ? 1.0 : 0.0)};
  velocity_motors_[k] = motor;
  if (hi + lo != 0 || has_range_input(k)) {  // the runtime moves the band by moving this force
    actuators.add("general")
        .set("name", motor_bias_name(motor))
        .set("joint", joint)
        .set("gainprm", "0")
        .set("biastype", "affine")
        .set("biasprm", number(centre) + " 0 0");
    ++actuator_count_;
  }
}

// MuJoCo divides its solvers' stopping tests (main and noslip) by the model's mean diagonal inertia. The
// reference joints weigh a billion times what they drive and would inflate that mean as much, so the
// solvers stopped before converging (a 7-link arm of motors sagged; the runtime's hardened rows were
// solved loosely). `<statistic meaninertia>` gives MuJoCo the mean over the model's own degrees of freedom.
void Lowering::write_mean_inertia(Element& root, const mjModel& draft) {
  constexpr std::string_view kSuffix = "/reference";
  double sum = 0;
  int count = 0;
  for (int j = 0; j < draft.njnt; ++j) {
    const std::string_view joint_name(draft.names + draft.name_jntadr[j]);
    if (joint_name.ends_with(kSuffix)) continue;
    const int dofs = draft.jnt_type[j] == mjJNT_FREE ? 6 : draft.jnt_type[j] == mjJNT_BALL ? 3 : 1;
    for (int k = 0; k < dofs; ++k) sum += draft.dof_M0[draft.jnt_dofadr[j] + k];
    count += dofs;
  }
  if (count > 0 && sum > 0) root.add("statistic").set("meaninertia", sum / count);
}

bool Lowering::has_range_input(int interaction) const {
  return std::any_of(view_.signals.begin(), view_.signals.end(), [&](const sn::Signal& s) {
    return s.input && s.source_kind == sn::SignalSource::Interaction && s.source == interaction &&
           any_of(signal_stem(s.type), {"TorqueRange", "ForceRange"});
  });
}

}  // namespace openplx::mjcf
