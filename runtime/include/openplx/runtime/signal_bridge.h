// Drive a MuJoCo model you loaded yourself, alone or merged with others into one scene, by the OpenPLX signal
// names of a model openplx2mjcf emitted, through the signal manifest it wrote beside the MJCF.
//
//   mjModel* m = mj_loadXML("scene.xml", ...);  // <include>s left.xml and right.xml (emitted with --prefix)
//   mjData* d = mj_makeData(m);
//   auto left = openplx::runtime::SignalBridge::attach("left.signals.json", m, d);
//   auto right = openplx::runtime::SignalBridge::attach("right.signals.json", m, d);
//   left.input("motor.torque_input").set(1.0);
//   left.before_step(); right.before_step();
//   mj_step(m, d);
//   left.after_step(); right.after_step();
//   double angle = right.output("hinge.angle_output").real();
//
// The bridge writes mjData (controls, velocities of kinematic bodies) and, for inputs MuJoCo has no control
// for (enable flags, effort ranges, clutch engagement, gear ratios), mjModel fields of its own model's
// elements. before_step() applies the laws MJCF cannot state (engine curves, torque converters); after_step()
// moves kinematic bodies, ramps clutches and keeps the constraint forces outputs read. Names are OpenPLX
// paths relative to the emitted root model, as for Simulation.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "openplx/runtime/simulation.h"

namespace openplx::runtime {

class SignalBridge {
 public:
  // `manifest`: the OUT.signals.json of the emitted model. `prefix`: the prefix its MuJoCo names carry in
  // `model`; empty: the one it was emitted with (the manifest records it). Throws LoadError when the
  // manifest cannot be read or names elements `model` does not have.
  static SignalBridge attach(const std::string& manifest, mjModel* model, mjData* data,
                             const std::string& prefix = "");

  SignalBridge(SignalBridge&&) noexcept;
  SignalBridge& operator=(SignalBridge&&) noexcept;
  ~SignalBridge();

  Input input(std::string_view name);  // throws SignalError
  Output output(std::string_view name);
  std::vector<SignalInfo> inputs() const;
  std::vector<SignalInfo> outputs() const;

  void before_step();
  void after_step();

 private:
  friend class Simulation;
  explicit SignalBridge(std::unique_ptr<SimulationState> state);
  std::unique_ptr<SimulationState> state_;
};

}  // namespace openplx::runtime
