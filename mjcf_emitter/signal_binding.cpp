#include "mjcf_emitter/signal_binding.h"

#include <cmath>

#include <algorithm>
#include <array>
#include <utility>

#include "frontend/quoted.h"
#include "mjcf_emitter/xml.h"

namespace openplx::mjcf {

using namespace std::string_view_literals;  // literals appended with their length known

namespace {

bool ends_with(std::string_view text, std::string_view suffix) {
  return text.size() >= suffix.size() && text.substr(text.size() - suffix.size()) == suffix;
}

}  // namespace

std::string_view signal_stem(std::string_view type) {
  if (const size_t dot = type.rfind('.'); dot != std::string_view::npos) type.remove_prefix(dot + 1);
  for (std::string_view end : {"Input", "Output"}) {
    if (ends_with(type, end)) type.remove_suffix(end.size());
  }
  return type;
}

SignalKind signal_kind(std::string_view type) {
  using V = SignalValue;
  // Longest names first where one ends another (AngularVelocity1D before Velocity1D is not needed: exact
  // match).
  static const std::array<std::pair<std::string_view, SignalKind>, 27> kinds{{
      {"Angle", {V::Real, "rad"}},
      {"AngularVelocity1D", {V::Real, "rad/s"}},
      {"Position1D", {V::Real, "m"}},
      {"LinearVelocity1D", {V::Real, "m/s"}},
      {"RelativeVelocity1D", {V::Real, "m/s"}},
      {"Torque1D", {V::Real, "N*m"}},
      {"Force1D", {V::Real, "N"}},
      {"TorqueRange", {V::Vec2, "N*m"}},
      {"ForceRange", {V::Vec2, "N"}},
      {"Position3D", {V::Vec3, "m"}},
      {"Position", {V::Vec3, "m"}},
      {"RPY", {V::Vec3, "rad"}},
      {"LinearVelocity3D", {V::Vec3, "m/s"}},
      {"AngularVelocity3D", {V::Vec3, "rad/s"}},
      {"Acceleration3D", {V::Vec3, "m/s^2"}},
      {"AngularAcceleration3D", {V::Vec3, "rad/s^2"}},
      {"Force3D", {V::Vec3, "N"}},
      {"Torque3D", {V::Vec3, "N*m"}},
      {"Duration", {V::Real, "s"}},
      {"Mass", {V::Real, "kg"}},
      {"Rpm", {V::Real, "rev/min"}},
      {"Fraction", {V::Real, ""}},
      {"Ratio", {V::Real, ""}},
      {"Int", {V::Int, ""}},
      {"Bool", {V::Bool, ""}},
      {"EnableInteraction", {V::Bool, ""}},
      {"InteractionEnabled", {V::Bool, ""}},
  }};
  const std::string_view s = signal_stem(type);
  for (const auto& [name, kind] : kinds) {
    if (s == name) return kind;
  }
  for (std::string_view boolean : {"Activate", "Activated", "Engage", "Engaged", "LockUp", "LockedUp"}) {
    if (ends_with(s, boolean)) return {V::Bool, ""};
  }
  if (ends_with(s, "Torque")) return {V::Real, "N*m"};  // e.g. TorqueConverterPumpTorqueOutput
  return {V::Real, ""};
}

std::string_view to_string(SignalValue value) {
  switch (value) {
    case SignalValue::Real:
      return "real";
    case SignalValue::Bool:
      return "bool";
    case SignalValue::Int:
      return "int";
    case SignalValue::Vec2:
      return "vec2";
    case SignalValue::Vec3:
      return "vec3";
    case SignalValue::Vector:
      return "vector";
  }
  return "real";
}

std::string_view to_string(MjObject object) {
  switch (object) {
    case MjObject::None:
      return "none";
    case MjObject::Actuator:
      return "actuator";
    case MjObject::Joint:
      return "joint";
    case MjObject::Body:
      return "body";
    case MjObject::Site:
      return "site";
    case MjObject::Equality:
      return "equality";
    case MjObject::Tendon:
      return "tendon";
    case MjObject::Sensor:
      return "sensor";
  }
  return "none";
}

std::string_view to_string(Quantity quantity) {
  switch (quantity) {
    case Quantity::None:
      return "none";
    case Quantity::Ctrl:
      return "ctrl";
    case Quantity::ForceRange:
      return "force_range";
    case Quantity::EqualityActive:
      return "equality_active";
    case Quantity::KinematicLinearVelocity:
      return "kinematic_linear_velocity";
    case Quantity::KinematicAngularVelocity:
      return "kinematic_angular_velocity";
    case Quantity::FreeLinearVelocity:
      return "free_linear_velocity";
    case Quantity::FreeAngularVelocity:
      return "free_angular_velocity";
    case Quantity::MotorForceRange:
      return "motor_force_range";
    case Quantity::InteractionEnabled:
      return "interaction_enabled";
    case Quantity::JointPosition:
      return "joint_position";
    case Quantity::JointVelocity:
      return "joint_velocity";
    case Quantity::ActuatorForce:
      return "actuator_force";
    case Quantity::MotorForce:
      return "motor_force";
    case Quantity::EngagementFraction:
      return "engagement_fraction";
    case Quantity::Engaged:
      return "engaged";
    case Quantity::TendonVelocity:
      return "tendon_velocity";
    case Quantity::TendonSpringForce:
      return "tendon_spring_force";
    case Quantity::TendonLength:
      return "tendon_length";
    case Quantity::TendonLimitForce:
      return "tendon_limit_force";
    case Quantity::DistanceTarget:
      return "distance_target";
    case Quantity::EqualityTarget:
      return "equality_target";
    case Quantity::GearRatio:
      return "gear_ratio";
    case Quantity::GearSelect:
      return "gear_select";
    case Quantity::EngageDuration:
      return "engage_duration";
    case Quantity::DisengageDuration:
      return "disengage_duration";
    case Quantity::EqualityForce:
      return "equality_force";
    case Quantity::JointLimitForce:
      return "joint_limit_force";
    case Quantity::BodyPosition:
      return "body_position";
    case Quantity::BodyRPY:
      return "body_rpy";
    case Quantity::BodyLinearVelocity:
      return "body_linear_velocity";
    case Quantity::BodyAngularVelocity:
      return "body_angular_velocity";
    case Quantity::BodyLinearAcceleration:
      return "body_linear_acceleration";
    case Quantity::SitePosition:
      return "site_position";
    case Quantity::SiteRPY:
      return "site_rpy";
    case Quantity::SiteLinearVelocity:
      return "site_linear_velocity";
    case Quantity::SiteAngularVelocity:
      return "site_angular_velocity";
    case Quantity::MateForce:
      return "mate_force";
    case Quantity::MateTorque:
      return "mate_torque";
    case Quantity::Composite:
      return "composite";
    case Quantity::SensorFields:
      return "sensor_fields";
    case Quantity::Broadcast:
      return "broadcast";
    case Quantity::Affine:
      return "affine";
    case Quantity::Constant:
      return "constant";
  }
  return "none";
}

GearSelection gearbox_ratio(const std::vector<double>& forward, const std::vector<double>& reverse,
                            bool has_neutral, int gear) {
  GearSelection g;
  if (gear > 0 && gear <= static_cast<int>(forward.size())) {
    g.ratio = std::abs(forward[static_cast<size_t>(gear - 1)]);
  } else if (gear < 0 && -gear <= static_cast<int>(reverse.size())) {
    g.ratio = -std::abs(reverse[static_cast<size_t>(-gear - 1)]);
  } else if (gear == 0) {
    if (!has_neutral && !forward.empty()) g.ratio = std::abs(forward.front());
  } else {
    g.valid = false;
  }
  return g;
}

double steering_polynomial(const std::vector<double>& c, double x) {
  double y = 0;
  for (size_t p = c.size(); p-- > 0;) y = y * x + c[p];  // Horner
  return y;
}

double steering_polynomial_inverse(const std::vector<double>& c, double y) {
  if (c.empty()) return y;
  const double slope = c.size() > 1 ? c[1] : 0;
  if (slope == 0) return 0;
  double x = (y - c[0]) / slope;
  for (int iteration = 0; iteration < 50; ++iteration) {
    double derivative = 0;
    for (size_t p = c.size() - 1; p >= 1; --p) derivative = derivative * x + static_cast<double>(p) * c[p];
    if (derivative == 0 || !std::isfinite(derivative)) break;
    const double dx = (steering_polynomial(c, x) - y) / derivative;
    x -= dx;
    if (std::abs(dx) <= 1e-15 * std::max(1.0, std::abs(x))) break;
  }
  return x;
}

namespace {

// Appends a JSON number; numbers JSON cannot hold are the strings "nan", "inf" and "-inf".
void append_json_number(std::string& out, double value) {
  if (std::isnan(value)) {
    out += "\"nan\""sv;
  } else if (std::isinf(value)) {
    out += value > 0 ? "\"inf\""sv : "\"-inf\""sv;
  } else {
    append_number(out, value);
  }
}

void append_numbers(std::string& out, const char* key, const std::vector<double>& values) {
  ((out += ", \""sv) += key) += "\": ["sv;
  for (size_t k = 0; k < values.size(); ++k) {
    if (k) out += ", "sv;
    append_json_number(out, values[k]);
  }
  out += ']';
}

// The characters frontend::append_quoted escapes, as a table: one load per character scanned.
constexpr std::array<bool, 256> kEscaped = [] {
  std::array<bool, 256> table{};
  for (unsigned char c : {'"', '\\', '\n', '\t', '\r'}) table[c] = true;
  return table;
}();

bool needs_escape(char c) {
  return kEscaped[static_cast<unsigned char>(c)];
}

// A JSON string as frontend::append_quoted writes it; names and paths rarely hold anything to escape, so
// those are copied whole after one plain scan.
void append_string(std::string& out, std::string_view text) {
  if (std::any_of(text.begin(), text.end(), needs_escape)) {
    frontend::append_quoted(out, text);
    return;
  }
  ((out += '"') += text) += '"';
}

}  // namespace

std::string manifest_json(std::string_view model_name, std::string_view prefix,
                          const std::vector<SignalBinding>& bindings, const std::vector<RuntimeLaw>& laws) {
  std::string whole;
  whole.reserve(64 + 400 * bindings.size());  // a little over what one binding takes: one allocation
  write_manifest_json(model_name, prefix, bindings, laws, [&whole](std::string_view part) { whole += part; });
  return whole;
}

void write_manifest_json(std::string_view model_name, std::string_view prefix,
                         const std::vector<SignalBinding>& bindings, const std::vector<RuntimeLaw>& laws,
                         const std::function<void(std::string_view)>& write) {
  // Appended in place (a large model has tens of thousands of signals) and handed on in pieces, so a file
  // written from it never holds the whole text in memory.
  constexpr size_t kPiece = 64 << 10;
  std::string out;
  out.reserve(kPiece + 4096);
  auto hand_on = [&](size_t at_least) {
    if (out.size() < at_least) return;
    write(out);
    out.clear();
  };
  out += "{\n  \"model\": "sv;
  append_string(out, model_name);
  out += ",\n  \"prefix\": "sv;
  append_string(out, prefix);
  out += ",\n  \"signals\": ["sv;
  bool first = true;
  for (const SignalBinding& b : bindings) {
    out += first ? "\n    {\"path\": "sv : ",\n    {\"path\": "sv;
    first = false;
    append_string(out, b.path);
    (out += ", \"direction\": \""sv) += b.input ? "input"sv : "output"sv;
    out += "\", \"type\": "sv;
    append_string(out, b.type);
    ((out += ", \"value\": \""sv) += to_string(b.value)) += "\", \"unit\": "sv;
    append_string(out, b.unit);
    (out += ", \"enabled\": "sv) += b.enabled ? "true"sv : "false"sv;
    ((out += ", \"quantity\": \""sv) += to_string(b.quantity)) += "\", \"object\": \""sv;
    (out += to_string(b.object)) += "\", \"names\": ["sv;
    for (size_t k = 0; k < b.names.size(); ++k) {
      if (k) out += ", "sv;
      append_string(out, b.names[k]);
    }
    out += "], \"sensor\": "sv;
    append_string(out, b.sensor);
    out += ", \"sign\": "sv;
    append_json_number(out, b.sign);
    out += ", \"initial\": "sv;
    append_json_number(out, b.initial);
    append_numbers(out, "initial_vector", b.initial_vector);
    out += ", \"low\": "sv;
    append_json_number(out, b.low);
    out += ", \"high\": "sv;
    append_json_number(out, b.high);
    out += ", \"reason\": "sv;
    append_string(out, b.reason);
    (out += ", \"runtime\": "sv) += b.runtime ? "true"sv : "false"sv;
    out += '}';
    hand_on(kPiece);
  }
  out += "\n  ],\n  \"laws\": ["sv;
  first = true;
  for (const RuntimeLaw& law : laws) {
    out += first ? "\n    {\"kind\": \""sv : ",\n    {\"kind\": \""sv;
    first = false;
    out += law.kind == RuntimeLaw::Kind::Engine ? "engine"sv : "torque_converter"sv;
    out += "\", \"path\": "sv;
    append_string(out, law.path);
    out += ", \"actuators\": ["sv;
    for (size_t k = 0; k < law.actuators.size(); ++k) {
      if (k) out += ", "sv;
      append_string(out, law.actuators[k]);
    }
    out += ']';
    append_numbers(out, "curve_x", law.curve_x);
    append_numbers(out, "curve_y", law.curve_y);
    append_numbers(out, "curve2_x", law.curve2_x);
    append_numbers(out, "curve2_y", law.curve2_y);
    out += ", \"parameter\": "sv;
    append_json_number(out, law.parameter);
    out += '}';
    hand_on(kPiece);
  }
  out += "\n  ]\n}\n"sv;
  hand_on(0);
}

}  // namespace openplx::mjcf
