// Lowering pass, compliant degrees of freedom (docs/mapping.md "Constraint rows the runtime owns"): an
// elastic tire's six directions on its rim. AGX holds each with a compliance row (1/k, SPOOK damping of
// relaxation time tau), which is stable at any time step. MuJoCo's joint stiffness is integrated explicitly
// and a tire's (3e5 N/m on 0.12 kg) blows up; so each direction is a joint held at 0 by a joint equality,
// which the runtime makes AGX's row (RuntimeLaw::Compliance). The MJCF alone keeps MuJoCo's soft equality
// with the spring's own period where the step resolves it, else the stiffest it holds (time constant 2 h).
#include <algorithm>
#include <cmath>

#include "mjcf_emitter/lowering.h"

namespace openplx::mjcf {

void Lowering::emit_compliant_dofs(Element& root) {
  if (compliant_dofs_.empty()) return;
  Element* equality = root.child("equality");
  if (!equality) equality = &root.add("equality");
  const double h = options_.timestep;
  for (const CompliantDof& c : compliant_dofs_) {
    const double period = c.inertia > 0 ? std::sqrt(c.inertia / c.stiffness) : 0.0;  // 1 / omega
    if (period < 2 * h) {
      warn(c.where, "`" + c.path + "` stiffness " + number(c.stiffness) +
                        " is stiffer than MuJoCo's own constraints hold at a " + number(h) +
                        " s step; the openplx2mjcf runtime solves it exactly as AGX's compliance, "
                        "the MJCF alone holds it softer (time constant " +
                        number(2 * h) + " s)");
    }
    const std::string name = c.joint + "/compliance";
    equality->add("joint")
        .set("name", name)
        .set("joint1", c.joint)
        .set("solref", number(std::max(2 * h, period)) + " 1")
        .set("solimp", rigid_solimp());
    compliant_equalities_.insert(name);
    RuntimeLaw law;
    law.kind = RuntimeLaw::Kind::Compliance;
    law.path = c.path.substr(0, c.path.find(' '));
    law.equalities = {name};
    law.stiffness = c.stiffness;
    law.parameter = c.relaxation_time;
    laws_.push_back(std::move(law));
  }
}

}  // namespace openplx::mjcf
