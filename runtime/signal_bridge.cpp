#include "openplx/runtime/signal_bridge.h"

#include "runtime/manifest_reader.h"
#include "runtime/simulation_state.h"

namespace openplx::runtime {

SignalBridge SignalBridge::attach(const std::string& manifest, mjModel* model, mjData* data,
                                  const std::string& prefix) {
  if (!model || !data) throw LoadError(manifest + ": error: a bridge needs a model and its data\n");
  Manifest read = read_manifest(manifest);
  // Names carry the prefix they were emitted with; another one given here replaces it.
  if (!prefix.empty() && prefix != read.prefix) {
    auto rename = [&](std::string& name) {
      if (name.compare(0, read.prefix.size(), read.prefix) == 0)
        name = prefix + name.substr(read.prefix.size());
    };
    for (mjcf::SignalBinding& b : read.signals) {
      for (std::string& name : b.names) rename(name);
      if (!b.sensor.empty()) rename(b.sensor);
    }
    for (mjcf::RuntimeLaw& law : read.laws)
      for (std::string& name : law.actuators) rename(name);
  }
  auto state = std::make_unique<SimulationState>();
  state->m = model;
  state->d = data;
  state->owns = false;
  state->root = read.model;
  // Every binding that names an element the model lacks is refused (resolve marks it unmapped); a model
  // without any of them is the wrong model or the wrong prefix.
  size_t named = 0, found = 0;
  for (const mjcf::SignalBinding& b : read.signals) {
    if (b.quantity == mjcf::Quantity::None || b.names.empty()) continue;
    ++named;
    found += mj_name2id(model, mjOBJ_UNKNOWN, b.names.front().c_str()) >= 0 ||
             mj_name2id(model, mjOBJ_JOINT, b.names.front().c_str()) >= 0 ||
             mj_name2id(model, mjOBJ_BODY, b.names.front().c_str()) >= 0 ||
             mj_name2id(model, mjOBJ_ACTUATOR, b.names.front().c_str()) >= 0 ||
             mj_name2id(model, mjOBJ_SITE, b.names.front().c_str()) >= 0 ||
             mj_name2id(model, mjOBJ_TENDON, b.names.front().c_str()) >= 0 ||
             mj_name2id(model, mjOBJ_EQUALITY, b.names.front().c_str()) >= 0;
  }
  if (named > 0 && found == 0) {
    throw LoadError(manifest + ": error: the model has none of the elements this manifest names (prefix `" +
                    (prefix.empty() ? read.prefix : prefix) + "`); is it the model emitted with it?\n");
  }
  state->resolve(std::move(read.signals), read.laws);
  return SignalBridge(std::move(state));
}

SignalBridge::SignalBridge(std::unique_ptr<SimulationState> state) : state_(std::move(state)) {}
SignalBridge::SignalBridge(SignalBridge&&) noexcept = default;
SignalBridge& SignalBridge::operator=(SignalBridge&&) noexcept = default;
SignalBridge::~SignalBridge() = default;

Input SignalBridge::input(std::string_view name) {
  const int index = state_->find(name, true);
  return Input(state_.get(), index, state_->signals[static_cast<size_t>(index)].direct);
}

Output SignalBridge::output(std::string_view name) {
  const int index = state_->find(name, false);
  state_->request_output(index);
  const ResolvedSignal& s = state_->signals[static_cast<size_t>(index)];
  return Output(state_.get(), index, s.direct, s.scale, s.direct3);
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
  state_->before_step();
}

void SignalBridge::after_step() {
  state_->after_step();
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
void Input::set(const Eigen::VectorXd& value) {
  state_->write(index_, value.data(), static_cast<int>(value.size()), ValueType::Vector);
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
Eigen::VectorXd Output::vector() const {
  Eigen::VectorXd v(static_cast<Eigen::Index>(info().size));
  state_->read(index_, v.data(), static_cast<int>(v.size()), ValueType::Vector);
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
