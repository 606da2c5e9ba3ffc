#include "mjcf_emitter/xml.h"

#include <algorithm>
#include <cmath>

namespace openplx::mjcf {
namespace {

bool needs_entity(char c) {
  return c == '&' || c == '<' || c == '>' || c == '"';
}

// Appends an attribute value with & < > " as entities; runs without them are copied whole.
void append_escaped(std::string& out, std::string_view text) {
  while (!text.empty()) {
    size_t plain = 0;
    while (plain < text.size() && !needs_entity(text[plain])) ++plain;
    out.append(text.substr(0, plain));
    if (plain == text.size()) return;
    switch (text[plain]) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      default:
        out += "&quot;";
        break;
    }
    text.remove_prefix(plain + 1);
  }
}

// A number token that is no finite number, as to_chars writes them ("inf", "-nan").
bool non_finite_token(std::string_view token) {
  if (!token.empty() && token.front() == '-') token.remove_prefix(1);
  return token == "inf" || token == "nan";
}

// MJCF attributes whose values are names (of the element or of what it refers to), never numbers.
bool names_something(std::string_view key) {
  for (std::string_view k :
       {"name",     "model",   "class", "childclass", "body",    "body1",  "body2",    "joint",
        "joint1",   "joint2",  "geom",  "geom1",      "geom2",   "site",   "tendon",   "mesh",
        "material", "texture", "file",  "hfield",     "objname", "target", "actuator", "type"}) {
    if (key == k) return true;
  }
  return false;
}

}  // namespace

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
  if (attributes_.empty()) attributes_.reserve(4);  // most elements have a few: one allocation
  attributes_.emplace_back(std::string(key), std::move(value));
  return *this;
}

Element& Element::erase(std::string_view key) {
  attributes_.erase(std::remove_if(attributes_.begin(), attributes_.end(),
                                   [&](const auto& attribute) { return attribute.first == key; }),
                    attributes_.end());
  return *this;
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

std::string Element::first_non_finite() const {
  std::vector<const Element*> stack{this};
  while (!stack.empty()) {
    const Element& e = *stack.back();
    stack.pop_back();
    for (const auto& [key, value] : e.attributes_) {
      if (names_something(key)) continue;  // a body named "inf" is no number
      for (size_t start = 0; start <= value.size();) {
        const size_t end = std::min(value.find(' ', start), value.size());
        if (non_finite_token(std::string_view(value).substr(start, end - start)))
          return "<" + e.name_ + " " + key + "=\"" + value + "\">";
        start = end + 1;
      }
    }
    for (auto it = e.children_.rbegin(); it != e.children_.rend(); ++it) stack.push_back(it->get());
  }
  return {};
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
    if (frame.next == 0) {
      out.append(frame.depth * 2, ' ');
      (out += '<') += e.name_;
      for (const auto& [k, v] : e.attributes_) {
        ((out += ' ') += k) += "=\"";
        append_escaped(out, v);
        out += '"';
      }
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
    out.append(frame.depth * 2, ' ');
    ((out += "</") += e.name_) += ">\n";
    stack.pop_back();
  }
  return out;
}

}  // namespace openplx::mjcf
