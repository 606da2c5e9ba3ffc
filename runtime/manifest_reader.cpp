#include "runtime/manifest_reader.h"

#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "openplx/runtime/simulation.h"

namespace openplx::runtime {

namespace {

using mjcf::MjObject;
using mjcf::Quantity;
using mjcf::SignalValue;
using nlohmann::json;

// Enums by the names to_string gives them; each enum runs from 0 to its last enumerator.
template <typename E>
E parse_enum(const std::string& text, E last, const char* what) {
  for (int k = 0; k <= static_cast<int>(last); ++k) {
    if (mjcf::to_string(static_cast<E>(k)) == text) return static_cast<E>(k);
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

mjcf::SignalBinding binding(const json& j) {
  mjcf::SignalBinding b;
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
  return b;
}

mjcf::RuntimeLaw law(const json& j) {
  mjcf::RuntimeLaw l;
  const std::string kind = j.at("kind").get<std::string>();
  if (kind != "engine" && kind != "torque_converter")
    throw std::invalid_argument("unknown law `" + kind + "`");
  l.kind = kind == "engine" ? mjcf::RuntimeLaw::Kind::Engine : mjcf::RuntimeLaw::Kind::TorqueConverter;
  l.path = j.at("path").get<std::string>();
  l.actuators = j.at("actuators").get<std::vector<std::string>>();
  l.curve_x = reals(j.at("curve_x"));
  l.curve_y = reals(j.at("curve_y"));
  l.curve2_x = reals(j.at("curve2_x"));
  l.curve2_y = reals(j.at("curve2_y"));
  l.parameter = real(j.at("parameter"));
  return l;
}

}  // namespace

Manifest read_manifest(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw LoadError(path + ": error: cannot open the signal manifest\n");
  std::ostringstream text;
  text << in.rdbuf();
  try {
    const json j = json::parse(text.str());
    Manifest m;
    m.model = j.at("model").get<std::string>();
    m.prefix = j.value("prefix", std::string());
    for (const json& s : j.at("signals")) m.signals.push_back(binding(s));
    if (j.contains("laws")) {
      for (const json& l : j.at("laws")) m.laws.push_back(law(l));
    }
    return m;
  } catch (const std::exception& e) {  // nlohmann's parse, type and key errors, and ours
    throw LoadError(path + ": error: not a signal manifest: " + e.what() + "\n");
  }
}

}  // namespace openplx::runtime
