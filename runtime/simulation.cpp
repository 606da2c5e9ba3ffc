#include "openplx/runtime/simulation.h"

#include <cmath>

#include "openplx/runtime/signal_bridge.h"
#include "runtime/load_model.h"
#include "runtime/simulation_state.h"

namespace openplx::runtime {

Simulation Simulation::load(const std::string& path, const LoadOptions& options) {
  if (!(options.timestep > 0) || !std::isfinite(options.timestep))
    throw LoadError(path + ": error: the time step must be a positive number of seconds\n");
  LoadedModel loaded =
      load_model(path, options.model, options.bundle_paths, options.timestep, options.default_bundles);
  auto state = std::make_unique<SimulationState>();
  state->m = loaded.model;
  state->d = mj_makeData(state->m);
  if (!state->d) throw LoadError(path + ": error: MuJoCo could not allocate the simulation data\n");
  // Free bodies' initial velocities come as the emitter's "initial" keyframe.
  if (const int key = mj_name2id(state->m, mjOBJ_KEY, "initial"); key >= 0)
    mj_resetDataKeyframe(state->m, state->d, key);
  state->root = std::move(loaded.root_name);
  state->xml = std::move(loaded.xml);
  state->warnings = std::move(loaded.warnings);
  state->resolve(std::move(loaded.signals), loaded.laws);
  state->laws.apply(state->m, state->d);
  mj_forward(state->m, state->d);  // outputs describe the initial state; the first step needs only mj_step2
  state->cache_constraint_forces();
  return Simulation(std::move(state));
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
  const long steps = std::lround(seconds / state_->m->opt.timestep);
  for (long k = 0; k < steps; ++k) state_->step();
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
