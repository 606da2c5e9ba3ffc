// Springs as AGX solves them (mjcf::RuntimeLaw::Kind::Spring, docs/mapping.md "Springs"): one constraint row
// per spring with compliance 1/k, SPOOK damping and its force bounded by the effort range. MuJoCo 2.2.2's
// force-bounded row is friction loss; between mj_step1 and mj_step2 each spring's friction row (its fixed
// tendon, the joint alone) gets the SPOOK reference acceleration and softness, so MuJoCo's solver finds the
// row force with every other constraint, clamped to the range. The MJCF's spring actuator keeps the centre
// of an asymmetric range and the switches (rest = ctrl, range = forcerange, enabled = gear); its force output
// becomes the spring's whole force after the step.
#pragma once

#include <mujoco/mujoco.h>

#include <vector>

#include "mjcf_emitter/signal_binding.h"

namespace openplx::runtime {

class SpringRows {
 public:
  // Takes over the spring's stand-in (the actuator's stiffness and damping, the damping it put on the joint)
  // and gives its tendon a friction row. False, leaving the stand-in, when the model does not fit.
  bool resolve(mjModel* m, const mjcf::RuntimeLaw& law);
  // After mj_step1 (the rows exist), before mj_step2.
  void write_rows(mjModel* m, mjData* d);
  // After mj_step2: each spring actuator's force (and its actuatorfrc sensors) = the centre + the row's
  // force.
  void add_row_forces(const mjModel* m, mjData* d) const;
  // A model with friction-row drives asks MuJoCo for noslip, which would re-solve the springs' rows without
  // their softness (rigid servos). With springs here, the runtime turns noslip off and hardens the other
  // friction rows itself (write_rows).
  void take_over_noslip(mjModel* m);
  bool empty() const { return springs_.empty() && !harden_other_friction_rows_; }

 private:
  struct Spring {
    int actuator = -1, tendon = -1;
    double stiffness = 0, relaxation_time = 0;
    std::vector<int> sensors;  // actuatorfrc sensors of the actuator
    int row = -1;              // its friction row in this step, -1 when MuJoCo built none
  };
  std::vector<Spring> springs_;
  std::vector<int> spring_of_tendon_;        // per tendon: its spring, -1
  bool harden_other_friction_rows_ = false;  // take_over_noslip
};

}  // namespace openplx::runtime
