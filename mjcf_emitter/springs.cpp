// Lowering pass, springs (docs/mapping.md "Springs"). AGX solves a spring as one constraint row: compliance
// 1/k, SPOOK damping (a relaxation time), its force bounded by the effort range, solved with everything else
// at the velocity level, so it brakes as hard as its limit allows. MuJoCo 2.2.2's only force-bounded row is
// friction loss, whose reference acceleration has no position term; the runtime gives it one (RuntimeLaw
// Spring: the row's reference and softness are written between mj_step1 and mj_step2). The MJCF alone
// carries the nearest static law: an actuator pushing k (rest - q) - b qdot clamped to the effort range.
#include <algorithm>
#include <cmath>

#include "mjcf_emitter/lowering.h"

namespace openplx::mjcf {

// The MJCF stand-in: its own rest (the actuator's control) and effort limits, f = k (rest - q) - b qdot
// clamped to [min, max]. An unlimited spring's damping joins that force while explicit Euler keeps it stable
// (b h below the inertia driven), else it goes to the joint, where Euler integrates it implicitly. A limited
// spring keeps its damping inside the clamp (joint damping would push beyond the limit), below the inertia
// per step (0.8 I / h). The fixed tendon NAME (the joint alone) carries the runtime's row; it has no friction
// loss until the runtime gives it one (and so does not ask for noslip, emitter.cpp).
void Lowering::emit_spring(Element& root, Element& actuators, const sn::Interaction1D& i, Element& joint,
                           std::map<Element*, double>& dampings) {
  const double k = i.stiffness, inertia = effective_inertia(joint), h = options_.timestep;
  double b = spring_damping(i, k);
  const auto [low, high] = effort_range(i);
  const bool limited = low > -kNoEffortLimit || high < kNoEffortLimit;
  const bool clamped_damping = limited || b * h < inertia;
  if (limited && inertia > 0) b = std::min(b, 0.8 * inertia / h);
  if (!clamped_damping) dampings[&joint] += b;
  const std::string spring = name(i.path);
  Element& a = actuators.add("general");
  a.set("name", spring)
      .set("joint", *joint.get("name"))
      .set("gainprm", k)
      .set("biastype", "affine")
      .set("biasprm", "0 " + number(-k) + " " + number(clamped_damping ? -b : 0.0));
  effort_limits(a, i);
  if (!i.enabled) a.set("gear", "0");  // transmits nothing until its enable input restores the gear
  const int index = index_in(system_.interactions, i);
  effort_ranges_[index] = effort_range(i);
  actuator_ctrl_[index] = {static_cast<int>(actuator_count_++), i.rest};
  springs_[index] = spring;
  if (!(k > 0)) return;  // no stiffness, no compliance row: the actuator's damping is all there is
  Element* tendons = root.child("tendon");
  if (!tendons) tendons = &root.add("tendon");
  Element& tendon = tendons->add("fixed");
  tendon.set("name", spring);
  tendon.add("joint").set("joint", *joint.get("name")).set("coef", 1.0);
  RuntimeLaw law;
  law.kind = RuntimeLaw::Kind::Spring;
  law.path = i.path;
  law.actuators = {spring};
  law.parameter = spring_relaxation_time(i, k);
  law.stiffness = k;
  law.joint_damping = clamped_damping ? 0.0 : b;
  laws_.push_back(std::move(law));
}

// SPOOK relaxation time of a spring (s): ConstraintRelaxationTimeDamping gives it, MechanicalDamping gives
// b = t k; AGX's default otherwise. Without a dissipation model, none.
double Lowering::spring_relaxation_time(const sn::Interaction1D& i, double k) {
  const sn::Damping& d = i.damping;
  if (!d.given) return 0.0;
  if (d.damping_constant) return k > 0 ? *d.damping_constant / k : 0.0;
  if (d.relaxation_time) return *d.relaxation_time;
  return kDefaultRelaxationTime;
}

// Viscous damping of a spring (N s/m, N m s/rad): MechanicalDamping as given, else relaxation time x k.
double Lowering::spring_damping(const sn::Interaction1D& i, double k) {
  const sn::Damping& d = i.damping;
  if (d.given && d.damping_constant) return *d.damping_constant;
  return spring_relaxation_time(i, k) * k;
}

}  // namespace openplx::mjcf
