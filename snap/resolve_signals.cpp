// Signals (inputs and outputs): their sources, composites' parts and IMU sensors' attachments.
#include <algorithm>
#include <cmath>

#include "snap/system_builder.h"

namespace openplx::snap::detail {
namespace {

// Whether the attribute holding signal `id` was declared in a user's file rather than in a bundle model,
// which declares some signals on every instance of it.
bool declared_by_user(const fe::ObjectGraph& graph, fe::ObjectId id) {
  const fe::Object& obj = graph.at(id);
  if (obj.owner == fe::kNoObject) return true;
  const fe::Object& owner = graph.at(obj.owner);
  const fe::Slot* slot = owner.find(obj.name);
  const fe::ModelInfo* declared_in = slot ? slot->declared_in() : owner.type;
  return !(declared_in && declared_in->doc && declared_in->doc->bundle);
}

}  // namespace

void SystemBuilder::add_signal(fe::ObjectId id, const Role::SignalModel& model) {
  const fe::Object& obj = ev_.graph().at(id);
  const size_t index = system_.signals.size();
  Signal& signal = system_.signals.emplace_back();  // filled in place
  signal.object = id;
  signal.input = model.input;
  signal.path = path_of(id);
  signal.type = obj.type->qualified;
  // The torque converter's own signal models name it `torque_converter`, not `source`; an affine output's
  // `source` is the signal it transforms.
  const SignalSlots::Slots slots = signal_slots_.of(obj);
  const fe::ObjectId source = model.affine_output ? fe::kNoObject : in_.object(id, slots[kSource]);
  signal_sources_.push_back(source != fe::kNoObject ? source : in_.object(id, slots[kTorqueConverter]));
  signal.where = where_of(id);
  signal.user_declared = declared_by_user(ev_.graph(), id);
  signal.enabled = in_.boolean(id, slots[kEnabled]).value_or(signal.enabled);
  std::vector<fe::ObjectId>& parts = composite_parts_.emplace_back();
  for (size_t list : {kTargets, kJointSources, kObjectSources, kSources}) {
    if (!slots[list].present()) continue;
    signal.composite = true;
    for (fe::ObjectId part : in_.objects(id, slots[list])) parts.push_back(part);
  }
  using Composition = Signal::Composition;
  if (model.broadcast) signal.composition = Composition::Broadcast;
  if (model.affine_input || model.affine_output) {
    signal.composite = true;
    signal.composition = Composition::Affine;
    signal.scale = real(id, "scale", 1.0);
    signal.offset = real(id, "offset", 0.0);
    parts = {object(id, signal.input ? "target" : "source")};
  }
  if (slots[kSensors].present()) signal.sensors = in_.objects(id, slots[kSensors]).size();
  read_relative_to(id, index);
  if (model.imu) {
    signal.imu = true;
    // A sensor without an attachment of its own sits where the IMU is attached.
    const fe::ObjectId imu = object(id, "source");
    const fe::ObjectId imu_attachment =
        imu == fe::kNoObject ? fe::kNoObject : object(imu, "mate_connector_attachment");
    for (fe::ObjectId field : in_.objects(id, "fields")) {
      Signal::SensorField f;
      f.axis = static_cast<int>(real(field, "field", 1.0)) - 1;
      const fe::ObjectId sensor = object(field, "sensor");
      if (sensor != fe::kNoObject) {
        const fe::Object& logic = ev_.graph().at(sensor);
        using Kind = Signal::SensorField::Kind;
        f.kind = is(logic, accelerometer_)  ? Kind::Accelerometer
                 : is(logic, gyroscope_)    ? Kind::Gyroscope
                 : is(logic, magnetometer_) ? Kind::Magnetometer
                                            : Kind::Unknown;
        f.sensor_path = path_of(sensor);
        read_sensor_noise(sensor, f);
        const fe::ObjectId own = object(sensor, "mate_connector_attachment");
        sensor_attachments_.emplace_back(index, signal.sensor_fields.size(),
                                         own != fe::kNoObject ? own : imu_attachment);
      }
      signal.sensor_fields.push_back(std::move(f));
    }
  }
}

// An IMU sensor's distortions for field `f`'s axis: Gaussian signal noise (distribution_x/y/z), several
// adding up as independent noises do (means add, variances add); any other distortion is kept to be warned
// about.
void SystemBuilder::read_sensor_noise(fe::ObjectId sensor, Signal::SensorField& f) {
  if (!ev_.graph().at(sensor).has("sensing_distortions")) return;
  double variance = 0;
  for (fe::ObjectId d : in_.objects(sensor, "sensing_distortions")) {
    const std::string& type = in_.type_name(d);
    if (type.find("SignalGaussianNoise") == std::string::npos || f.axis < 0 || f.axis > 2) {
      f.unapplied.push_back({path_of(d), type, where_of(d)});
      continue;
    }
    const fe::ObjectId g = object(d, f.axis == 0   ? "distribution_x"
                                     : f.axis == 1 ? "distribution_y"
                                                   : "distribution_z");
    if (g == fe::kNoObject) continue;
    f.noise_mean += real(g, "mean");
    variance += std::pow(real(g, "standard_deviation"), 2);
  }
  f.noise_deviation = std::sqrt(variance);
}

// What a signal's values are expressed relative to: a connector output's reference connector (resolved to
// an index once every connector is known) or a force or torque output's transform.
void SystemBuilder::read_relative_to(fe::ObjectId id, size_t index) {
  const fe::ObjectId reference = object(id, "relative_to");
  if (reference == fe::kNoObject) return;
  const fe::Object& obj = ev_.graph().at(reference);
  if (is(obj, connector_)) {
    signal_references_.emplace_back(index, reference);
  } else if (obj.type->qualified == "Math.AffineTransform") {
    system_.signals[index].relative_transform = affine(reference);
  } else {
    system_.signals[index].relative_to_path = path_of(reference);
  }
}

// `relative_to` connectors by index: the World singleton is the default (world values); another connector
// outside the tree lives in the world, as a mate's does.
void SystemBuilder::resolve_signal_references() {
  for (const auto& [signal, reference] : signal_references_) {
    const fe::Object& obj = ev_.graph().at(reference);
    if (auto it = connector_of_.find(reference); it != connector_of_.end()) {
      system_.signals[signal].relative_to = it->second;
    } else if (obj.is_const_singleton && obj.type->qualified == "Physics3D.Interactions.World") {
      continue;
    } else if (obj.is_const_singleton) {
      add_connector(reference, kWorld, false);
      system_.connectors.back().path = obj.type->qualified;
      system_.signals[signal].relative_to = connector_of_[reference];
    } else {
      system_.signals[signal].relative_to_path = path_of(reference);
    }
  }
}

// IMU fields' and lidars' connectors by index.
void SystemBuilder::resolve_sensor_attachments() {
  if (sensor_attachments_.empty() && system_.lidars.empty()) return;  // no index to build
  std::unordered_map<fe::ObjectId, int> index;
  for (size_t k = 0; k < system_.connectors.size(); ++k)
    index[system_.connectors[k].object] = static_cast<int>(k);
  for (const auto& [signal, field, connector] : sensor_attachments_) {
    auto it = index.find(connector);
    system_.signals[signal].sensor_fields[field].connector = it == index.end() ? -1 : it->second;
  }
  for (Lidar& lidar : system_.lidars) {
    auto it = index.find(lidar.attachment);
    lidar.connector = it == index.end() ? -1 : it->second;
  }
}

// A composite's parts are signals of the tree, found by object.
void SystemBuilder::resolve_composites() {
  if (std::all_of(composite_parts_.begin(), composite_parts_.end(),
                  [](const std::vector<fe::ObjectId>& parts) { return parts.empty(); }))
    return;  // no index to build
  std::unordered_map<fe::ObjectId, int> index;
  for (size_t k = 0; k < system_.signals.size(); ++k) index[system_.signals[k].object] = static_cast<int>(k);
  for (size_t k = 0; k < system_.signals.size(); ++k) {
    for (fe::ObjectId part : composite_parts_[k]) {
      auto it = index.find(part);
      system_.signals[k].parts.push_back(it == index.end() ? -1 : it->second);
    }
  }
}

// What a signal's source is: the first of interaction, mate, body, shaft and connector it is.
void SystemBuilder::resolve_source(Signal& signal, fe::ObjectId source) {
  if (source == fe::kNoObject) return;
  if (sources_.empty()) build_source_index();
  auto it = sources_.find(source);
  if (it != sources_.end()) {
    signal.source_kind = it->second.first;
    signal.source = it->second.second;
    return;
  }
  signal.source_kind = SignalSource::Other;
  signal.source_path = path_of(source);
}

void SystemBuilder::build_source_index() {
  sources_.reserve(system_.connectors.size() + system_.shafts.size() + system_.couplings.size() +
                   system_.nodes.size() + system_.mates.size() + system_.interactions.size() +
                   system_.lidars.size());  // no rehashing
  // Inserted in reverse priority, so an object that were two things would keep the first kind.
  auto add = [&](SignalSource kind, const auto& items, auto accept) {
    for (size_t k = 0; k < items.size(); ++k)
      if (accept(items[k])) sources_[items[k].object] = {kind, static_cast<int>(k)};
  };
  auto all = [](const auto&) { return true; };
  add(SignalSource::Connector, system_.connectors, all);
  add(SignalSource::Shaft, system_.shafts, all);
  add(SignalSource::Coupling, system_.couplings, all);
  add(SignalSource::Body, system_.nodes, [](const FrameNode& n) { return n.kind == FrameNode::Kind::Body; });
  add(SignalSource::Mate, system_.mates, all);
  add(SignalSource::Interaction, system_.interactions, all);
  add(SignalSource::Lidar, system_.lidars, all);
}

}  // namespace openplx::snap::detail
