// AGX's constraint law inside MuJoCo's solver (docs/mapping.md "Constraint rows the runtime owns"). AGX
// solves velocity motors, springs, compliant degrees of freedom, ranges, brakes, clutches and gears as
// constraint rows, all together, with SPOOK compliance and damping and force bounds. MuJoCo 2.2.2 solves its
// rows together too, but computes each row's reference acceleration (efc_aref) and softness (efc_R, efc_D)
// from solref/solimp itself. After mj_fwdVelocity has built the rows and before the solve, the runtime
// overwrites them with AGX's law (write), then solves up to twice more, each time shifting the rigid rows'
// reference by their softness times the force just found (refine), so that a rigid row ends exact while
// Newton's method still sees a well-conditioned problem. ../shared/design/owned-rows.md measured the idea.
//
// One ConstraintRows holds the rows of one model's laws (mjcf::RuntimeLaw) on one mjData. It is driven
// either by the process-wide mjcb_control (row_hook.h: a bridge around the user's mj_step) or by the
// Simulation's own step, between mj_step1 and mj_step2.
#pragma once

#include <mujoco/mujoco.h>

#include <cstddef>
#include <string>
#include <vector>

#include "contract/signal_binding.h"

namespace openplx::runtime {

class ConstraintRows {
 public:
  // Takes over the stand-ins the laws name (a velocity motor's or spring's actuator gain, the joint damping a
  // spring's stand-in added, noslip) in `m` and records the rows. Idempotent per model: a second mjData on
  // the same mjModel resolves the same rows. Returns the problems of laws that did not fit the model.
  std::vector<std::string> resolve(mjModel* m, const std::vector<mjcf::RuntimeLaw>& laws);
  // Lets go of the model: the last ConstraintRows on it puts its stand-ins back (the MJCF's own behaviour).
  // Before the model is deleted.
  void release();
  ConstraintRows() = default;
  ConstraintRows(const ConstraintRows&) = delete;
  ConstraintRows& operator=(const ConstraintRows&) = delete;
  ~ConstraintRows() { release(); }
  bool empty() const { return motors_.empty() && springs_.empty() && compliances_.empty() && rigid_.empty(); }

  // The step's rows in AGX's law: after mj_fwdVelocity, before mj_fwdConstraint.
  void write(const mjModel* m, mjData* d);
  // After an extra solve: the rigid rows' references shifted by R (f - f_estimate); returns the largest
  // change of a rigid row's velocity this makes (R h |f - f_estimate|), in the rows' units.
  double refine(const mjModel* m, mjData* d);
  // write, then the extra solves.
  void control(const mjModel* m, mjData* d);
  // The same for every set of rows on one mjData (several bridges): all written, then solved together.
  static void control(const mjModel* m, mjData* d, ConstraintRows* const* all, size_t count);
  // After the step's solve: springs' actuator force (and its actuatorfrc sensors) = the centre + the row's
  // force.
  void after_step(const mjModel* m, mjData* d);

  // The softness of a rigid row, a fraction of its diagonal: small enough that what it leaves after two
  // refinements is below 1e-9 of the step's change, large enough that Newton's line search resolves it.
  static constexpr double kRigidSoftness = 1e-6;
  // Extra solves per step; each cuts a rigid row's error about 500-fold (owned-rows.md, exp5).
  static constexpr int kRefinements = 2;
  // Velocity error (in the row's units per second) below which a step skips the extra solves.
  static constexpr double kRefineTolerance = 1e-10;

 private:
  struct Rigid {
    int type = -1, id = -1;          // mjtConstraint and object id of its rows
    double target = 0;               // velocity target (a motor's)
    int actuator = -1;               // a velocity motor's stand-in
    std::vector<double> force;       // per row of the object: the force of the last solve (its estimate)
    std::vector<double> last_final;  // per row: the force the last step ended with
    std::vector<int> rows;           // this step's row indices
    int previous_rows = 0;           // how many it had the step before
  };
  struct Spring {
    int actuator = -1, tendon = -1, row = -1;
    double stiffness = 0, relaxation_time = 0;
    std::vector<int> sensors;  // actuatorfrc sensors of the actuator
  };
  struct Compliance {
    int equality = -1;
    double stiffness = 0, relaxation_time = 0;
  };
  void add_rigid(int type, int id, int actuator);
  bool write_step(const mjModel* m, mjData* d);  // write; whether this step needs the extra solves
  void write_rigid(const mjModel* m, mjData* d, Rigid& r, int row, int k);
  std::vector<Rigid> motors_, rigid_;
  std::vector<Spring> springs_;
  std::vector<Compliance> compliances_;
  // object id -> index: per constraint type, which Rigid (motors_ first, then rigid_ offset by motors_)
  std::vector<std::vector<int>> by_type_;
  std::vector<int> spring_of_tendon_, compliance_of_equality_;
  // Whether the next step needs the extra solves: after_step found the last final solve moved the rigid rows'
  // forces by more than the shift resolves, or was not called.
  bool needs_refinement_ = true;
  bool changed_ = false;      // this step's rows differ from the last (a new row, a new motor target)
  mjModel* model_ = nullptr;  // the model whose stand-ins it took over (release)
};

// Row i's softness R (and D = 1 / R; the diagonal of A + R that the dual solvers, PGS and noslip, read).
void set_row_softness(const mjModel* m, mjData* d, int i, double softness);

}  // namespace openplx::runtime
