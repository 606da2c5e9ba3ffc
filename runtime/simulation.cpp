#include "openplx/runtime/simulation.h"

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "contract/numbers.h"
#include "openplx/runtime/signal_bridge.h"
#include "runtime/load_model.h"
#include "runtime/mujoco_messages.h"
#include "runtime/simulation_state.h"

namespace openplx::runtime {

Simulation Simulation::load(const std::string& path, const LoadOptions& options) {
  install_mujoco_handlers();
  if (path.empty()) throw LoadError("error: no model file given (the path is empty)\n");
  if (!(options.timestep > 0) || !std::isfinite(options.timestep))
    throw LoadError(path + ": error: the time step must be a positive number of seconds\n");
  if (options.timestep < kMinTimestep || options.timestep > kMaxTimestep) {
    throw LoadError(path + ": error: the time step " + mjcf::number(options.timestep) +
                    " s is outside what a simulation can use (" + mjcf::number(kMinTimestep) + " to " +
                    mjcf::number(kMaxTimestep) + " s)\n");
  }
  for (const std::string& dir : options.bundle_paths) {
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec))
      throw LoadError(dir + ": error: bundle folder not found (LoadOptions::bundle_paths)\n");
  }
  LoadedModel loaded;
  try {
    loaded = load_model(path, options.model, options.bundle_paths, options.timestep, options.default_bundles);
  } catch (const std::filesystem::filesystem_error& e) {
    throw LoadError(path + ": error: " + e.what() + "\n");
  }
  auto state = std::make_unique<SimulationState>();
  state->m = loaded.model;
  state->source = path;
  state->emitted_timestep = options.timestep;
  state->on_instability = options.on_instability;
  state->noise = options.sensor_noise;
  std::string error;
  if (!call_mujoco(
          nullptr, [&state] { state->d = mj_makeData(state->m); }, error) ||
      !state->d)
    throw LoadError(path + ": error: MuJoCo could not allocate the simulation data" +
                    (error.empty() ? "" : ": " + error) + "\n");
  // Free bodies' initial velocities come as the emitter's "initial" keyframe.
  if (const int key = mj_name2id(state->m, mjOBJ_KEY, "initial"); key >= 0) {
    if (!call_mujoco(
            state->d, [&state, key] { mj_resetDataKeyframe(state->m, state->d, key); }, error))
      throw LoadError(path + ": error: MuJoCo: " + error + "\n");
  }
  state->root = std::move(loaded.root_name);
  state->xml = std::move(loaded.xml);
  state->warnings = std::move(loaded.warnings);
  state->files_read = std::move(loaded.files_read);
  state->resolve(std::move(loaded.signals), loaded.laws);
  if (!state->row_problems.empty()) {
    std::string text;
    for (const std::string& problem : state->row_problems) text += path + ": error: " + problem + "\n";
    throw LoadError(text);
  }
  state->laws.apply(state->m, state->d);
  // Outputs describe the initial state; the first step needs only mj_step2.
  if (!call_mujoco(
          state->d, [&state] { mj_forward(state->m, state->d); }, error))
    throw LoadError(path + ": error: MuJoCo: " + error + "\n");
  state->cache_constraint_forces();
  Simulation sim(std::move(state));
  sim.bridge_->register_own();
  return sim;
}

Simulation::Simulation(std::unique_ptr<SimulationState> state)
    : bridge_(new SignalBridge(std::move(state))), state_(bridge_->state_.get()) {}
Simulation::Simulation(Simulation&&) noexcept = default;
Simulation& Simulation::operator=(Simulation&&) noexcept = default;
Simulation::~Simulation() = default;

Input Simulation::input(std::string_view name) {
  return bridge_->input(name);
}
Output Simulation::output(std::string_view name) {
  return bridge_->output(name);
}

void Simulation::step() {
  state_->step();
}

void Simulation::advance(double seconds) {
  if (!(seconds >= 0) || !std::isfinite(seconds))
    throw std::invalid_argument("advance: " + mjcf::number(seconds) +
                                " is not a span of seconds to simulate");
  const double steps = std::round(seconds / state_->m->opt.timestep);
  if (steps > static_cast<double>(kMaxAdvanceSteps)) {
    throw std::invalid_argument("advance: " + mjcf::number(seconds) + " s is " + mjcf::number(steps) +
                                " steps of " + mjcf::number(state_->m->opt.timestep) + " s, more than the " +
                                std::to_string(kMaxAdvanceSteps) + " one call takes");
  }
  for (long k = 0; k < static_cast<long>(steps); ++k) state_->step();
}

void Simulation::set_sensor_noise(const SensorNoiseOptions& noise) {
  state_->noise = noise;
}

void Simulation::set_on_instability(OnInstability what) {
  state_->on_instability = what;
}

double Simulation::time() const {
  return state_->d->time;
}
double Simulation::timestep() const {
  return state_->m->opt.timestep;
}
const mjModel* Simulation::model() const {
  return state_->m;
}
mjData* Simulation::data() {
  return state_->d;
}
const std::string& Simulation::root_model() const {
  return state_->root;
}
const std::string& Simulation::mjcf() const {
  return state_->xml;
}
const std::vector<std::string>& Simulation::files_read() const {
  return state_->files_read;
}

const std::vector<std::string>& Simulation::warnings() const {
  return state_->warnings;
}

std::vector<SignalInfo> Simulation::inputs() const {
  return bridge_->inputs();
}
std::vector<SignalInfo> Simulation::outputs() const {
  return bridge_->outputs();
}

}  // namespace openplx::runtime
