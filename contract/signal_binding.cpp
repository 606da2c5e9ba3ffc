#include "contract/signal_binding.h"

#include <cmath>
#include <cstdint>
#include <cstring>

#include <algorithm>
#include <array>
#include <utility>

#include "contract/numbers.h"

namespace openplx::mjcf {

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

std::string_view to_string(RuntimeLaw::Kind kind) {
  switch (kind) {
    case RuntimeLaw::Kind::Engine:
      return "engine";
    case RuntimeLaw::Kind::TorqueConverter:
      return "torque_converter";
    case RuntimeLaw::Kind::Spring:
      return "spring";
    case RuntimeLaw::Kind::VelocityMotor:
      return "velocity_motor";
    case RuntimeLaw::Kind::Compliance:
      return "compliance";
    case RuntimeLaw::Kind::RigidRows:
      return "rigid_rows";
  }
  return "";
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
    case Quantity::SiteLinearAcceleration:
      return "site_linear_acceleration";
    case Quantity::SiteAngularAcceleration:
      return "site_angular_acceleration";
    case Quantity::SiteRelativePosition:
      return "site_relative_position";
    case Quantity::SiteRelativeRPY:
      return "site_relative_rpy";
    case Quantity::SiteRelativeLinearVelocity:
      return "site_relative_linear_velocity";
    case Quantity::SiteRelativeAngularVelocity:
      return "site_relative_angular_velocity";
    case Quantity::SiteRelativeLinearAcceleration:
      return "site_relative_linear_acceleration";
    case Quantity::SiteRelativeAngularAcceleration:
      return "site_relative_angular_acceleration";
    case Quantity::MateForceInFrame:
      return "mate_force_in_frame";
    case Quantity::MateTorqueInFrame:
      return "mate_torque_in_frame";
    case Quantity::BodyTorque:
      return "body_torque";
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
  // In 64 bits: -gear of INT_MIN does not fit an int, and a list's size need not either.
  const int64_t n = gear, forward_count = static_cast<int64_t>(forward.size()),
                reverse_count = static_cast<int64_t>(reverse.size());
  if (n > 0 && n <= forward_count) {
    g.ratio = std::abs(forward[static_cast<size_t>(n - 1)]);
  } else if (n < 0 && -n <= reverse_count) {
    g.ratio = -std::abs(reverse[static_cast<size_t>(-n - 1)]);
  } else if (n == 0) {
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

// The characters frontend::append_quoted escapes, as a table: one load per character scanned.
constexpr std::array<bool, 256> kEscaped = [] {
  std::array<bool, 256> table{};
  for (unsigned char c : {'"', '\\', '\n', '\t', '\r'}) table[c] = true;
  return table;
}();

// Whether `text` has nothing to escape, eight bytes at a time (names and paths rarely have anything), the
// last eight overlapping the others. A word with a byte below 0x20 also fails, which only sends it through
// the exact escaping loop.
bool plain(std::string_view text) {
  if (text.size() < 8) {
    for (char c : text) {
      if (kEscaped[static_cast<unsigned char>(c)]) return false;
    }
    return true;
  }
  constexpr uint64_t kOnes = 0x0101010101010101, kHigh = 0x8080808080808080;
  auto has_zero = [](uint64_t x) { return (x - kOnes) & ~x & kHigh; };
  auto special = [&](size_t at) {
    uint64_t x;
    std::memcpy(&x, text.data() + at, 8);
    return ((x - kOnes * 0x20) & ~x & kHigh) | has_zero(x ^ (kOnes * '"')) | has_zero(x ^ (kOnes * '\\'));
  };
  for (size_t k = 0; k + 8 < text.size(); k += 8) {
    if (special(k)) return false;
  }
  return !special(text.size() - 8);
}

// Writes the manifest into room made ahead (room_for), so fixed text is a copy of known length and nothing
// checks capacity piece by piece (a large model has tens of thousands of signals).
class Cursor {
 public:
  explicit Cursor(char* at) : at_(at) {}
  char* end() const { return at_; }

  template <size_t N>
  Cursor& text(const char (&literal)[N]) {
    std::memcpy(at_, literal, N - 1);
    at_ += N - 1;
    return *this;
  }
  Cursor& text(std::string_view s) {
    if (!s.empty()) std::memcpy(at_, s.data(), s.size());  // an empty view may hold no pointer
    at_ += s.size();
    return *this;
  }
  Cursor& boolean(bool value) { return value ? text("true") : text("false"); }
  // A JSON string as frontend::append_quoted writes it. Room: twice its length and the quotes.
  Cursor& string(std::string_view s) {
    *at_++ = '"';
    if (plain(s)) {
      text(s);
    } else {
      for (char c : s) escape(c);
    }
    *at_++ = '"';
    return *this;
  }
  // Room: kNumberChars. Numbers JSON cannot hold are the strings "nan", "inf" and "-inf".
  Cursor& number(double value) {
    if (value == 0.0) return text("0");  // most signs, initial values and ranges: no call (-0 too, as ever)
    if (value == 1.0) return text("1");
    if (std::isnan(value)) return text("\"nan\"");
    if (std::isinf(value)) return value > 0 ? text("\"inf\"") : text("\"-inf\"");
    at_ = write_number(at_, value);
    return *this;
  }
  Cursor& numbers(const std::vector<double>& values) {
    *at_++ = '[';
    for (size_t k = 0; k < values.size(); ++k) {
      if (k) text(", ");
      number(values[k]);
    }
    *at_++ = ']';
    return *this;
  }
  Cursor& strings(const std::vector<std::string>& values) {
    *at_++ = '[';
    for (size_t k = 0; k < values.size(); ++k) {
      if (k) text(", ");
      string(values[k]);
    }
    *at_++ = ']';
    return *this;
  }

 private:
  void escape(char c) {
    switch (c) {
      case '"':
        text("\\\"");
        break;
      case '\\':
        text("\\\\");
        break;
      case '\n':
        text("\\n");
        break;
      case '\t':
        text("\\t");
        break;
      case '\r':
        text("\\r");
        break;
      default:
        *at_++ = c;
    }
  }

  char* at_;
};

// Room for what Cursor writes: fixed text and enumerations (under 400 characters), strings escaped (twice
// their length, quoted and separated), numbers.
constexpr size_t kFixedRoom = 512;
size_t string_room(std::string_view s) {
  return 2 * s.size() + 4;
}
size_t strings_room(const std::vector<std::string>& values) {
  size_t room = 2;
  for (const std::string& value : values) room += string_room(value);
  return room;
}
size_t numbers_room(const std::vector<double>& values) {
  return 2 + values.size() * (kNumberChars + 2);
}

size_t room_for(const SignalBinding& b) {
  return kFixedRoom + 4 * kNumberChars + string_room(b.path) + string_room(b.type) + string_room(b.unit) +
         strings_room(b.names) + string_room(b.sensor) + numbers_room(b.initial_vector) +
         string_room(b.reason) + numbers_room(b.noise.mean) + numbers_room(b.noise.deviation) +
         numbers_room(b.noise.deviation_per_metre);
}

size_t room_for(const RuntimeLaw& law) {
  return kFixedRoom + kNumberChars + string_room(law.path) + strings_room(law.actuators) +
         numbers_room(law.curve_x) + numbers_room(law.curve_y) + numbers_room(law.curve2_x) +
         numbers_room(law.curve2_y);
}

void write_binding(Cursor& out, const SignalBinding& b) {
  out.text("{\"path\": ").string(b.path);
  if (b.input) {
    out.text(", \"direction\": \"input\", \"type\": ");
  } else {
    out.text(", \"direction\": \"output\", \"type\": ");
  }
  out.string(b.type).text(", \"value\": \"").text(to_string(b.value)).text("\", \"unit\": ").string(b.unit);
  if (b.enabled) {
    out.text(", \"enabled\": true, \"quantity\": \"");
  } else {
    out.text(", \"enabled\": false, \"quantity\": \"");
  }
  out.text(to_string(b.quantity)).text("\", \"object\": \"").text(to_string(b.object));
  out.text("\", \"names\": ").strings(b.names).text(", \"sensor\": ").string(b.sensor);
  out.text(", \"sign\": ").number(b.sign).text(", \"initial\": ").number(b.initial);
  out.text(", \"initial_vector\": ").numbers(b.initial_vector);
  out.text(", \"low\": ").number(b.low).text(", \"high\": ").number(b.high);
  out.text(", \"reason\": ").string(b.reason).text(", \"runtime\": ").boolean(b.runtime);
  if (!b.noise.empty()) {  // only outputs with sensor noise: every other line stays as it was
    out.text(", \"noise\": {\"mean\": ").numbers(b.noise.mean);
    out.text(", \"deviation\": ").numbers(b.noise.deviation);
    if (!b.noise.deviation_per_metre.empty())
      out.text(", \"deviation_per_metre\": ").numbers(b.noise.deviation_per_metre);
    out.text("}");
  }
  out.text("}");
}

void write_law(Cursor& out, const RuntimeLaw& law) {
  out.text("{\"kind\": \"").text(to_string(law.kind)).text("\", \"path\": ");
  out.string(law.path).text(", \"actuators\": ").strings(law.actuators);
  out.text(", \"curve_x\": ").numbers(law.curve_x).text(", \"curve_y\": ").numbers(law.curve_y);
  out.text(", \"curve2_x\": ").numbers(law.curve2_x).text(", \"curve2_y\": ").numbers(law.curve2_y);
  out.text(", \"parameter\": ").number(law.parameter);
  if (law.kind == RuntimeLaw::Kind::Spring || law.kind == RuntimeLaw::Kind::VelocityMotor)
    out.text(", \"joint_damping\": ").number(law.joint_damping);
  if (law.kind == RuntimeLaw::Kind::Compliance || law.kind == RuntimeLaw::Kind::Spring)
    out.text(", \"stiffness\": ").number(law.stiffness);
  if (!law.joints.empty()) out.text(", \"joints\": ").strings(law.joints);
  if (!law.tendons.empty()) out.text(", \"tendons\": ").strings(law.tendons);
  if (!law.equalities.empty()) out.text(", \"equalities\": ").strings(law.equalities);
  out.text("}");
}

}  // namespace

std::string manifest_json(std::string_view model_name, std::string_view prefix,
                          const std::vector<SignalBinding>& bindings, const std::vector<RuntimeLaw>& laws,
                          const ManifestModel& model) {
  std::string whole;
  whole.reserve(64 + 400 * bindings.size());  // a little over what one binding takes: one allocation
  write_manifest_json(model_name, prefix, bindings, laws, model,
                      [&whole](std::string_view part) { whole += part; });
  return whole;
}

void write_manifest_json(std::string_view model_name, std::string_view prefix,
                         const std::vector<SignalBinding>& bindings, const std::vector<RuntimeLaw>& laws,
                         const std::function<void(std::string_view)>& write) {
  write_manifest_json(model_name, prefix, bindings, laws, ManifestModel{}, write);
}

void write_manifest_json(std::string_view model_name, std::string_view prefix,
                         const std::vector<SignalBinding>& bindings, const std::vector<RuntimeLaw>& laws,
                         const ManifestModel& model, const std::function<void(std::string_view)>& write) {
  // Written in place and handed on in pieces, so a file written from it never holds the whole text in memory.
  constexpr size_t kPiece = 64 << 10;
  std::string buffer(kPiece + 8192, '\0');
  size_t used = 0;
  auto cursor = [&](size_t room) {
    if (used + room > buffer.size()) buffer.resize(used + room);
    return Cursor(buffer.data() + used);
  };
  auto done = [&](const Cursor& out, size_t hand_on_at) {
    used = static_cast<size_t>(out.end() - buffer.data());
    if (used < hand_on_at) return;
    write(std::string_view(buffer.data(), used));
    used = 0;
  };
  Cursor head = cursor(kFixedRoom + 2 * kNumberChars + string_room(model_name) + string_room(prefix) +
                       string_room(model.fingerprint) + string_room(model.mujoco) +
                       strings_room(model.timestep_choices));
  head.text("{\n  \"format_version\": ").number(kManifestFormatVersion);
  head.text(",\n  \"model\": ").string(model_name).text(",\n  \"prefix\": ").string(prefix);
  if (!model.fingerprint.empty()) head.text(",\n  \"fingerprint\": ").string(model.fingerprint);
  if (model.timestep > 0) {
    head.text(",\n  \"timestep\": ").number(model.timestep);
    if (!model.mujoco.empty()) head.text(",\n  \"mujoco\": ").string(model.mujoco);
    head.text(",\n  \"timestep_dependent\": ").boolean(!model.timestep_choices.empty());
    head.text(",\n  \"timestep_choices\": ").strings(model.timestep_choices);
  }
  head.text(",\n  \"signals\": [");
  done(head, kPiece);
  // The items of one JSON array, each on its own line.
  auto items = [&](const auto& list, auto write_item) {
    for (size_t k = 0; k < list.size(); ++k) {
      Cursor out = cursor(room_for(list[k]));
      if (k) out.text(",");
      out.text("\n    ");
      write_item(out, list[k]);
      done(out, kPiece);
    }
  };
  items(bindings, [](Cursor& out, const SignalBinding& b) { write_binding(out, b); });
  Cursor middle = cursor(kFixedRoom);
  middle.text("\n  ],\n  \"laws\": [");
  done(middle, kPiece);
  items(laws, [](Cursor& out, const RuntimeLaw& law) { write_law(out, law); });
  Cursor tail = cursor(kFixedRoom);
  tail.text("\n  ]\n}\n");
  done(tail, 0);
}

}  // namespace openplx::mjcf
