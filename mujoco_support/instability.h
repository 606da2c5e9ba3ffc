// MuJoCo's warnings (mjData::warning) told in a user's terms: when, what, which DOF and so which OpenPLX
// joint and body, the values that blew up, and a hint. Shared by the runtime (Simulation::step, the bridge's
// after_step) and the converter's --check, which loads MuJoCo through dlopen: this file therefore reads
// mjModel/mjData struct fields only and calls no MuJoCo function.
//
// Use: remember the counters before a step (WarningCounts::of(d)), take the step, then
//   for (int w : counts.risen(d)) if (warning_severity(w) == WarningSeverity::Wrong) ...
//     describe_warning(m, {w, d->warning[w].lastinfo, time_before_step, ...})
// MuJoCo 2.2.2's mj_checkPos/Vel/Acc reset mjData (time back to 0) before they count the warning, so the
// time and values must be kept from before the reset (the runtime keeps the time from before the step and
// copies the state in MuJoCo's warning callback, which runs before the reset).
#pragma once

#include <mujoco/mujoco.h>

#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace openplx::mjcf {

enum class WarningSeverity {
  Ignore,  // nothing the simulation depends on (mjWARN_VGEOMFULL: visualisation only)
  Note,    // worth telling, the step is still the model's (mjWARN_INERTIA)
  Wrong,   // the state is no longer the model's motion: bad QPOS/QVEL/QACC (MuJoCo reset mjData), bad CTRL
           // (MuJoCo zeroed the controls), contact or constraint buffer full (contacts/constraints dropped)
};
WarningSeverity warning_severity(int warning);  // an mjtWarning; out of range: Ignore

// Whether MuJoCo reset mjData for this warning (mj_resetData: time 0, qpos0, zero velocities).
bool warning_resets(int warning);

// mjData::warning[k].number for every k, to compare after a step.
struct WarningCounts {
  std::array<int, mjNWARNING> number{};
  static WarningCounts of(const mjData* d) {
    WarningCounts c;
    for (int k = 0; k < mjNWARNING; ++k) c.number[static_cast<size_t>(k)] = d->warning[k].number;
    return c;
  }
  // The warnings whose count changed since (a reset zeroes the counters, then MuJoCo counts the one that
  // caused it: a count that went down and up again reads as changed unless it lands on the same number,
  // which `time_went_back` catches for the resetting ones).
  std::vector<int> risen(const mjData* d, bool time_went_back = false) const {
    std::vector<int> out;
    for (int k = 0; k < mjNWARNING; ++k) {
      const bool changed = d->warning[k].number != number[static_cast<size_t>(k)];
      const bool reset_here = time_went_back && warning_resets(k) && d->warning[k].number > 0;
      if ((changed && d->warning[k].number > 0) || reset_here) out.push_back(k);
    }
    return out;
  }
};

// What is known about one warning. Pointers are optional (null: unknown); when given, they hold the state
// MuJoCo saw when it raised the warning (before any reset): m->nq, nv, nv and nu numbers.
struct WarningFacts {
  int warning = 0;  // an mjtWarning
  int info = -1;    // mjData::warning[warning].lastinfo: the qpos index (BADQPOS), the DOF (BADQVEL,
                    // BADQACC, INERTIA), the actuator (BADCTRL), the buffer size (CONTACTFULL, CNSTRFULL)
  double time = 0;  // the simulated time it happened at (before MuJoCo's reset), s
  const double* qpos = nullptr;
  const double* qvel = nullptr;
  const double* qacc = nullptr;
  const double* ctrl = nullptr;
  double emitted_timestep = 0;  // the time step the model was emitted for, s; 0: unknown
  std::string_view prefix;      // stripped from MuJoCo names, leaving OpenPLX paths
};

// The state MuJoCo saw when it first warned during a step: it warns before mj_checkPos/Vel/Acc reset mjData,
// so a warning callback keeps it for the description. clear() before each step.
struct WarnedState {
  bool valid = false;
  double time = 0;
  std::vector<double> qpos, qvel, qacc, ctrl;
  void clear() { valid = false; }
  void capture(const mjModel* m, const mjData* d);  // keeps only the first of a step
  // `warning`'s facts as d counts it, with this state when one was captured, else at `time_before`.
  WarningFacts facts(const mjData* d, int warning, double time_before) const;
};

// One paragraph, no trailing newline, e.g.
//   "at t = 0.07 s MuJoCo found a NaN, infinite or huge acceleration (qacc) at DOF 12, the rotation of joint
//    `car.front_left.hinge` in body `car.front_left` (qpos 1.2, qvel 8.1e9, qacc nan); MuJoCo reset the
//    simulation to its initial state (time 0). hint: the time step is 0.005 s but the model was emitted
//    for 0.002 s; ..."
// m must be the model the warning came from; facts.info out of range is described as such.
std::string describe_warning(const mjModel* m, const WarningFacts& facts);

// "joint `name` in body `name`" for a DOF (the prefix stripped), "DOF n" alone when it has no named joint.
std::string describe_dof(const mjModel* m, int dof, std::string_view prefix);
// The joint and DOF a qpos index belongs to (BADQPOS reports qpos indices); -1 when out of range.
int joint_of_qpos(const mjModel* m, int qpos_index);

}  // namespace openplx::mjcf
