#include "frontend/urdf/urdf_document.h"

#include <console_bridge/console.h>

#include <algorithm>
#include <filesystem>
#include <mutex>
#include <set>

namespace openplx::frontend {

using tinyxml2::XMLElement;

namespace {

// tinyxml2's error in words (its own text is the enumerator's name and the line number again).
std::string xml_error_text(const tinyxml2::XMLDocument& doc) {
  switch (doc.ErrorID()) {
    case tinyxml2::XML_ERROR_PARSING_ELEMENT:
      return "an element on this line is not well formed";
    case tinyxml2::XML_ERROR_PARSING_ATTRIBUTE:
      return "an attribute on this line is not well formed";
    case tinyxml2::XML_ERROR_MISMATCHED_ELEMENT:
      return "an element opened here is not closed by a matching end tag";
    case tinyxml2::XML_ERROR_EMPTY_DOCUMENT:
      return "the file has no XML element";
    case tinyxml2::XML_ERROR_PARSING_TEXT:
    case tinyxml2::XML_ERROR_PARSING_CDATA:
    case tinyxml2::XML_ERROR_PARSING_COMMENT:
    case tinyxml2::XML_ERROR_PARSING_DECLARATION:
    case tinyxml2::XML_ERROR_PARSING_UNKNOWN:
    case tinyxml2::XML_ERROR_PARSING:
      return "the XML here cannot be parsed";
    default:
      return doc.ErrorName() ? doc.ErrorName() : "XML error";
  }
}

}  // namespace

UrdfDocument::UrdfDocument(std::string text, std::string path)
    : path_(std::move(path)), text_(std::move(text)) {
  line_starts_.push_back(0);
  for (uint32_t i = 0; i < text_.size(); ++i) {
    if (text_[i] == '\n') line_starts_.push_back(i + 1);
  }
  if (doc_.Parse(text_.data(), text_.size()) != tinyxml2::XML_SUCCESS) {
    uint32_t at = offset_of_line(doc_.ErrorLineNum());
    while (at < text_.size() && (text_[at] == ' ' || text_[at] == '\t')) ++at;
    findings_.push_back({true, at, "malformed URDF: " + xml_error_text(doc_), {}});
    return;
  }
  robot_ = doc_.FirstChildElement("robot");
  if (!robot_) {
    findings_.push_back({true, 0, "a URDF's root element must be <robot>", {}});
    return;
  }
  well_formed_ = true;
  std::map<std::pair<int, std::string>, uint32_t> counts;
  std::vector<const XMLElement*> stack{robot_};
  while (!stack.empty()) {  // document order
    const XMLElement* e = stack.back();
    stack.pop_back();
    std::string tag = e->Name();
    const uint32_t nth = counts[{e->GetLineNum(), tag}]++;
    places_.emplace(e, Place{std::move(tag), nth});
    for (const XMLElement* c = e->LastChildElement(); c; c = c->PreviousSiblingElement()) stack.push_back(c);
  }
  find_xacro();
  for (const XMLElement* e = robot_->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const char* name = e->Attribute("name");
    if (!name) continue;
    if (std::string_view(e->Name()) == "link") links_.emplace(name, e);
    if (std::string_view(e->Name()) == "joint") joints_.emplace(name, e);
  }
}

void UrdfDocument::find_xacro() {
  std::vector<const XMLElement*> stack{robot_};
  while (!stack.empty() && !xacro_) {  // document order: the first one is reported
    const XMLElement* e = stack.back();
    stack.pop_back();
    if (std::string_view(e->Name()).substr(0, 6) == "xacro:") xacro_ = e;
    for (const tinyxml2::XMLAttribute* a = e->FirstAttribute(); a && !xacro_; a = a->Next()) {
      const std::string_view value = a->Value();
      if (value.find("${") != std::string_view::npos || value.find("$(") != std::string_view::npos)
        xacro_ = e;
    }
    for (const XMLElement* c = e->LastChildElement(); c; c = c->PreviousSiblingElement()) stack.push_back(c);
  }
  std::string extension = std::filesystem::path(path_).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (robot_->Attribute("xmlns:xacro") || extension == ".xacro") xacro_declared_ = robot_;
}

// The command that expands this file: `xacro arm.urdf.xacro > arm.urdf`.
std::string UrdfDocument::expand_command() const {
  const std::filesystem::path file = std::filesystem::path(path_).filename();
  const std::string name = file.empty() ? "model.urdf.xacro" : file.string();
  std::string out = file.empty() ? "model.urdf" : file.stem().string();
  std::string extension = std::filesystem::path(name).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension != ".xacro") {
    out += ".expanded.urdf";  // not the file itself: the shell would empty it before xacro reads it
  } else if (std::filesystem::path(out).extension().empty()) {
    out += ".urdf";
  }
  return "`xacro " + name + " > " + out + "`";
}

uint32_t UrdfDocument::offset_of_line(int line) const {
  if (line < 1) return 0;
  return line_starts_[std::min<size_t>(static_cast<size_t>(line - 1), line_starts_.size() - 1)];
}

uint32_t UrdfDocument::offset_of(const XMLElement* e) const {
  if (!e) return 0;
  const int line = e->GetLineNum();
  const uint32_t begin = offset_of_line(line);
  const auto place = places_.find(e);
  const std::string tag = place != places_.end() ? place->second.tag : std::string(e->Name());
  auto [found, fresh] = tag_offsets_.try_emplace({line, tag});
  std::vector<uint32_t>& offsets = found->second;
  if (fresh) {
    const uint32_t end = static_cast<size_t>(line) < line_starts_.size()
                             ? line_starts_[line]
                             : static_cast<uint32_t>(text_.size());
    const std::string open = "<" + tag;
    const std::string_view text = std::string_view(text_).substr(begin, end - begin);
    for (size_t at = text.find(open); at != std::string_view::npos; at = text.find(open, at + 1)) {
      const size_t after = at + open.size();  // `<inertia` must not match `<inertial`
      if (after >= text.size() || std::string_view(" \t\r\n/>").find(text[after]) != std::string_view::npos)
        offsets.push_back(begin + static_cast<uint32_t>(at));
    }
  }
  if (offsets.empty()) return begin;
  const uint32_t nth = place != places_.end() ? place->second.nth : 0;
  return offsets[nth < offsets.size() ? nth : 0];
}

const XMLElement* UrdfDocument::named(const std::multimap<std::string, const XMLElement*>& index,
                                      const std::string& name, int nth) const {
  auto [first, last] = index.equal_range(name);
  for (; first != last; ++first) {
    if (nth-- == 0) return first->second;
  }
  return nullptr;
}

const XMLElement* UrdfDocument::link(const std::string& name, int nth) const {
  return named(links_, name, nth);
}
const XMLElement* UrdfDocument::joint(const std::string& name, int nth) const {
  return named(joints_, name, nth);
}

const XMLElement* UrdfDocument::child(const XMLElement* parent, const char* tag, int nth) {
  if (!parent) return nullptr;
  for (const XMLElement* e = parent->FirstChildElement(tag); e; e = e->NextSiblingElement(tag)) {
    if (nth-- == 0) return e;
  }
  return nullptr;
}

// The first element (document order) with an attribute whose value contains `needle`.
const XMLElement* UrdfDocument::element_with_attribute_text(const std::string& needle) const {
  std::vector<const XMLElement*> stack{robot_};
  while (!stack.empty()) {
    const XMLElement* e = stack.back();
    stack.pop_back();
    for (const tinyxml2::XMLAttribute* a = e->FirstAttribute(); a; a = a->Next()) {
      if (std::string_view(a->Value()).find(needle) != std::string_view::npos) return e;
    }
    std::vector<const XMLElement*> children;
    for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) children.push_back(c);
    stack.insert(stack.end(), children.rbegin(), children.rend());
  }
  return nullptr;
}

namespace {

// The names a urdfdom message quotes, as `[name]` or `'name'`, in order.
std::vector<std::string> quoted_names(const std::string& message) {
  std::vector<std::string> names;
  for (size_t i = 0; i < message.size(); ++i) {
    const char close = message[i] == '[' ? ']' : message[i] == '\'' ? '\'' : 0;
    if (!close) continue;
    const size_t end = message.find(close, i + 1);
    if (end == std::string::npos) break;
    names.push_back(message.substr(i + 1, end - i - 1));
    i = end;
  }
  return names;
}

const char* attribute(const XMLElement* e, const char* name) {
  const char* v = e ? e->Attribute(name) : nullptr;
  return v ? v : "";
}

}  // namespace

// Every link is some joint's child when the joints form a loop (or a joint is its own parent): urdfdom then
// finds no root. The joint that closes the loop is the useful place to point at.
std::optional<UrdfFinding> UrdfDocument::loop_finding() const {
  std::map<std::string, const XMLElement*> parent_joint;  // child link -> its joint
  for (const auto& [name, j] : joints_) {
    const std::string parent = attribute(child(j, "parent"), "link"),
                      kid = attribute(child(j, "child"), "link");
    if (!parent.empty() && parent == kid) {
      return UrdfFinding{
          true, offset_of(j), "joint `" + name + "` has link `" + parent + "` as parent and child", {}};
    }
    parent_joint.emplace(kid, j);
  }
  // The links on a loop, found in one pass (each link has one parent): a walk up from every link would be
  // quadratic in a long chain.
  std::map<std::string, int> state;  // absent: not seen; 1: on the current walk; 2: done
  std::set<std::string> on_loop;
  for (const auto& [first, unused] : parent_joint) {
    std::vector<std::string> walk;
    std::string l = first;
    while (!state.count(l)) {
      state[l] = 1;
      walk.push_back(l);
      const auto up = parent_joint.find(l);
      if (up == parent_joint.end()) break;
      l = attribute(child(up->second, "parent"), "link");
    }
    if (state.count(l) && state[l] == 1 && parent_joint.count(walk.back())) {
      for (auto it = std::find(walk.begin(), walk.end(), l); it != walk.end(); ++it) on_loop.insert(*it);
    }
    for (const std::string& w : walk) state[w] = 2;
  }
  for (const auto& [start, unused] : links_) {
    if (!on_loop.count(start)) continue;
    std::vector<const XMLElement*> path;
    std::set<std::string> seen;
    for (std::string l = start; parent_joint.count(l) && seen.insert(l).second;) {
      path.push_back(parent_joint.at(l));
      l = attribute(child(path.back(), "parent"), "link");
      if (l == start) {
        const XMLElement* last = *std::max_element(
            path.begin(), path.end(), [](auto* a, auto* b) { return a->GetLineNum() < b->GetLineNum(); });
        std::string cycle;
        for (auto it = path.rbegin(); it != path.rend(); ++it)
          cycle += std::string(attribute(*it, "name")) + " → ";
        return UrdfFinding{true,
                           offset_of(last),
                           "joint `" + std::string(attribute(last, "name")) + "` closes a loop (" + cycle +
                               attribute(path.back(), "name") + "); a URDF must be a tree",
                           {}};
      }
    }
  }
  return std::nullopt;
}

// urdfdom refuses a <robot> without a name; MuJoCo's importer loads it. It is named after its file, said.
bool UrdfDocument::name_a_nameless_robot() {
  XMLElement* robot = doc_.FirstChildElement("robot");
  const char* written = robot->Attribute("name");
  if (written && *written) return false;
  std::string name = std::filesystem::path(path_).stem().string();
  if (name.empty()) name = "robot";
  robot->SetAttribute("name", name.c_str());
  findings_.push_back({false,
                       offset_of(robot_),
                       std::string("the <robot> has ") + (written ? "an empty name" : "no name") +
                           " (URDF requires one); it was named `" + name + "` after its file",
                       {}});
  return true;
}

std::string UrdfDocument::lenient_text() {
  if (xacro_) {  // the rest would only be the template's placeholders, each an error
    const std::string what = std::string_view(xacro_->Name()).substr(0, 6) == "xacro:"
                                 ? "<" + std::string(xacro_->Name()) + ">"
                                 : "a ${...} or $(...) placeholder";
    findings_.push_back({true,
                         offset_of(xacro_),
                         "this is an unexpanded xacro template (" + what +
                             " here), not a URDF: a URDF reader would see only what lies outside its macros. "
                             "Expand it first: " +
                             expand_command() + ", and convert the result",
                         {}});
    return text_;
  }
  bool changed = check_values();
  // The DOM itself (not the const index) is edited here.
  changed = name_a_nameless_robot() || changed;
  for (XMLElement* j = doc_.FirstChildElement("robot")->FirstChildElement("joint"); j;
       j = j->NextSiblingElement("joint")) {
    XMLElement* limit = j->FirstChildElement("limit");
    if (!limit) continue;
    const std::string name = j->Attribute("name") ? j->Attribute("name") : "";
    std::string missing;
    for (const char* attribute : {"effort", "velocity"}) {
      if (limit->Attribute(attribute)) continue;
      limit->SetAttribute(attribute, "0");
      missing += missing.empty() ? attribute : std::string(" and ") + attribute;
      changed = true;
    }
    if (!missing.empty()) {
      findings_.push_back({false,
                           offset_of(limit),
                           "the <limit> of joint `" + name + "` has no " + missing +
                               " (URDF requires them); read as no limit",
                           {}});
    }
  }
  if (!changed) return text_;
  tinyxml2::XMLPrinter printer;
  doc_.Print(&printer);
  return printer.CStr();
}

UrdfFinding UrdfDocument::locate(const std::vector<std::string>& messages) const {
  UrdfFinding finding{true, offset_of(robot_), "urdfdom rejected the robot", {}};
  bool located = false;
  for (const std::string& message : messages) {
    if (located) {
      finding.notes.push_back("urdfdom: " + message);
      continue;
    }
    const XMLElement* at = nullptr;
    if (message.find("root link") != std::string::npos) {
      if (std::optional<UrdfFinding> loop = loop_finding()) {
        finding = *loop;
        finding.notes.push_back("urdfdom: " + message);
        located = true;
        continue;
      }
    }
    const bool duplicate = message.find("not unique") != std::string::npos;
    for (const std::string& name : quoted_names(message)) {
      at = joint(name, duplicate ? 1 : 0);
      if (!at) at = link(name, duplicate ? 1 : 0);
      // A message about one part of the element ("Malformed parent origin", "Could not parse limit"):
      // point at that part.
      for (const char* part : {"origin", "limit", "axis", "mimic", "dynamics", "inertia", "calibration",
                               "safety_controller", "geometry", "material"}) {
        if (at && message.find(part) != std::string::npos && child(at, part)) {
          at = child(at, part);
          break;
        }
      }
      if (!at && !name.empty() && link(name) == nullptr && joint(name) == nullptr &&
          message.find("parse") != std::string::npos) {
        at = element_with_attribute_text(name);  // a malformed value: the element that holds it
      }
      if (at) break;
    }
    if (at) {
      finding = {true, offset_of(at), message, {}};
      located = true;
    } else {
      finding.notes.push_back("urdfdom: " + message);
    }
  }
  if (!located && !finding.notes.empty()) {
    finding.message = finding.notes.front().substr(9);  // urdfdom's first message, at <robot>
    finding.notes.erase(finding.notes.begin());
  }
  if (xacro_declared_) {
    const std::string why =
        xacro_declared_->Attribute("xmlns:xacro")
            ? "declares the xacro namespace (line " + std::to_string(xacro_declared_->GetLineNum()) + ")"
            : "is named as a xacro template";
    finding.notes.push_back("the file " + why + ": if it is a template, expand it first: " +
                            expand_command() + ", and convert the result");
  }
  return finding;
}

struct UrdfdomCapture::Impl : console_bridge::OutputHandler {
  std::unique_lock<std::mutex> lock;
  std::vector<std::string>& errors;
  std::vector<std::string>& warnings;
  console_bridge::OutputHandler* previous;
  Impl(std::vector<std::string>& e, std::vector<std::string>& w)
      : lock(mutex()), errors(e), warnings(w), previous(console_bridge::getOutputHandler()) {
    console_bridge::useOutputHandler(this);
  }
  ~Impl() override { console_bridge::useOutputHandler(previous); }
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR)
      errors.push_back(text);
    else if (level == console_bridge::CONSOLE_BRIDGE_LOG_WARN)
      warnings.push_back(text);
  }
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
};

UrdfdomCapture::UrdfdomCapture(std::vector<std::string>& errors, std::vector<std::string>& warnings)
    : impl_(new Impl(errors, warnings)) {}
UrdfdomCapture::~UrdfdomCapture() {
  delete impl_;
}

}  // namespace openplx::frontend
