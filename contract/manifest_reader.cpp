#include "contract/manifest_reader.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

namespace openplx::mjcf {

namespace {

using nlohmann::json;

// Enums by the names to_string gives them; each enum runs from 0 to its last enumerator.
template <typename E>
E parse_enum(const std::string& text, E last, const char* what) {
  for (int k = 0; k <= static_cast<int>(last); ++k) {
    if (to_string(static_cast<E>(k)) == text) return static_cast<E>(k);
  }
  throw std::invalid_argument(std::string("unknown ") + what + " `" + text + "`");
}

// Numbers, and the strings the writer uses for values JSON cannot hold ("inf", "-inf", "nan").
double real(const json& v) {
  if (v.is_number()) return v.get<double>();
  const std::string text = v.get<std::string>();
  if (text == "inf") return std::numeric_limits<double>::infinity();
  if (text == "-inf") return -std::numeric_limits<double>::infinity();
  if (text == "nan") return std::numeric_limits<double>::quiet_NaN();
  throw std::invalid_argument("`" + text + "` is not a number");
}

std::vector<double> reals(const json& v) {
  std::vector<double> out;
  for (const json& item : v) out.push_back(real(item));
  return out;
}

SignalBinding binding(const json& j) {
  SignalBinding b;
  b.path = j.at("path").get<std::string>();
  b.input = j.at("direction").get<std::string>() == "input";
  b.type = j.at("type").get<std::string>();
  b.value = parse_enum(j.at("value").get<std::string>(), SignalValue::Vector, "value kind");
  b.unit = j.at("unit").get<std::string>();
  b.enabled = j.at("enabled").get<bool>();
  b.quantity = parse_enum(j.at("quantity").get<std::string>(), Quantity::Constant, "quantity");
  b.object = parse_enum(j.at("object").get<std::string>(), MjObject::Sensor, "object");
  b.names = j.at("names").get<std::vector<std::string>>();
  b.sensor = j.at("sensor").get<std::string>();
  b.sign = real(j.at("sign"));
  b.initial = real(j.at("initial"));
  b.initial_vector = reals(j.at("initial_vector"));
  b.low = real(j.at("low"));
  b.high = real(j.at("high"));
  b.reason = j.at("reason").get<std::string>();
  b.runtime = j.value("runtime", false);
  if (j.contains("noise")) {
    const json& n = j.at("noise");
    b.noise.mean = reals(n.at("mean"));
    b.noise.deviation = reals(n.at("deviation"));
    if (n.contains("deviation_per_metre")) b.noise.deviation_per_metre = reals(n.at("deviation_per_metre"));
  }
  return b;
}

RuntimeLaw law(const json& j) {
  RuntimeLaw l;
  const std::string kind = j.at("kind").get<std::string>();
  bool known = false;
  for (RuntimeLaw::Kind k :
       {RuntimeLaw::Kind::Engine, RuntimeLaw::Kind::TorqueConverter, RuntimeLaw::Kind::Spring,
        RuntimeLaw::Kind::VelocityMotor, RuntimeLaw::Kind::Compliance, RuntimeLaw::Kind::RigidRows}) {
    if (kind == to_string(k)) {
      l.kind = k;
      known = true;
    }
  }
  if (!known) throw std::invalid_argument("unknown law `" + kind + "`");
  l.path = j.at("path").get<std::string>();
  l.actuators = j.at("actuators").get<std::vector<std::string>>();
  l.curve_x = reals(j.at("curve_x"));
  l.curve_y = reals(j.at("curve_y"));
  l.curve2_x = reals(j.at("curve2_x"));
  l.curve2_y = reals(j.at("curve2_y"));
  l.parameter = real(j.at("parameter"));
  if (j.contains("joint_damping")) l.joint_damping = real(j.at("joint_damping"));
  if (j.contains("stiffness")) l.stiffness = real(j.at("stiffness"));
  for (auto [key, names] :
       {std::pair{"joints", &l.joints}, {"tendons", &l.tendons}, {"equalities", &l.equalities}})
    if (j.contains(key)) *names = j.at(key).get<std::vector<std::string>>();
  return l;
}

// The kind of MuJoCo element each quantity acts on (InteractionEnabled: one of three).
bool object_fits(Quantity q, MjObject o) {
  switch (q) {
    case Quantity::None:
      return true;
    case Quantity::Composite:
    case Quantity::Broadcast:
    case Quantity::Affine:
    case Quantity::Constant:
      return o == MjObject::None;
    case Quantity::Ctrl:
    case Quantity::ForceRange:
    case Quantity::ActuatorForce:
      return o == MjObject::Actuator;
    case Quantity::EqualityActive:
    case Quantity::GearRatio:
    case Quantity::DistanceTarget:
    case Quantity::GearSelect:
    case Quantity::EqualityTarget:
    case Quantity::EqualityForce:
      return o == MjObject::Equality;
    case Quantity::KinematicLinearVelocity:
    case Quantity::KinematicAngularVelocity:
    case Quantity::BodyPosition:
    case Quantity::BodyRPY:
    case Quantity::BodyLinearVelocity:
    case Quantity::BodyAngularVelocity:
    case Quantity::BodyLinearAcceleration:
    case Quantity::BodyTorque:
      return o == MjObject::Body;
    case Quantity::FreeLinearVelocity:
    case Quantity::FreeAngularVelocity:
    case Quantity::JointPosition:
    case Quantity::JointVelocity:
    case Quantity::JointLimitForce:
      return o == MjObject::Joint;
    case Quantity::InteractionEnabled:
      return o == MjObject::Tendon || o == MjObject::Actuator || o == MjObject::Joint;
    case Quantity::MotorForceRange:
    case Quantity::EngagementFraction:
    case Quantity::Engaged:
    case Quantity::EngageDuration:
    case Quantity::DisengageDuration:
    case Quantity::MotorForce:
    case Quantity::TendonVelocity:
    case Quantity::TendonLength:
    case Quantity::TendonLimitForce:
    case Quantity::TendonSpringForce:
      return o == MjObject::Tendon;
    case Quantity::SitePosition:
    case Quantity::SiteRPY:
    case Quantity::SiteLinearVelocity:
    case Quantity::SiteAngularVelocity:
    case Quantity::SiteLinearAcceleration:
    case Quantity::SiteAngularAcceleration:
    case Quantity::SiteRelativePosition:
    case Quantity::SiteRelativeRPY:
    case Quantity::SiteRelativeLinearVelocity:
    case Quantity::SiteRelativeAngularVelocity:
    case Quantity::SiteRelativeLinearAcceleration:
    case Quantity::SiteRelativeAngularAcceleration:
    case Quantity::MateForce:
    case Quantity::MateTorque:
    case Quantity::MateForceInFrame:
    case Quantity::MateTorqueInFrame:
      return o == MjObject::Site;
    case Quantity::SensorFields:
      return o == MjObject::Sensor;
  }
  return false;
}

bool all_finite(const std::vector<double>& values) {
  for (double v : values) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

// Why the runtime cannot use binding `b` as it stands ("" when it can): everything it indexes or computes
// with must be there and finite.
std::string binding_problem(const SignalBinding& b) {
  const Quantity q = b.quantity;
  if (q == Quantity::None) return "";
  if (!object_fits(q, b.object)) {
    return "quantity `" + std::string(to_string(q)) + "` does not act on a `" +
           std::string(to_string(b.object)) + "`";
  }
  const bool composed = q == Quantity::Composite || q == Quantity::Broadcast || q == Quantity::Affine;
  if (b.names.empty() && q != Quantity::Constant && q != Quantity::Composite && q != Quantity::Broadcast)
    return "it names no MuJoCo element";
  if (!composed) {
    for (const std::string& name : b.names) {
      if (name.empty()) return "it names an element with an empty name";
    }
  }
  if (!std::isfinite(b.sign)) return "its sign is not a finite number";
  if (!std::isfinite(b.initial)) return "its initial value is not a finite number";
  if (!all_finite(b.initial_vector)) return "its initial_vector holds a number that is not finite";
  if (std::isnan(b.low) || std::isnan(b.high)) return "its low or high is NaN";
  auto value_is = [&](SignalValue v) { return b.value == v; };
  switch (q) {
    case Quantity::ForceRange:
    case Quantity::MotorForceRange:
      if (!value_is(SignalValue::Vec2)) return "a range takes two numbers (value `vec2`)";
      break;
    case Quantity::KinematicLinearVelocity:
    case Quantity::KinematicAngularVelocity:
      if (b.input && !value_is(SignalValue::Vec3))
        return "a velocity input takes three numbers (value `vec3`)";
      if (!b.initial_vector.empty() && b.initial_vector.size() != 3)
        return "its initial_vector must hold a velocity's three numbers";
      break;
    case Quantity::FreeLinearVelocity:
    case Quantity::FreeAngularVelocity:
      if (!value_is(SignalValue::Vec3)) return "a velocity input takes three numbers (value `vec3`)";
      break;
    case Quantity::InteractionEnabled:
      if (b.low > b.high) return "its effort range's low exceeds its high";
      break;
    case Quantity::Engaged:
      if (b.initial_vector.size() != 1 || b.initial_vector[0] < 0)
        return "its initial_vector must hold the clutch's torque capacity (one number, not negative)";
      if (!(b.low >= 0 && b.high >= 0 && std::isfinite(b.low) && std::isfinite(b.high)))
        return "its engage and disengage durations (low, high) must be finite and not negative";
      break;
    case Quantity::EngagementFraction:
      if (!(std::isfinite(b.high) && b.high >= 0))
        return "its capacity (high) must be finite and not negative";
      break;
    case Quantity::GearSelect:
      if (!value_is(SignalValue::Int)) return "a gear is an Int (value `int`)";
      if (std::floor(b.initial) != b.initial || std::abs(b.initial) > 1e9)
        return "its initial gear is not a whole number of a gearbox";
      if (!std::isfinite(b.low)) return "its forward gear count (low) is not finite";
      break;
    case Quantity::Affine:
      if (!std::isfinite(b.low) || !std::isfinite(b.high)) return "its scale and offset must be finite";
      break;
    case Quantity::SensorFields:
      if (b.initial_vector.size() != b.names.size()) return "it needs one field index per sensor";
      break;
    case Quantity::SiteRelativePosition:
    case Quantity::SiteRelativeRPY:
    case Quantity::SiteRelativeLinearVelocity:
    case Quantity::SiteRelativeAngularVelocity:
    case Quantity::SiteRelativeLinearAcceleration:
    case Quantity::SiteRelativeAngularAcceleration:
      if (b.names.size() != 2) return "a relative value names two sites: the connector's and the reference's";
      break;
    case Quantity::MateForceInFrame:
    case Quantity::MateTorqueInFrame:
      if (b.initial_vector.size() != 4 || !(Eigen::Vector4d(b.initial_vector.data()).norm() > 1e-12))
        return "its initial_vector must hold the frame's rotation quaternion (w, x, y, z), not zero";
      break;
    case Quantity::BodyTorque:
      if (!b.input || !value_is(SignalValue::Vec3)) return "a body torque is an input of three numbers";
      break;
    default:
      break;
  }
  return "";
}

// Sensor noise: on a sensor's values only, each list one number for all of them or one per value, means
// finite, deviations finite and not negative.
std::string noise_problem(const SignalBinding& b) {
  const SignalNoise& n = b.noise;
  if (n.empty()) return "";
  if (b.input || b.quantity != Quantity::SensorFields)
    return "only a sensor's output (sensor_fields) has noise";
  const size_t values = b.names.size();
  for (const auto& [list, what] : {std::pair{&n.mean, "mean"},
                                   {&n.deviation, "deviation"},
                                   {&n.deviation_per_metre, "deviation_per_metre"}}) {
    if (list == &n.deviation_per_metre && list->empty()) continue;  // optional: none
    if (list->size() != 1 && list->size() != values) {
      return std::string("its noise's ") + what + " holds " + std::to_string(list->size()) +
             " numbers: one for every value, or one per value (" + std::to_string(values) + ")";
    }
    for (double v : *list) {
      if (!std::isfinite(v)) return std::string("its noise's ") + what + " holds a number that is not finite";
      if (list != &n.mean && v < 0) return std::string("its noise's ") + what + " holds a negative number";
    }
  }
  return "";
}

std::string law_problem(const RuntimeLaw& l) {
  using Kind = RuntimeLaw::Kind;
  const size_t wanted = l.kind == Kind::TorqueConverter                           ? 2
                        : l.kind == Kind::Compliance || l.kind == Kind::RigidRows ? 0
                                                                                  : 1;
  if (l.actuators.size() != wanted) {
    const char* law = l.kind == Kind::Engine            ? "an engine law"
                      : l.kind == Kind::TorqueConverter ? "a torque-converter law"
                      : l.kind == Kind::Spring          ? "a spring law"
                      : l.kind == Kind::VelocityMotor   ? "a velocity-motor law"
                      : l.kind == Kind::Compliance      ? "a compliance law"
                                                        : "a rigid-rows law";
    return std::string(law) + " needs " +
           (wanted == 0   ? "no actuator"
            : wanted == 1 ? "one actuator"
                          : "two actuators (pump, turbine)") +
           ", not " + std::to_string(l.actuators.size());
  }
  if (l.kind == Kind::Spring && !(l.parameter >= 0 && l.joint_damping >= 0 && std::isfinite(l.joint_damping)))
    return "a spring's relaxation time and joint damping must be finite and not negative";
  if (l.kind == Kind::Compliance &&
      (l.equalities.size() != 1 || !(l.stiffness > 0) || !std::isfinite(l.stiffness) || !(l.parameter >= 0)))
    return "a compliance needs one equality, a positive finite stiffness and a relaxation time not negative";
  if (l.kind == Kind::VelocityMotor && !(l.joint_damping >= 0 && std::isfinite(l.joint_damping)))
    return "a velocity motor's joint damping must be finite and not negative";
  for (const auto* curve : {&l.curve_x, &l.curve_y, &l.curve2_x, &l.curve2_y}) {
    if (!all_finite(*curve)) return "a curve holds a number that is not finite";
  }
  if (l.curve_x.size() != l.curve_y.size() || l.curve2_x.size() != l.curve2_y.size())
    return "a curve's x and y differ in length";
  if (!std::is_sorted(l.curve_x.begin(), l.curve_x.end()) ||
      !std::is_sorted(l.curve2_x.begin(), l.curve2_x.end()))
    return "a curve's x values are not in ascending order";
  if (!std::isfinite(l.parameter)) return "its parameter is not finite";
  return "";
}

}  // namespace

Manifest read_manifest(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ManifestError(path + ": error: cannot open the signal manifest\n");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_manifest(text.str(), path);
}

Manifest parse_manifest(const std::string& text, const std::string& path) {
  Manifest m;
  try {
    const json j = json::parse(text);
    // First: a newer format may have changed whatever follows.
    m.format_version = j.value("format_version", 0);
    if (m.format_version > kManifestFormatVersion) {
      throw ManifestError(path + ": error: the manifest's format_version is " +
                          std::to_string(m.format_version) + " but this runtime reads up to " +
                          std::to_string(kManifestFormatVersion) +
                          " (a newer openplx2mjcf wrote it: use the runtime of that version)\n");
    }
    m.model = j.at("model").get<std::string>();
    m.prefix = j.value("prefix", std::string());
    m.fingerprint = j.value("fingerprint", std::string());
    if (j.contains("timestep")) m.timestep = real(j.at("timestep"));
    m.mujoco = j.value("mujoco", std::string());
    m.timestep_dependent = j.value("timestep_dependent", true);
    m.timestep_choices = j.value("timestep_choices", std::vector<std::string>());
    for (const json& s : j.at("signals")) m.signals.push_back(binding(s));
    if (j.contains("laws")) {
      for (const json& l : j.at("laws")) m.laws.push_back(law(l));
    }
  } catch (const ManifestError&) {
    throw;
  } catch (const std::exception& e) {  // nlohmann's parse, type and key errors, and ours
    throw ManifestError(path + ": error: not a signal manifest: " + e.what() + "\n");
  }
  if (!(m.timestep >= 0 && std::isfinite(m.timestep)))
    throw ManifestError(path + ": error: its timestep is not a positive number of seconds\n");
  for (const SignalBinding& b : m.signals) {
    std::string problem = binding_problem(b);
    if (problem.empty()) problem = noise_problem(b);
    if (!problem.empty()) throw ManifestError(path + ": error: signal `" + b.path + "`: " + problem + "\n");
  }
  for (const RuntimeLaw& l : m.laws) {
    if (const std::string problem = law_problem(l); !problem.empty())
      throw ManifestError(path + ": error: law of `" + l.path + "`: " + problem + "\n");
  }
  return m;
}

}  // namespace openplx::mjcf
