#include "contract/manifest_reader.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <unordered_set>

namespace openplx::mjcf {

namespace {

using nlohmann::json;

// Enums by the names to_string gives them; each enum runs from 0 to its last enumerator.
template <typename E>
E parse_enum(const std::string& text, E last, const char* key) {
  for (int k = 0; k <= static_cast<int>(last); ++k) {
    if (to_string(static_cast<E>(k)) == text) return static_cast<E>(k);
  }
  throw std::invalid_argument("`" + std::string(key) + "`: unknown " + key + " `" + text + "`");
}

// A field's value for a message: its JSON text, cut short.
std::string shown(const json& v) {
  std::string text = v.dump(-1, ' ', false, json::error_handler_t::replace);
  if (text.size() > 40) text = text.substr(0, 37) + "...";
  return text;
}

// Field troubles are std::invalid_argument with what() "`key` ..."; the caller adds the signal or law.
[[noreturn]] void wrong(const std::string& key, const char* wanted, const json& v) {
  throw std::invalid_argument("`" + key + "` must be " + wanted + ", not " + shown(v));
}

const json& field(const json& j, const char* key) {
  const auto at = j.find(key);
  if (at == j.end()) throw std::invalid_argument("`" + std::string(key) + "` is missing");
  return *at;
}

std::string str(const json& j, const char* key) {
  const json& v = field(j, key);
  if (!v.is_string()) wrong(key, "a string", v);
  return v.get<std::string>();
}

bool flag(const json& j, const char* key) {
  const json& v = field(j, key);
  if (!v.is_boolean()) wrong(key, "true or false", v);
  return v.get<bool>();
}

// Numbers, and the strings the writer uses for values JSON cannot hold ("inf", "-inf", "nan").
double real(const json& v, const std::string& key) {
  if (v.is_number()) return v.get<double>();
  if (v.is_string()) {
    const std::string& s = v.get_ref<const std::string&>();
    if (s == "inf") return std::numeric_limits<double>::infinity();
    if (s == "-inf") return -std::numeric_limits<double>::infinity();
    if (s == "nan") return std::numeric_limits<double>::quiet_NaN();
  }
  wrong(key, "a number (or \"inf\", \"-inf\", \"nan\")", v);
}

double real(const json& j, const char* key) {
  return real(field(j, key), std::string(key));
}

const json& array(const json& j, const char* key) {
  const json& v = field(j, key);
  if (!v.is_array()) wrong(key, "an array", v);
  return v;
}

std::vector<double> reals(const json& j, const char* key) {
  std::vector<double> out;
  for (const json& item : array(j, key))
    out.push_back(real(item, std::string(key) + "[" + std::to_string(out.size()) + "]"));
  return out;
}

std::vector<std::string> texts(const json& j, const char* key) {
  std::vector<std::string> out;
  for (const json& item : array(j, key)) {
    if (!item.is_string()) wrong(std::string(key) + "[" + std::to_string(out.size()) + "]", "a string", item);
    out.push_back(item.get<std::string>());
  }
  return out;
}

// A whole number within [low, high]: JSON's integers, and numbers with a zero fraction (JSON Schema's
// integers include 1.0); nothing for other numbers, 1e300 and 2^64 among them (no cast that overflows).
std::optional<long long> whole_number(const json& v, long long low, long long high) {
  if (v.is_number_unsigned()) {
    const uint64_t x = v.get<uint64_t>();
    if (high >= 0 && x <= static_cast<uint64_t>(high) && (low <= 0 || x >= static_cast<uint64_t>(low)))
      return static_cast<long long>(x);
    return std::nullopt;
  }
  if (v.is_number_integer()) {
    const int64_t x = v.get<int64_t>();
    if (x >= low && x <= high) return x;
    return std::nullopt;
  }
  if (v.is_number_float()) {
    const double x = v.get<double>();
    if (std::floor(x) == x && x >= static_cast<double>(low) && x <= static_cast<double>(high))
      return static_cast<long long>(x);
  }
  return std::nullopt;
}

SignalBinding binding(const json& j) {
  SignalBinding b;
  const std::string direction = str(j, "direction");
  if (direction != "input" && direction != "output") wrong("direction", "\"input\" or \"output\"", direction);
  b.input = direction == "input";
  b.type = str(j, "type");
  b.value = parse_enum(str(j, "value"), SignalValue::Vector, "value");
  b.unit = str(j, "unit");
  b.enabled = flag(j, "enabled");
  b.quantity = parse_enum(str(j, "quantity"), Quantity::Constant, "quantity");
  b.object = parse_enum(str(j, "object"), MjObject::Sensor, "object");
  b.names = texts(j, "names");
  b.sensor = str(j, "sensor");
  b.sign = real(j, "sign");
  b.initial = real(j, "initial");
  b.initial_vector = reals(j, "initial_vector");
  b.low = real(j, "low");
  b.high = real(j, "high");
  b.reason = str(j, "reason");
  if (j.contains("runtime")) b.runtime = flag(j, "runtime");
  if (j.contains("noise")) {
    const json& n = j.at("noise");
    if (!n.is_object()) wrong("noise", "an object", n);
    try {
      b.noise.mean = reals(n, "mean");
      b.noise.deviation = reals(n, "deviation");
      if (n.contains("deviation_per_metre")) b.noise.deviation_per_metre = reals(n, "deviation_per_metre");
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("its noise's ") + e.what());
    }
  }
  return b;
}

RuntimeLaw law(const json& j) {
  RuntimeLaw l;
  const std::string kind = str(j, "kind");
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
  l.actuators = texts(j, "actuators");
  l.curve_x = reals(j, "curve_x");
  l.curve_y = reals(j, "curve_y");
  l.curve2_x = reals(j, "curve2_x");
  l.curve2_y = reals(j, "curve2_y");
  l.parameter = real(j, "parameter");
  if (j.contains("joint_damping")) l.joint_damping = real(j, "joint_damping");
  if (j.contains("stiffness")) l.stiffness = real(j, "stiffness");
  for (auto [key, names] :
       {std::pair{"joints", &l.joints}, {"tendons", &l.tendons}, {"equalities", &l.equalities}})
    if (j.contains(key)) *names = texts(j, key);
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

// The value kinds a quantity gives or takes, as the runtime reads and writes them (signal_reads.cpp,
// signal_writes.cpp): a scalar quantity fills one number, a vector one three; another kind would leave the
// caller's other numbers unwritten or write past them. "" when `v` fits.
std::string value_problem(Quantity q, SignalValue v) {
  using V = SignalValue;
  auto want = [&](std::initializer_list<V> kinds, const char* what) -> std::string {
    for (V k : kinds) {
      if (k == v) return "";
    }
    return "quantity `" + std::string(to_string(q)) + "` " + what + ", not `" + std::string(to_string(v)) +
           "`";
  };
  switch (q) {
    case Quantity::None:
      return "";
    case Quantity::EqualityActive:
    case Quantity::InteractionEnabled:
    case Quantity::Engaged:
      return want({V::Bool}, "is on or off (value `bool`)");
    case Quantity::GearSelect:
      return want({V::Int}, "is a gear number (value `int`)");
    case Quantity::ForceRange:
    case Quantity::MotorForceRange:
      return want({V::Vec2}, "is a range of two numbers (value `vec2`)");
    case Quantity::Composite:
    case Quantity::SensorFields:
      return want({V::Vector}, "is a list of numbers (value `vector`)");
    case Quantity::Constant:
      return want({V::Real, V::Bool, V::Int}, "is one number (value `real`, `bool` or `int`)");
    case Quantity::Broadcast:  // its targets' kind; each target checks what it is given
      return want({V::Real, V::Bool, V::Int, V::Vec2, V::Vec3}, "takes its targets' kind of value");
    case Quantity::KinematicLinearVelocity:
    case Quantity::KinematicAngularVelocity:
    case Quantity::FreeLinearVelocity:
    case Quantity::FreeAngularVelocity:
    case Quantity::BodyPosition:
    case Quantity::BodyRPY:
    case Quantity::BodyLinearVelocity:
    case Quantity::BodyAngularVelocity:
    case Quantity::BodyLinearAcceleration:
    case Quantity::BodyTorque:
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
      return want({V::Vec3}, "is three numbers (value `vec3`)");
    case Quantity::Ctrl:
    case Quantity::EngagementFraction:
    case Quantity::EngageDuration:
    case Quantity::DisengageDuration:
    case Quantity::GearRatio:
    case Quantity::DistanceTarget:
    case Quantity::EqualityTarget:
    case Quantity::JointPosition:
    case Quantity::JointVelocity:
    case Quantity::ActuatorForce:
    case Quantity::MotorForce:
    case Quantity::JointLimitForce:
    case Quantity::EqualityForce:
    case Quantity::TendonVelocity:
    case Quantity::TendonLength:
    case Quantity::TendonLimitForce:
    case Quantity::TendonSpringForce:
    case Quantity::Affine:
      return want({V::Real}, "is one number (value `real`)");
  }
  return "";
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
      if (!(b.low >= 0 && b.low <= static_cast<double>(b.initial_vector.size())) ||
          std::floor(b.low) != b.low)
        return "its forward gear count (low) must be a whole number from 0 to the number of its ratios";
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
  return value_problem(q, b.value);  // after the particular messages above
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
  json j;
  try {
    j = json::parse(text);
  } catch (const std::exception& e) {  // nlohmann's parse errors: not JSON, or numbers beyond a double
    throw ManifestError(path + ": error: not a signal manifest: " + e.what() + "\n");
  }
  auto refuse = [&](const std::string& what) { throw ManifestError(path + ": error: " + what + "\n"); };
  if (!j.is_object()) refuse("not a signal manifest: a JSON object, not " + shown(j));
  // First: a newer format may have changed whatever follows. Absent: written before it existed.
  if (j.contains("format_version")) {
    const json& v = j.at("format_version");
    const std::optional<long long> version = whole_number(v, 1, std::numeric_limits<int>::max());
    if (!version) {
      refuse("format_version must be a whole number from 1 to " + std::to_string(kManifestFormatVersion) +
             " (the formats this runtime reads), not " + shown(v));
    }
    m.format_version = static_cast<int>(*version);
  }
  if (m.format_version > kManifestFormatVersion) {
    refuse("the manifest's format_version is " + std::to_string(m.format_version) +
           " but this runtime reads up to " + std::to_string(kManifestFormatVersion) +
           " (a newer openplx2mjcf wrote it: use the runtime of that version)");
  }
  try {
    m.model = str(j, "model");
    if (j.contains("prefix")) m.prefix = str(j, "prefix");
    if (j.contains("fingerprint")) m.fingerprint = str(j, "fingerprint");
    if (j.contains("timestep")) m.timestep = real(j, "timestep");
    if (j.contains("mujoco")) m.mujoco = str(j, "mujoco");
    if (j.contains("timestep_dependent")) m.timestep_dependent = flag(j, "timestep_dependent");
    if (j.contains("timestep_choices")) m.timestep_choices = texts(j, "timestep_choices");
    array(j, "signals");
    if (j.contains("laws")) array(j, "laws");
  } catch (const std::invalid_argument& e) {
    refuse(std::string("not a signal manifest: ") + e.what());
  }
  // Each signal and law named in its errors: by its path, or by its place when the path is what is wrong.
  std::unordered_set<std::string> paths;
  for (const json& s : j.at("signals")) {
    std::string where = "signal " + std::to_string(m.signals.size() + 1);
    try {
      if (!s.is_object()) throw std::invalid_argument("must be an object, not " + shown(s));
      const std::string signal_path = str(s, "path");
      if (signal_path.empty()) throw std::invalid_argument("`path` is empty");
      where = "signal `" + signal_path + "`";
      // The bridge finds signals by path: a second one of a path could never be reached.
      if (!paths.insert(signal_path).second) refuse(where + " is listed twice");
      m.signals.push_back(binding(s));
      m.signals.back().path = signal_path;
    } catch (const std::invalid_argument& e) {
      refuse("not a signal manifest: " + where + ": " + e.what());
    }
  }
  if (j.contains("laws")) {
    for (const json& l : j.at("laws")) {
      std::string where = "law " + std::to_string(m.laws.size() + 1);
      try {
        if (!l.is_object()) throw std::invalid_argument("must be an object, not " + shown(l));
        const std::string law_path = str(l, "path");
        where = "law of `" + law_path + "`";
        m.laws.push_back(law(l));
        m.laws.back().path = law_path;
      } catch (const std::invalid_argument& e) {
        refuse("not a signal manifest: " + where + ": " + e.what());
      }
    }
  }
  if (!(m.timestep >= 0 && std::isfinite(m.timestep)))
    refuse("its timestep is not a positive number of seconds");
  for (const SignalBinding& b : m.signals) {
    std::string problem = binding_problem(b);
    if (problem.empty()) problem = noise_problem(b);
    if (!problem.empty()) refuse("signal `" + b.path + "`: " + problem);
  }
  for (const RuntimeLaw& l : m.laws) {
    if (const std::string problem = law_problem(l); !problem.empty())
      refuse("law of `" + l.path + "`: " + problem);
  }
  return m;
}

}  // namespace openplx::mjcf
