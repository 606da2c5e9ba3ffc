// A small typed-enough XML tree for MJCF: elements with ordered attributes and children, printed with a
// fixed order, two-space indentation and locale-independent shortest round-trip numbers, so the same model
// always gives the same bytes.
#pragma once

#include <concepts>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "contract/numbers.h"

namespace openplx::mjcf {

class Element {
 public:
  explicit Element(std::string name) : name_(std::move(name)) {}

  Element& set(std::string_view key, std::string value);
  Element& set(std::string_view key, double value) { return set(key, number(value)); }
  Element& set(std::string_view key, int value) { return set(key, std::to_string(value)); }
  // Any vector with x(), y(), z() (Eigen's among them: this header does not need Eigen).
  template <typename Vector>
  requires requires(const Vector& v) {
    { v.z() } -> std::convertible_to<double>;
  }
  Element& set(std::string_view key, const Vector& v) { return set(key, numbers({v.x(), v.y(), v.z()})); }
  // A quaternion (Eigen's), normalised, as "w x y z" with w >= 0 (q and -q are the same rotation).
  template <typename Quaternion>
  Element& set_quat(std::string_view key, const Quaternion& q) {
    const auto n = q.normalized();
    const double s = n.w() < 0 ? -1.0 : 1.0;
    return set(key, numbers({s * n.w(), s * n.x(), s * n.y(), s * n.z()}));
  }
  Element& add(std::string name);  // appends a child and returns it
  Element& add(Element child);

  const std::string& name() const { return name_; }
  const std::string* get(std::string_view key) const;
  Element& erase(std::string_view key);  // removes the attribute if present
  // Children are held by pointer, so an element's address never changes: emitters keep pointers to joints
  // and bodies while adding more elements.
  const std::vector<std::unique_ptr<Element>>& children() const { return children_; }
  std::vector<std::unique_ptr<Element>>& children() { return children_; }
  // The first child element named `name` (MJCF sections such as <contact> appear once), or null.
  Element* child(std::string_view name);

  // The whole tree as XML text (iterative, so deep trees cannot exhaust the stack).
  std::string to_string() const;
  // The first attribute in the tree holding a NaN or an infinity, as `<name key="value">`; empty if none.
  std::string first_non_finite() const;

 private:
  std::string name_;
  std::vector<std::pair<std::string, std::string>> attributes_;
  std::vector<std::unique_ptr<Element>> children_;
};

}  // namespace openplx::mjcf
