// Load an OpenPLX model straight into MuJoCo and drive it by OpenPLX signal names.
//
//   auto sim = openplx::runtime::Simulation::load("pendulum.openplx");
//   auto torque = sim.input("motor.torque_input");
//   auto angle = sim.output("hinge.angle_output");
//   for (int k = 0; k < 1000; ++k) { torque.set(-5.0 * angle.real()); sim.step(); }
//
// Signal names, values and errors are those of signals.h. Outputs read after step() describe the state after
// that step; forces and accelerations describe the step just taken. This is the converter in-process (target
// openplx2mjcf::runtime); a program that attaches an emitted manifest to its own model needs only
// signal_bridge.h (target openplx2mjcf::bridge, no converter).
#pragma once

#include <mujoco/mujoco.h>

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "openplx/runtime/signals.h"

namespace openplx::runtime {

struct LoadOptions {
  std::string model;                      // the root model; empty: the file's last model
  std::vector<std::string> bundle_paths;  // extra bundle folders (like openplx2mjcf -B)
  double timestep = 0.002;                // MuJoCo's time step, s (like openplx2mjcf --timestep)
  bool default_bundles = true;  // false: only bundle_paths and OPENPLX_BUNDLE_PATH (--no-default-bundles)
  OnInstability on_instability = OnInstability::Throw;
  SensorNoiseOptions sensor_noise{};  // on, seed 0 (openplx-sim --seed, --no-noise)
};

// A model loaded from OpenPLX, with its own mjModel and mjData and one SignalBridge on them.
class Simulation {
 public:
  // Throws LoadError for every reason it cannot load: an empty or missing path, a bundle folder of
  // options.bundle_paths that does not exist, a time step outside [kMinTimestep, kMaxTimestep], the
  // model's own errors, MuJoCo's. Installs MuJoCo's message handlers when none are set (runtime/README.md).
  static Simulation load(const std::string& path, const LoadOptions& options = {});
  static constexpr double kMinTimestep = 1e-6, kMaxTimestep = 1.0;  // s, as openplx2mjcf --timestep

  Simulation(Simulation&&) noexcept;
  Simulation& operator=(Simulation&&) noexcept;
  ~Simulation();

  Input input(std::string_view name);  // throws SignalError
  Output output(std::string_view name);

  // One MuJoCo step. Throws SimulationError when MuJoCo's warnings say it was not the model's motion (unless
  // set_on_instability(OnInstability::Continue)), and for an error MuJoCo stopped on.
  void step();
  // Steps until time() has advanced by `seconds` (rounded to whole steps). Throws std::invalid_argument for
  // a negative or non-finite span or one of more than kMaxAdvanceSteps steps; SimulationError as step().
  void advance(double seconds);
  static constexpr long kMaxAdvanceSteps = 1'000'000'000;
  void set_on_instability(OnInstability what);
  void set_sensor_noise(const SensorNoiseOptions& noise);  // from the next read on
  double time() const;
  double timestep() const;

  // Raw access for existing MuJoCo pipelines. After writing qpos/qvel or model fields yourself, call
  // mj_forward(model(), data()) so outputs and the next step see the change.
  const mjModel* model() const;
  mjData* data();

  std::vector<SignalInfo> inputs() const;
  std::vector<SignalInfo> outputs() const;
  const std::string& root_model() const;
  const std::string& mjcf() const;  // the MJCF the model was loaded from
  // Printed warnings of the transpilation, then those of the run as they come (each a line ending in '\n'):
  // an input clamped to its range (once per input), MuJoCo's own warnings, and instabilities under
  // OnInstability::Continue.
  const std::vector<std::string>& warnings() const;
  // Every file the load read from disk (the model, the OpenPLX files and bundles it reaches, URDFs, meshes):
  // what a tool writing files next to the model must not overwrite (openplx-sim --csv).
  const std::vector<std::string>& files_read() const;

 private:
  explicit Simulation(std::unique_ptr<SimulationState> state);
  std::unique_ptr<SignalBridge> bridge_;
  SimulationState* state_;  // the bridge's
};

// Adds a folder searched for the standard bundles when the library is not run from its build or install
// tree. The installed CMake package calls it (through OPENPLX2MJCF_INSTALLED_BUNDLES) with its own folder.
void add_default_bundle_dir(const std::string& dir);

#ifdef OPENPLX2MJCF_INSTALLED_BUNDLES
inline const bool installed_bundles_registered =
    (add_default_bundle_dir(OPENPLX2MJCF_INSTALLED_BUNDLES), true);
#endif

// Adds a file tried for the URDF importer module (libopenplx_urdf.so, loaded on the first URDF import) when
// the library is not run from its build or install tree. The installed CMake package registers its own.
void add_urdf_module(const std::string& path);

#ifdef OPENPLX2MJCF_INSTALLED_URDF_MODULE
inline const bool installed_urdf_module_registered =
    (add_urdf_module(OPENPLX2MJCF_INSTALLED_URDF_MODULE), true);
#endif

}  // namespace openplx::runtime
