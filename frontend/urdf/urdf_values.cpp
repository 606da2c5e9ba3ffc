// What urdfdom would swallow or misread, found in the DOM first: malformed numbers (urdfdom drops the
// element, or the whole geometry, without a word), URDF 1.1 forms urdfdom 3.0.1 does not know (`quat_xyzw`
// origins, `<capsule>`), and the blocks for other tools (`<transmission>`, `<mujoco>`, `<gazebo>`) that are
// read by nobody here.
#include <Eigen/Geometry>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string_view>

#include "frontend/urdf/urdf_document.h"

namespace openplx::frontend {
namespace {

using tinyxml2::XMLElement;

// Numeric attributes by element, with how many numbers each holds.
const std::map<std::string, std::map<std::string, int>>& numeric_attributes() {
  static const std::map<std::string, std::map<std::string, int>> table = {
      {"origin", {{"xyz", 3}, {"rpy", 3}, {"quat_xyzw", 4}}},
      {"axis", {{"xyz", 3}}},
      {"mass", {{"value", 1}}},
      {"inertia", {{"ixx", 1}, {"ixy", 1}, {"ixz", 1}, {"iyy", 1}, {"iyz", 1}, {"izz", 1}}},
      {"box", {{"size", 3}}},
      {"cylinder", {{"radius", 1}, {"length", 1}}},
      {"capsule", {{"radius", 1}, {"length", 1}}},
      {"sphere", {{"radius", 1}}},
      {"mesh", {{"scale", 3}}},
      {"color", {{"rgba", 4}}},
      {"limit", {{"lower", 1}, {"upper", 1}, {"effort", 1}, {"velocity", 1}}},
      {"dynamics", {{"damping", 1}, {"friction", 1}}},
      {"mimic", {{"multiplier", 1}, {"offset", 1}}},
      {"safety_controller",
       {{"soft_lower_limit", 1}, {"soft_upper_limit", 1}, {"k_position", 1}, {"k_velocity", 1}}},
      {"calibration", {{"rising", 1}, {"falling", 1}}},
  };
  return table;
}

constexpr std::string_view kSpace = " \t\n\v\f\r";  // what `>>` skips in the classic locale

bool digit(char c) {
  return c >= '0' && c <= '9';
}

// Whether `word` is one number as urdfdom's strToDouble reads it (`std::stringstream >> double` in the
// classic locale, which must then reach the end): leading white space, a sign, digits with at most one point
// (`5.`, `.5`), an exponent after a digit (`1e-3`, `1E+2`), and nothing after it, not even a space. Checked
// by hand: a std::istringstream per attribute cost more than the rest of the import.
bool urdfdom_number(std::string_view word) {
  size_t i = std::min(word.find_first_not_of(kSpace), word.size());
  if (i < word.size() && (word[i] == '+' || word[i] == '-')) ++i;
  size_t digits = 0;
  for (; i < word.size() && digit(word[i]); ++i) ++digits;
  if (i < word.size() && word[i] == '.') {
    for (++i; i < word.size() && digit(word[i]); ++i) ++digits;
  }
  if (digits == 0) return false;
  if (i < word.size() && (word[i] == 'e' || word[i] == 'E')) {
    ++i;
    if (i < word.size() && (word[i] == '+' || word[i] == '-')) ++i;
    size_t exponent = 0;
    for (; i < word.size() && digit(word[i]); ++i) ++exponent;
    if (exponent == 0) return false;
  }
  return i == word.size();
}

// The value of a word urdfdom_number accepted, or nullopt when it overflows (urdfdom rejects that too; a
// number too small for a double is read as zero or a subnormal, as urdfdom does).
std::optional<double> urdfdom_value(std::string_view word) {
  word.remove_prefix(std::min(word.find_first_not_of(kSpace), word.size()));
  if (word[0] == '+') word.remove_prefix(1);  // std::from_chars reads no '+'
  double v = 0;
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), v);
  if (error == std::errc::result_out_of_range) {
    v = std::strtod(std::string(word).c_str(), nullptr);
  } else if (error != std::errc() || end != word.data() + word.size()) {
    return std::nullopt;
  }
  if (!std::isfinite(v)) return std::nullopt;
  return v;
}

// The numbers of `text` as urdfdom reads them, or nullopt with the first word that is not a finite number
// in `bad`. A list (xyz, rpy, size, scale, rgba) is split at spaces only, empty words skipped, so a tab or a
// line break between two numbers leaves one word that is no number; a single value is the whole text.
std::optional<std::vector<double>> numbers(const std::string& text, int count, std::string& bad) {
  std::vector<double> values;
  auto read = [&](std::string_view word) {
    const std::optional<double> v = urdfdom_number(word) ? urdfdom_value(word) : std::nullopt;
    if (!v) bad = std::string(word);
    if (v) values.push_back(*v);
    return v.has_value();
  };
  if (count == 1) {
    if (!read(text)) return std::nullopt;
    return values;
  }
  for (size_t begin = 0; begin <= text.size();) {
    const size_t stop = std::min(text.find(' ', begin), text.size());
    if (stop > begin && !read(std::string_view(text).substr(begin, stop - begin))) return std::nullopt;
    begin = stop + 1;
  }
  return values;
}

// Why `word` is no number, when a reader might not see it: white space urdfdom does not take.
std::string why_not_a_number(const std::string& word) {
  const size_t first = word.find_first_not_of(kSpace);
  if (first == std::string::npos) return word.empty() ? ": it is empty" : ": it is blank";
  const std::string_view rest = std::string_view(word).substr(first);
  if (rest.find_first_of(kSpace) == std::string_view::npos) return "";
  if (rest.find_first_not_of(kSpace, rest.find_first_of(kSpace)) == std::string_view::npos)
    return ": urdfdom reads nothing after a number, not even a space";
  return ": URDF separates numbers by spaces only; urdfdom reads a tab or a line break as part of a number";
}

// `text` with tabs, line breaks and other control characters shown as escapes, for a one-line message.
std::string shown(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '\t') {
      out += "\\t";
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char hex[8];
      std::snprintf(hex, sizeof(hex), "\\x%02x", static_cast<unsigned char>(c));
      out += hex;
    } else {
      out += c;
    }
  }
  return out;
}

// The shapes a <geometry> can hold (URDF 1.1 included) and the attributes each requires.
const std::map<std::string, std::vector<const char*>>& shapes() {
  static const std::map<std::string, std::vector<const char*>> table = {
      {"box", {"size"}},
      {"cylinder", {"radius", "length"}},
      {"capsule", {"radius", "length"}},
      {"sphere", {"radius"}},
      {"mesh", {"filename"}},
  };
  return table;
}

std::string exact(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof(buffer), "%.17g", v);
  return buffer;
}

// Roll, pitch, yaw (URDF's fixed-axis X, Y, Z order: R = Rz(yaw) Ry(pitch) Rx(roll)) of a rotation, from its
// matrix so that no angle loses precision near the poles.
Eigen::Vector3d rpy_of(const Eigen::Quaterniond& q) {
  const Eigen::Matrix3d r = q.normalized().toRotationMatrix();
  return {std::atan2(r(2, 1), r(2, 2)), std::atan2(-r(2, 0), std::hypot(r(0, 0), r(1, 0))),
          std::atan2(r(1, 0), r(0, 0))};
}

}  // namespace

bool UrdfDocument::check_values() {
  bool changed = false;
  std::vector<XMLElement*> stack{doc_.FirstChildElement("robot")};
  while (!stack.empty()) {
    XMLElement* e = stack.back();
    stack.pop_back();
    for (XMLElement* c = e->LastChildElement(); c; c = c->PreviousSiblingElement()) stack.push_back(c);
    const std::string tag = e->Name();
    const bool top = e->Parent() == doc_.FirstChildElement("robot");
    if (top && (tag == "transmission" || tag == "mujoco" || tag == "gazebo")) {
      const char* what = tag == "transmission"
                             ? "a ros_control transmission: no actuator was made from it (add motors to the "
                               "joint's mate in OpenPLX)"
                         : tag == "mujoco" ? "MuJoCo's own URDF compiler options, which do not apply to this "
                                             "converter's output"
                                           : "Gazebo settings";
      findings_.push_back({false, offset_of(e), "<" + tag + "> was not read: it holds " + what, {}});
      continue;
    }
    // A <geometry> holds one shape with what it needs: urdfdom drops the whole <visual> or <collision>
    // otherwise, without failing the robot.
    if (tag == "geometry") {
      const XMLElement* shape = e->FirstChildElement();
      if (!shape) {
        findings_.push_back({true, offset_of(e), "<geometry> holds no shape", {}});
      } else if (!shapes().count(shape->Name())) {
        findings_.push_back({true,
                             offset_of(shape),
                             "<" + std::string(shape->Name()) +
                                 "> is not a URDF shape (box, cylinder, sphere, mesh, capsule)",
                             {}});
      } else {
        for (const char* required : shapes().at(shape->Name())) {
          if (!shape->Attribute(required)) {
            findings_.push_back({true,
                                 offset_of(shape),
                                 "<" + std::string(shape->Name()) + "> has no " + required + " attribute",
                                 {}});
          }
        }
      }
    }
    auto known = numeric_attributes().find(tag);
    if (known == numeric_attributes().end()) continue;
    for (const auto& [attribute, count] : known->second) {
      const char* value = e->Attribute(attribute.c_str());
      if (!value) continue;
      std::string bad;
      const std::optional<std::vector<double>> v = numbers(value, count, bad);
      if (!v || static_cast<int>(v->size()) != count) {
        findings_.push_back({true,
                             offset_of(e),
                             "<" + tag + "> " + attribute + "=\"" + shown(value) + "\" is not " +
                                 (count == 1 ? "a number" : std::to_string(count) + " numbers") +
                                 (v ? "" : " (`" + shown(bad) + "`" + why_not_a_number(bad) + ")"),
                             {}});
      }
    }
    // URDF 1.1: an origin's rotation as a quaternion, x y z w. urdfdom 3.0.1 ignores it; it gets the same
    // rotation as rpy.
    if (tag == "origin" && e->Attribute("quat_xyzw")) {
      std::string bad;
      const std::optional<std::vector<double>> q = numbers(e->Attribute("quat_xyzw"), 4, bad);
      if (e->Attribute("rpy")) {
        findings_.push_back({true, offset_of(e), "<origin> has both rpy and quat_xyzw; URDF allows one", {}});
      } else if (q && q->size() == 4) {
        const Eigen::Quaterniond rotation((*q)[3], (*q)[0], (*q)[1], (*q)[2]);
        if (rotation.norm() < 1e-12) {
          findings_.push_back({true, offset_of(e), "<origin> quat_xyzw is zero, which is no rotation", {}});
        } else {
          const Eigen::Vector3d rpy = rpy_of(rotation);
          e->SetAttribute("rpy", (exact(rpy.x()) + " " + exact(rpy.y()) + " " + exact(rpy.z())).c_str());
        }
      }
      e->DeleteAttribute("quat_xyzw");
      changed = true;
    }
    // URDF 1.1 capsules: urdfdom reads the shape as a cylinder of the same radius and length (the length of
    // its cylindrical part); the import makes it a capsule again.
    if (tag == "capsule") {
      e->SetName("cylinder");
      capsules_.insert(e);
      changed = true;
    }
  }
  return changed;
}

bool UrdfDocument::is_capsule(const XMLElement* e) const {
  return capsules_.count(e) > 0;
}

}  // namespace openplx::frontend
