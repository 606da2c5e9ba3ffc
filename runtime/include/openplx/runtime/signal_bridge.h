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

#include "openplx/runtime/signals.h"

namespace openplx::runtime {

class SignalBridge {
 public:
  // `manifest`: the OUT.signals.json of the emitted model. `prefix`: the prefix its MuJoCo names carry in
  // `model`; empty: the one it was emitted with (the manifest records it). Throws LoadError when the
  // manifest cannot be read, is inconsistent in itself (a binding or law the runtime could not use), was
  // written for another model (its fingerprint, over the model's own bodies and joints by name without
  // the prefix, differs from `model`'s: see contract/model_fingerprint.h; manifests without one skip
  // this), names any element `model` lacks or has of another kind, has a newer format_version than this
  // runtime reads, or when a bridge for the same prefix is already attached to `data` (two would disagree;
  // the first must be destroyed before another attaches). A `model` stepping at another time step than the
  // manifest's is a warning in warnings() when the model's stability choices follow it (the manifest's
  // timestep_dependent). The manifest's format: docs/signals.schema.json.
  // Also installs MuJoCo's message handlers when none are set (runtime/README.md "MuJoCo's messages").
  // `noise`: the sensor noise the manifest gives outputs (on, seed 0 by default; see signals.h).
  static SignalBridge attach(const std::string& manifest, mjModel* model, mjData* data,
                             const std::string& prefix = "", const SensorNoiseOptions& noise = {});

  SignalBridge(SignalBridge&&) noexcept;
  SignalBridge& operator=(SignalBridge&&) noexcept;
  ~SignalBridge();

  Input input(std::string_view name);  // throws SignalError
  Output output(std::string_view name);
  std::vector<SignalInfo> inputs() const;
  std::vector<SignalInfo> outputs() const;

  // Around each mj_step: before_step() applies the drive laws and remembers MuJoCo's warning counters and
  // time; after_step() throws SimulationError when a warning rose that means the step was not the model's
  // motion (see simulation.h; MuJoCo's own reset stands) unless set_on_instability(Continue), then does
  // its post-step work.
  void before_step();
  void after_step();
  void set_on_instability(OnInstability what);
  void set_sensor_noise(const SensorNoiseOptions& noise);  // from the next read on
  // Run warnings: inputs clamped to their range (once per input), MuJoCo's warnings and instabilities under
  // OnInstability::Continue; each a line ending in '\n'.
  const std::vector<std::string>& warnings() const;

 private:
  friend class Simulation;
  explicit SignalBridge(std::unique_ptr<SimulationState> state);
  void register_own();
  std::unique_ptr<SimulationState> state_;
};

}  // namespace openplx::runtime
