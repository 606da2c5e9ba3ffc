// Converts a scene with one signal attached (the "probe") through the command line's own entry point, in
// process, and reads what became of the probe: mapped (its manifest quantity and MuJoCo element), warned
// (the manifest's reason; the warning printed), left unmapped without a warning, or an error.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "tools/cli/cli.h"

namespace openplx::catalogue {

struct Outcome {
  enum class Kind { Mapped, Warned, Silent, Error };
  Kind kind = Kind::Error;
  std::string detail;  // "quantity on object `name`", the reason, or the error message
};

inline std::string_view to_string(Outcome::Kind kind) {
  switch (kind) {
    case Outcome::Kind::Mapped:
      return "mapped";
    case Outcome::Kind::Warned:
      return "warned";
    case Outcome::Kind::Silent:
      return "unmapped, no warning";
    case Outcome::Kind::Error:
      return "error";
  }
  return "";
}

struct Conversion {
  int status = 0;
  std::vector<std::string> errors, warnings;  // messages without their `file:line:col: kind: ` prefix
  std::string manifest;
};

namespace detail {

inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The message of each `...: <kind>: message` line (file names left out: they hold the scratch folder).
inline std::vector<std::string> messages(const std::string& text, std::string_view kind) {
  std::vector<std::string> out;
  std::istringstream lines(text);
  const std::string marker = ": " + std::string(kind) + ": ";
  for (std::string line; std::getline(lines, line);) {
    const size_t at = line.find(marker);
    if (at != std::string::npos) out.push_back(line.substr(at + marker.size()));
  }
  return out;
}

// The JSON string (or list of strings, joined by ", ") after `"key": ` in `line`.
inline std::string json_field(std::string_view line, std::string_view key) {
  const std::string marker = "\"" + std::string(key) + "\": ";
  size_t at = line.find(marker);
  if (at == std::string_view::npos) return "";
  at += marker.size();
  std::string out;
  const bool list = line[at] == '[';
  bool in_string = false;
  for (size_t i = at; i < line.size(); ++i) {
    const char c = line[i];
    if (in_string) {
      if (c == '\\' && i + 1 < line.size()) {
        out += line[++i];
      } else if (c == '"') {
        in_string = false;
        if (!list) return out;
      } else {
        out += c;
      }
    } else if (c == '"') {
      if (list && !out.empty()) out += ", ";
      in_string = true;
    } else if (list && c == ']') {
      return out;
    } else if (!list) {
      return out;
    }
  }
  return out;
}

}  // namespace detail

// Writes `text` as `dir/name.openplx` and converts it to `dir/name.xml` (and its manifest).
inline Conversion convert(const std::filesystem::path& dir, const std::string& name,
                          const std::string& text) {
  const std::filesystem::path input = dir / (name + ".openplx"), xml = dir / (name + ".xml");
  std::ofstream(input, std::ios::binary) << text;
  std::ostringstream out, err;
  Conversion c;
  c.status = openplx::cli::run({input.string(), "-o", xml.string()}, out, err);
  c.errors = detail::messages(err.str(), "error");
  c.warnings = detail::messages(err.str(), "warning");
  if (c.status == 0) c.manifest = detail::read_file(openplx::cli::manifest_path(xml.string()));
  return c;
}

// What became of the signal at `path` (relative to the scene) in `c`.
inline Outcome outcome_of(const Conversion& c, const std::string& path) {
  if (c.status != 0) {
    return {Outcome::Kind::Error,
            c.errors.empty() ? "exit status " + std::to_string(c.status) : c.errors.front()};
  }
  const std::string key = "{\"path\": \"" + path + "\",";
  const size_t at = c.manifest.find(key);
  if (at == std::string::npos) return {Outcome::Kind::Error, "not in the manifest"};
  const std::string_view line = std::string_view(c.manifest).substr(at, c.manifest.find('\n', at) - at);
  std::vector<std::string> mine;  // warnings naming the probe
  for (const std::string& w : c.warnings) {
    if (w.find("`" + path + "`") != std::string::npos || w.find("`" + path + ".") != std::string::npos)
      mine.push_back(w);
  }
  const std::string quantity = detail::json_field(line, "quantity");
  if (quantity != "none") {
    const std::string object = detail::json_field(line, "object"), names = detail::json_field(line, "names");
    std::string detail = quantity;
    if (object != "none") {
      detail += " on " + object + " `" + names + "`";
    } else if (!names.empty()) {
      detail += " of `" + names + "`";  // composites: their parts' signal paths
    }
    for (const std::string& w : mine) detail += "; warns: " + w;
    return {Outcome::Kind::Mapped, detail};
  }
  const std::string reason = detail::json_field(line, "reason");
  if (mine.empty()) return {Outcome::Kind::Silent, reason};
  return {Outcome::Kind::Warned, reason.empty() ? mine.front() : reason};
}

}  // namespace openplx::catalogue
