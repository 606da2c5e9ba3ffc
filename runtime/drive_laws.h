// The laws MJCF cannot state that act through actuators (mjcf::RuntimeLaw): engine torque curves with their
// idle governor and torque converters' fluid coupling, written into their actuators before every step. The
// laws that are constraint rows are constraint_rows.h's.
#pragma once

#include <mujoco/mujoco.h>

#include <vector>

#include "contract/signal_binding.h"

namespace openplx::runtime {

class DriveLaws {
 public:
  // Resolves actuator names to ids (a law whose actuators are missing is skipped) and clears the static
  // stand-ins the MJCF carries (an engine's linear speed falloff). Laws of other kinds are left alone.
  void resolve(mjModel* m, const std::vector<mjcf::RuntimeLaw>& laws);
  // Sets gains, biases and controls from the current velocities; cheap enough for every step.
  void apply(mjModel* m, mjData* d);
  bool empty() const { return laws_.empty(); }

 private:
  struct Law {
    mjcf::RuntimeLaw::Kind kind;
    std::vector<int> actuators;
    std::vector<int> dofs;  // per actuator: its joint's dof
    std::vector<double> x, y, x2, y2;
    double parameter = 0;
  };
  std::vector<Law> laws_;
};

// Linear interpolation in (x, y), flat beyond the ends (0 for an empty table).
double interpolate(const std::vector<double>& x, const std::vector<double>& y, double at);

}  // namespace openplx::runtime
