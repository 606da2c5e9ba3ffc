// The URDF as XML with positions: tinyxml2 reads it first so that every error (malformed XML, or one urdfdom
// reports without a position) and every generated OpenPLX line points at the URDF line it came from.
#pragma once

#include <tinyxml2.h>

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "frontend/urdf/urdf_result.h"

namespace openplx::frontend {

class UrdfDocument {
 public:
  // Parses `text` (the file at `path`, named in hints); a malformed document gives one located error in
  // `findings()`.
  explicit UrdfDocument(std::string text, std::string path = "");

  bool well_formed() const { return well_formed_; }
  const std::string& text() const { return text_; }
  std::vector<UrdfFinding>& findings() { return findings_; }

  // Byte offset of element `e`'s opening `<` (the start of its line when it cannot be found).
  uint32_t offset_of(const tinyxml2::XMLElement* e) const;
  uint32_t offset_of_line(int line) const;
  // The `<link>` or `<joint>` element of that name (the `nth` of that name, 0-based), or null.
  const tinyxml2::XMLElement* link(const std::string& name, int nth = 0) const;
  const tinyxml2::XMLElement* joint(const std::string& name, int nth = 0) const;
  const tinyxml2::XMLElement* robot() const { return robot_; }
  // The `nth` child of `parent` named `tag`, or null.
  static const tinyxml2::XMLElement* child(const tinyxml2::XMLElement* parent, const char* tag, int nth = 0);

  // The text urdfdom should read: the URDF itself, or, when a joint's <limit> lacks the effort or velocity
  // URDF requires (MuJoCo's compiler accepts that), a copy with them set to 0 (no limit) and a warning.
  // Malformed numbers become located errors here, URDF 1.1 forms urdfdom 3.0.1 cannot read are rewritten
  // (see check_values).
  std::string lenient_text();
  // Whether a shape element was a URDF 1.1 <capsule> (urdfdom reads it as a cylinder).
  bool is_capsule(const tinyxml2::XMLElement* e) const;

  // Turns urdfdom's messages (which carry no position) into one located error: at the first element a
  // message names, or at the joint that closes a loop, or else at `<robot>`; the other messages are notes.
  UrdfFinding locate(const std::vector<std::string>& urdfdom_messages) const;

 private:
  const tinyxml2::XMLElement* named(const std::multimap<std::string, const tinyxml2::XMLElement*>& index,
                                    const std::string& name, int nth) const;
  std::optional<UrdfFinding> loop_finding() const;
  const tinyxml2::XMLElement* element_with_attribute_text(const std::string& needle) const;
  bool check_values();  // urdf_values.cpp; true when the DOM was rewritten
  void find_xacro();    // sets xacro_ and xacro_declared_
  std::string expand_command() const;
  bool name_a_nameless_robot();  // true when the DOM was rewritten

  std::string path_;
  // An unexpanded xacro template: its first `<xacro:...>` element or `${...}`/`$(...)` attribute (a
  // reader would see only what lies outside its macros), or null.
  const tinyxml2::XMLElement* xacro_ = nullptr;
  // The xacro namespace or a .xacro name, which expanded files keep too: a hint only when the robot fails.
  const tinyxml2::XMLElement* xacro_declared_ = nullptr;

  std::string text_;
  tinyxml2::XMLDocument doc_;
  bool well_formed_ = false;
  const tinyxml2::XMLElement* robot_ = nullptr;
  std::vector<uint32_t> line_starts_;
  // Where each element's start tag is among those of its name on its line (document order), taken before
  // any rewrite renames an element: the nth `<link` of a long line is the nth link on it.
  struct Place {
    std::string tag;
    uint32_t nth = 0;
  };
  std::unordered_map<const tinyxml2::XMLElement*, Place> places_;
  // The offsets of `<tag` on a line, found once per line and name: a URDF written on one line is scanned
  // once per name, not once per element.
  mutable std::map<std::pair<int, std::string>, std::vector<uint32_t>> tag_offsets_;
  std::multimap<std::string, const tinyxml2::XMLElement*> links_, joints_;
  std::vector<UrdfFinding> findings_;
  std::set<const tinyxml2::XMLElement*> capsules_;
};

// While alive, urdfdom's console messages are collected into `errors` and `warnings` instead of
// printed: they become located diagnostics. console_bridge's handler is process-wide, so a mutex
// serialises concurrent imports.
class UrdfdomCapture {
 public:
  UrdfdomCapture(std::vector<std::string>& errors, std::vector<std::string>& warnings);
  ~UrdfdomCapture();
  UrdfdomCapture(const UrdfdomCapture&) = delete;
  UrdfdomCapture& operator=(const UrdfdomCapture&) = delete;

 private:
  struct Impl;
  Impl* impl_;
};

}  // namespace openplx::frontend
