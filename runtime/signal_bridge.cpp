#include "openplx/runtime/signal_bridge.h"

#include <cmath>
#include <mutex>
#include <set>
#include <utility>

#include "contract/manifest_reader.h"
#include "contract/model_fingerprint.h"
#include "contract/numbers.h"
#include "runtime/mujoco_messages.h"
#include "runtime/row_hook.h"
#include "runtime/signal_conversions.h"
#include "runtime/simulation_state.h"

namespace openplx::runtime {

namespace {

// The bridges alive, by the data they drive and their prefix: two on the same elements would each keep
// their own inputs (clutch ramps, gears, kinematic velocities) and disagree.
std::mutex registry_mutex;
std::set<std::pair<const mjData*, std::string>>& registry() {
  static std::set<std::pair<const mjData*, std::string>> bridges;
  return bridges;
}

bool composed(mjcf::Quantity q) {
  return q == mjcf::Quantity::Composite || q == mjcf::Quantity::Broadcast || q == mjcf::Quantity::Affine;
}

// Every MuJoCo element the manifest names that `model` lacks, as "kind `name`".
std::vector<std::string> missing_elements(const mjcf::Manifest& read, const mjModel* model, size_t& named) {
  std::set<std::pair<mjcf::MjObject, std::string>> wanted;
  for (const mjcf::SignalBinding& b : read.signals) {
    if (b.quantity == mjcf::Quantity::None || composed(b.quantity)) continue;
    for (const std::string& name : b.names) wanted.emplace(b.object, name);
    if (!b.sensor.empty()) wanted.emplace(mjcf::MjObject::Sensor, b.sensor);
  }
  for (const mjcf::RuntimeLaw& law : read.laws)
    for (const std::string& name : law.actuators) wanted.emplace(mjcf::MjObject::Actuator, name);
  named = wanted.size();
  std::vector<std::string> missing;
  for (const auto& [object, name] : wanted) {
    if (mj_name2id(model, object_type(object), name.c_str()) < 0)
      missing.push_back(std::string(mjcf::to_string(object)) + " `" + name + "`");
  }
  return missing;
}

// The bodies in the trees (below a child of the world) of the bodies, joints and sites the manifest names.
std::vector<bool> named_trees(const mjcf::Manifest& read, const mjModel* model) {
  std::vector<bool> roots(static_cast<size_t>(model->nbody), false), trees(roots.size(), false);
  for (const mjcf::SignalBinding& b : read.signals) {
    if (b.quantity == mjcf::Quantity::None || composed(b.quantity)) continue;
    for (const std::string& name : b.names) {
      const int id = mj_name2id(model, object_type(b.object), name.c_str());
      if (id < 0) continue;
      const int body = b.object == mjcf::MjObject::Body    ? id
                       : b.object == mjcf::MjObject::Joint ? model->jnt_bodyid[id]
                       : b.object == mjcf::MjObject::Site  ? model->site_bodyid[id]
                                                           : -1;
      if (body > 0) roots[static_cast<size_t>(model->body_rootid[body])] = true;
    }
  }
  for (int body = 1; body < model->nbody; ++body)
    trees[static_cast<size_t>(body)] = roots[static_cast<size_t>(model->body_rootid[body])];
  return trees;
}

std::string list(const std::vector<std::string>& items, size_t most) {
  std::string text;
  for (size_t k = 0; k < items.size() && k < most; ++k) text += (k ? ", " : "") + items[k];
  if (items.size() > most) text += " and " + std::to_string(items.size() - most) + " more";
  return text;
}

}  // namespace

SignalBridge SignalBridge::attach(const std::string& manifest, mjModel* model, mjData* data,
                                  const std::string& prefix, const SensorNoiseOptions& noise) {
  if (!model || !data) throw LoadError(manifest + ": error: a bridge needs a model and its data\n");
  install_mujoco_handlers();
  mjcf::Manifest read;
  try {
    read = mjcf::read_manifest(manifest);
  } catch (const mjcf::ManifestError& e) {
    throw LoadError(e.what());
  }
  // Names carry the prefix they were emitted with; another one given here replaces it.
  if (!prefix.empty() && prefix != read.prefix) {
    auto rename = [&](std::string& name) {
      if (name.compare(0, read.prefix.size(), read.prefix) == 0)
        name = prefix + name.substr(read.prefix.size());
    };
    for (mjcf::SignalBinding& b : read.signals) {
      if (composed(b.quantity)) continue;  // its names are OpenPLX paths
      for (std::string& name : b.names) rename(name);
      if (!b.sensor.empty()) rename(b.sensor);
    }
    for (mjcf::RuntimeLaw& law : read.laws)
      for (std::string& name : law.actuators) rename(name);
  }
  const std::string used_prefix = prefix.empty() ? read.prefix : prefix;
  const std::string is_it =
      "; is it the model emitted with this manifest (names with prefix `" + used_prefix + "`)?\n";
  // The model the manifest was emitted for: its own bodies and joints, wherever the scene put them.
  if (!read.fingerprint.empty()) {
    mjcf::Fingerprint expected;
    if (!mjcf::Fingerprint::parse(read.fingerprint, expected))
      throw LoadError(manifest + ": error: its fingerprint `" + read.fingerprint +
                      "` is not one this runtime reads (a newer openplx2mjcf wrote it?)\n");
    mjcf::Fingerprint found = mjcf::model_fingerprint(model, used_prefix);
    auto same = [&] {
      return found.bodies == expected.bodies && found.joints == expected.joints &&
             found.hash == expected.hash;
    };
    // Without a prefix, a scene's other models count too: then only the body trees that hold the elements the
    // manifest names (every body has signals) are the model's.
    if (!same() && used_prefix.empty()) {
      const std::vector<bool> trees = named_trees(read, model);
      found = mjcf::model_fingerprint(model, used_prefix, &trees);
    }
    if (!same()) {
      throw LoadError(manifest + ": error: the manifest was written for another model: it describes " +
                      std::to_string(expected.bodies) + " bodies and " + std::to_string(expected.joints) +
                      " joints (fingerprint " + expected.hash + "), the model's own are " +
                      std::to_string(found.bodies) + " bodies and " + std::to_string(found.joints) +
                      " joints (fingerprint " + found.hash + ")" + is_it);
    }
  }
  size_t named = 0;
  const std::vector<std::string> missing = missing_elements(read, model, named);
  if (!missing.empty()) {
    throw LoadError(manifest + ": error: the model lacks " + std::to_string(missing.size()) + " of the " +
                    std::to_string(named) + " MuJoCo elements this manifest names (" + list(missing, 5) +
                    ")" + is_it);
  }
  auto state = std::make_unique<SimulationState>();
  state->m = model;
  state->d = data;
  state->owns = false;
  state->root = read.model;
  state->source = manifest;
  state->prefix = used_prefix;
  state->noise = noise;
  state->emitted_timestep = read.timestep;
  // A scene stepping at another time step (its own <option>, or one read after the included file's) runs the
  // emitter's stability caps outside the range they were set for; a model without any (the manifest says
  // which it has; older manifests do not, and are taken to have some) means the same at any step.
  if (read.timestep > 0 && read.timestep_dependent &&
      std::abs(model->opt.timestep - read.timestep) > 1e-9 * read.timestep) {
    std::string which;
    for (const std::string& choice : read.timestep_choices) which += (which.empty() ? "" : ", ") + choice;
    state->warn(manifest + ": warning: the scene steps at " + mjcf::number(model->opt.timestep) +
                " s but the model was emitted for " + mjcf::number(read.timestep) + " s; " +
                (which.empty() ? "its motor gains and soft constraints" : "its " + which) +
                " follow the time step it was emitted for: emit it with --timestep " +
                mjcf::number(model->opt.timestep) + "\n");
  }
  state->resolve(std::move(read.signals), read.laws);
  if (!state->mismatches.empty()) {
    throw LoadError(manifest + ": error: the manifest does not fit the model: " + list(state->mismatches, 5) +
                    is_it);
  }
  {
    const std::lock_guard<std::mutex> lock(registry_mutex);
    if (!registry().emplace(data, used_prefix).second) {
      throw LoadError(manifest + ": error: a bridge for the names with prefix `" + used_prefix +
                      "` is already attached to this mjData; a second one would keep inputs of its own and "
                      "disagree with it: use the first\n");
    }
  }
  state->registered = true;
  if (!state->rows.empty()) {
    row_hook::attach(data, &state->rows);
    state->rows_hooked = true;
  }
  state->begin_watch();
  current_sink() = nullptr;
  return SignalBridge(std::move(state));
}

SignalBridge::SignalBridge(std::unique_ptr<SimulationState> state) : state_(std::move(state)) {}
SignalBridge::SignalBridge(SignalBridge&&) noexcept = default;
SignalBridge& SignalBridge::operator=(SignalBridge&& other) noexcept {
  if (this != &other) {
    SignalBridge gone(std::move(*this));  // unregistered as it goes
    state_ = std::move(other.state_);
  }
  return *this;
}
SignalBridge::~SignalBridge() {
  if (!state_ || !state_->registered) return;
  const std::lock_guard<std::mutex> lock(registry_mutex);
  registry().erase({state_->d, state_->prefix});
}

// A Simulation's own bridge: registered like attached ones, so a bridge attached to its data is refused.
void SignalBridge::register_own() {
  const std::lock_guard<std::mutex> lock(registry_mutex);
  registry().emplace(state_->d, state_->prefix);
  state_->registered = true;
}

Input SignalBridge::input(std::string_view name) {
  const int index = state_->find(name, true);
  const ResolvedSignal& s = state_->signals[static_cast<size_t>(index)];
  return Input(state_.get(), index, s.direct, s.low, s.high);
}

Output SignalBridge::output(std::string_view name) {
  const int index = state_->find(name, false);
  state_->request_output(index);
  const ResolvedSignal& s = state_->signals[static_cast<size_t>(index)];
  return Output(state_.get(), index, s.direct, s.scale, s.direct3, &state_->derived_state_behind);
}

std::vector<SignalInfo> SignalBridge::inputs() const {
  std::vector<SignalInfo> out;
  for (const ResolvedSignal& s : state_->signals) {
    if (s.binding.input) out.push_back(s.info);
  }
  return out;
}

std::vector<SignalInfo> SignalBridge::outputs() const {
  std::vector<SignalInfo> out;
  for (const ResolvedSignal& s : state_->signals) {
    if (!s.binding.input) out.push_back(s.info);
  }
  return out;
}

void SignalBridge::before_step() {
  if (state_->stale) {  // an input changed model fields mj_step1 reads: mj_step's own step1 picks them up
    state_->stale = false;
  }
  state_->begin_watch();
  state_->before_step();
}

void SignalBridge::after_step() {
  state_->end_watch();
  if (state_->rows_hooked && !state_->hook_replaced_said && !row_hook::installed()) {
    state_->hook_replaced_said = true;
    state_->warn(state_->source +
                 ": warning: mjcb_control was replaced after the bridge attached, so MuJoCo no longer gives "
                 "the model's motors, springs, ranges and couplings AGX's constraint law (they fall back to "
                 "the MJCF's own elements); set your callback before attaching, and the bridge calls it\n");
  }
  state_->after_step();
  state_->derived_state_behind = true;  // mj_step computed them before integrating (bring_current.cpp)
  state_->begin_watch();                // a caller that skips before_step is still watched from here
  current_sink() = nullptr;
}

void SignalBridge::set_sensor_noise(const SensorNoiseOptions& noise) {
  state_->noise = noise;
}

void SignalBridge::set_on_instability(OnInstability what) {
  state_->on_instability = what;
}

const std::vector<std::string>& SignalBridge::warnings() const {
  return state_->warnings;
}

void Input::set_checked(double value) {
  state_->write(index_, &value, 1, ValueType::Real);
}
void Input::set(bool value) {
  const double v = value ? 1.0 : 0.0;
  state_->write(index_, &v, 1, ValueType::Bool);
}
void Input::set_values(const double* values, int count, ValueType given) {
  state_->write(index_, values, count, given);
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
std::array<double, 2> Output::vec2_values() const {
  std::array<double, 2> v{};
  state_->read(index_, v.data(), 2, ValueType::Vec2);
  return v;
}
std::vector<double> Output::vector_values() const {
  std::vector<double> v(info().size);
  state_->read(index_, v.data(), static_cast<int>(v.size()), ValueType::Vector);
  return v;
}
std::array<double, 3> Output::vec3_checked() const {
  std::array<double, 3> v{};
  state_->read(index_, v.data(), 3, ValueType::Vec3);
  return v;
}
const SignalInfo& Output::info() const {
  return state_->signals[static_cast<size_t>(index_)].info;
}

}  // namespace openplx::runtime
