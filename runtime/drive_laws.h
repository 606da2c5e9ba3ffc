// The laws MJCF cannot state (mjcf::RuntimeLaw): engine torque curves with their idle governor and torque
// converters' fluid coupling, written into their actuators before every step; springs as AGX's constraint
// rows (spring_rows.h).
#pragma once

#include <mujoco/mujoco.h>

#include <vector>

#include "mjcf_emitter/signal_binding.h"
#include "runtime/spring_rows.h"

namespace openplx::runtime {

class DriveLaws {
 public:
  // Resolves actuator names to ids (a law whose actuators are missing is skipped) and clears the static
  // stand-ins the MJCF carries (an engine's linear speed falloff). `between_steps`: apply() runs between
  // mj_step1 and mj_step2 (a Simulation), which springs' rows need; otherwise (a bridge around the user's
  // mj_step) springs keep their MJCF stand-ins.
  void resolve(mjModel* m, const std::vector<mjcf::RuntimeLaw>& laws, bool between_steps = false);
  // Sets gains, biases and controls from the current velocities, and springs' rows; cheap enough for every
  // step.
  void apply(mjModel* m, mjData* d);
  // After mj_step2: springs' force outputs.
  void after_step(const mjModel* m, mjData* d) const { springs_.add_row_forces(m, d); }
  bool empty() const { return laws_.empty() && springs_.empty(); }

 private:
  struct Law {
    mjcf::RuntimeLaw::Kind kind;
    std::vector<int> actuators;
    std::vector<int> dofs;  // per actuator: its joint's dof
    std::vector<double> x, y, x2, y2;
    double parameter = 0;
  };
  std::vector<Law> laws_;
  SpringRows springs_;
};

// Linear interpolation in (x, y), flat beyond the ends (0 for an empty table).
double interpolate(const std::vector<double>& x, const std::vector<double>& y, double at);

}  // namespace openplx::runtime
