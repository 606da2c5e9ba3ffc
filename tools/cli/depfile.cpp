#include "tools/cli/depfile.h"

#include <algorithm>
#include <filesystem>

namespace openplx::cli {
namespace {

namespace fs = std::filesystem;

std::string absolute_file(const fs::path& path) {
  std::error_code ec;
  const fs::path absolute = fs::absolute(path, ec);
  if (ec || !fs::is_regular_file(absolute, ec)) return "";
  return absolute.lexically_normal().string();
}

// Why Make or Ninja cannot read `path` back from a depfile, or "" when both can.
std::string unexpressible(const std::string& path, bool target) {
  auto named = [](char c) -> std::string {
    switch (c) {
      case '\n':
        return "a newline";
      case '\t':
        return "a tab";
      case '\r':
        return "a carriage return";
      default:
        break;
    }
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      static const char* digits = "0123456789abcdef";
      return std::string("the control character \\x") + digits[(c >> 4) & 0xf] + digits[c & 0xf];
    }
    return std::string("'") + c + "'";
  };
  for (size_t k = 0; k < path.size(); ++k) {
    const char c = path[k];
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      return named(c) + ", which Make and Ninja cannot read";
    if (std::string_view("()=;").find(c) != std::string_view::npos)
      return named(c) + ", which Make reads as syntax";
    if (std::string_view("*?\"'&|<>`^").find(c) != std::string_view::npos)
      return named(c) + ", where Ninja ends the name";
    if (c == '\\' &&
        (k + 1 == path.size() || std::string_view(" #:\\$").find(path[k + 1]) != std::string_view::npos))
      return "a backslash before '" + std::string(k + 1 == path.size() ? "" : path.substr(k + 1, 1)) +
             "' or at the end, which Make and Ninja read as an escape";
    if (c == '%' && target) return "'%', which makes Make read the output as a pattern rule";
  }
  if (!path.empty() && path.front() == '~') return "a leading '~', which Make reads as a home folder";
  return "";
}

// The escapes both read: a space, '#' and ':' behind a backslash, '$' doubled.
std::string escaped(const std::string& path) {
  std::string out;
  for (char c : path) {
    if (c == ' ' || c == '#' || c == ':') out += '\\';
    if (c == '$') out += '$';
    out += c;
  }
  return out;
}

}  // namespace

std::vector<std::string> files_the_mjcf_reads(const mjcf::Element& document, const std::string& output_dir) {
  std::vector<std::string> files;
  std::vector<const mjcf::Element*> stack{&document};
  while (!stack.empty()) {
    const mjcf::Element* e = stack.back();
    stack.pop_back();
    if (const std::string* file = e->get("file")) {
      const fs::path path(*file);
      const std::string found =
          absolute_file(path.is_absolute() || output_dir.empty() ? path : fs::path(output_dir) / path);
      if (!found.empty()) files.push_back(found);
    }
    for (const auto& child : e->children()) stack.push_back(child.get());
  }
  return files;
}

std::vector<std::string> source_files(const frontend::SourceManager& sources) {
  std::vector<std::string> files;
  for (size_t id = 0; id < sources.size(); ++id) {
    const std::string& path = sources.file(static_cast<frontend::FileId>(id)).path();
    if (path.empty() || path.front() == '<') continue;  // "<builtin>", "<import robot.urdf>"
    const std::string found = absolute_file(path);
    if (!found.empty()) files.push_back(found);
  }
  return files;
}

bool depfile_text(const std::string& target, std::vector<std::string> inputs, std::string& text,
                  std::string& error) {
  std::sort(inputs.begin(), inputs.end());
  inputs.erase(std::unique(inputs.begin(), inputs.end()), inputs.end());
  for (size_t k = 0; k <= inputs.size(); ++k) {
    const std::string& name = k == 0 ? target : inputs[k - 1];
    const std::string why = unexpressible(name, k == 0);
    if (!why.empty()) {
      error = "cannot write a depfile naming '" + name + "': its name has " + why;
      return false;
    }
  }
  text = escaped(target) + ":";
  for (const std::string& input : inputs) text += " \\\n  " + escaped(input);
  text += "\n";
  return true;
}

}  // namespace openplx::cli
