#include "mjcf_emitter/xml.h"

#include <algorithm>

#include <charconv>
#include <cmath>

namespace openplx::mjcf {
namespace {

std::string escaped(std::string_view text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

}  // namespace

std::string number(double value) {
  if (value == 0.0) return "0";  // also folds -0, which MuJoCo reads the same
  char buffer[64];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, end);
}

Element* Element::child(std::string_view name) {
  for (const std::unique_ptr<Element>& e : children_) {
    if (e->name() == name) return e.get();
  }
  return nullptr;
}

Element& Element::set(std::string_view key, std::string value) {
  for (auto& [k, v] : attributes_) {
    if (k == key) {
      v = std::move(value);
      return *this;
    }
  }
  attributes_.emplace_back(std::string(key), std::move(value));
  return *this;
}

Element& Element::erase(std::string_view key) {
  attributes_.erase(std::remove_if(attributes_.begin(), attributes_.end(),
                                   [&](const auto& attribute) { return attribute.first == key; }),
                    attributes_.end());
  return *this;
}

Element& Element::set(std::string_view key, const Eigen::Vector3d& v) {
  return set(key, number(v.x()) + " " + number(v.y()) + " " + number(v.z()));
}

Element& Element::set_quat(std::string_view key, const Eigen::Quaterniond& q) {
  Eigen::Quaterniond n = q.normalized();
  if (n.w() < 0) n.coeffs() = -n.coeffs();
  return set(key, number(n.w()) + " " + number(n.x()) + " " + number(n.y()) + " " + number(n.z()));
}

Element& Element::add(std::string name) {
  children_.push_back(std::make_unique<Element>(std::move(name)));
  return *children_.back();
}

Element& Element::add(Element child) {
  children_.push_back(std::make_unique<Element>(std::move(child)));
  return *children_.back();
}

const std::string* Element::get(std::string_view key) const {
  for (const auto& [k, v] : attributes_) {
    if (k == key) return &v;
  }
  return nullptr;
}

std::string Element::to_string() const {
  std::string out;
  struct Frame {
    const Element* element;
    size_t next;
    size_t depth;
  };
  std::vector<Frame> stack{{this, 0, 0}};
  while (!stack.empty()) {
    Frame& frame = stack.back();
    const Element& e = *frame.element;
    const std::string indent(frame.depth * 2, ' ');
    if (frame.next == 0) {
      out += indent + "<" + e.name_;
      for (const auto& [k, v] : e.attributes_) out += " " + k + "=\"" + escaped(v) + "\"";
      if (e.children_.empty()) {
        out += "/>\n";
        stack.pop_back();
        continue;
      }
      out += ">\n";
    }
    if (frame.next < e.children_.size()) {
      const Element* child = e.children_[frame.next++].get();
      stack.push_back({child, 0, frame.depth + 1});
      continue;
    }
    out += indent + "</" + e.name_ + ">\n";
    stack.pop_back();
  }
  return out;
}

}  // namespace openplx::mjcf
