// A small typed-enough XML tree for MJCF: elements with ordered attributes and children, printed with a
// fixed order, two-space indentation and locale-independent shortest round-trip numbers, so the same model
// always gives the same bytes.
#pragma once

#include <Eigen/Dense>
#include <initializer_list>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace openplx::mjcf {

// Shortest text that reads back as the same double ("0.5", "1e-07", "-0"); never locale-dependent.
std::string number(double value);
// Appends number(value) to `out`, with no string of its own.
void append_number(std::string& out, double value);
// Writes number(value) at `at`, which has room for kNumberChars, and returns the end of what it wrote.
inline constexpr size_t kNumberChars = 32;  // the longest double ("-1.7976931348623157e+308") is 24
char* write_number(char* at, double value);
// Numbers separated by single spaces ("0 0 1.5"), as MJCF writes vectors.
std::string numbers(std::initializer_list<double> values);
// How many NaNs and infinities write_number has written on this thread: none may reach an MJCF (MuJoCo
// reads them, then fails or blows up), so the emitter counts them as a backstop behind the value checks.
size_t non_finite_numbers_written();

class Element {
 public:
  explicit Element(std::string name) : name_(std::move(name)) {}

  Element& set(std::string_view key, std::string value);
  Element& set(std::string_view key, double value) { return set(key, number(value)); }
  Element& set(std::string_view key, int value) { return set(key, std::to_string(value)); }
  Element& set(std::string_view key, const Eigen::Vector3d& v);
  Element& set_quat(std::string_view key, const Eigen::Quaterniond& q);  // "w x y z", w >= 0
  Element& add(std::string name);                                        // appends a child and returns it
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
