#include "openplx/runtime/simulation.h"

#include <cmath>

#include "runtime/load_model.h"
#include "runtime/simulation_state.h"

namespace openplx::runtime {

Simulation Simulation::load(const std::string& path, const LoadOptions& options) {
  if (!(options.timestep > 0) || !std::isfinite(options.timestep))
    throw LoadError(path + ": error: the time step must be a positive number of seconds\n");
  LoadedModel loaded = load_model(path, options.model, options.bundle_paths, options.timestep);
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

Simulation::Simulation(std::unique_ptr<SimulationState> state) : state_(std::move(state)) {}
Simulation::Simulation(Simulation&&) noexcept = default;
Simulation& Simulation::operator=(Simulation&&) noexcept = default;
Simulation::~Simulation() = default;

Input Simulation::input(std::string_view name) {
  const int index = state_->find(name, true);
  return Input(state_.get(), index, state_->signals[static_cast<size_t>(index)].direct);
}
Output Simulation::output(std::string_view name) {
  const int index = state_->find(name, false);
  state_->request_output(index);
  const ResolvedSignal& s = state_->signals[static_cast<size_t>(index)];
  return Output(state_.get(), index, s.direct, s.scale, s.direct3);
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
  std::vector<SignalInfo> out;
  for (const ResolvedSignal& s : state_->signals) {
    if (s.binding.input) out.push_back(s.info);
  }
  return out;
}

std::vector<SignalInfo> Simulation::outputs() const {
  std::vector<SignalInfo> out;
  for (const ResolvedSignal& s : state_->signals) {
    if (!s.binding.input) out.push_back(s.info);
  }
  return out;
}

void Input::set_checked(double value) {
  state_->write(index_, &value, 1, ValueType::Real);
}
void Input::set(bool value) {
  const double v = value ? 1.0 : 0.0;
  state_->write(index_, &v, 1, ValueType::Bool);
}
void Input::set(const Eigen::Vector2d& value) {
  state_->write(index_, value.data(), 2, ValueType::Vec2);
}
void Input::set(const Eigen::Vector3d& value) {
  state_->write(index_, value.data(), 3, ValueType::Vec3);
}
const SignalInfo& Input::info() const {
  return state_->signals[static_cast<size_t>(index_)].info;
}

double Output::real_checked() const {
  double v = 0;
  state_->read(index_, &v, 1, ValueType::Real);
  return v;
}
bool Output::boolean() const {
  double v = 0;
  state_->read(index_, &v, 1, ValueType::Bool);
  return v != 0;
}
Eigen::Vector2d Output::vec2() const {
  Eigen::Vector2d v;
  state_->read(index_, v.data(), 2, ValueType::Vec2);
  return v;
}
Eigen::Vector3d Output::vec3_checked() const {
  Eigen::Vector3d v;
  state_->read(index_, v.data(), 3, ValueType::Vec3);
  return v;
}
const SignalInfo& Output::info() const {
  return state_->signals[static_cast<size_t>(index_)].info;
}

}  // namespace openplx::runtime
