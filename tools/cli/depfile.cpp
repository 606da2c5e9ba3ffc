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

// Make's escapes: a space or '#' behind a backslash, '$' doubled.
std::string escaped(const std::string& path) {
  std::string out;
  for (char c : path) {
    if (c == ' ' || c == '#') out += '\\';
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

std::string depfile_text(const std::string& target, std::vector<std::string> inputs) {
  std::sort(inputs.begin(), inputs.end());
  inputs.erase(std::unique(inputs.begin(), inputs.end()), inputs.end());
  std::string text = escaped(target) + ":";
  for (const std::string& input : inputs) text += " \\\n  " + escaped(input);
  return text + "\n";
}

}  // namespace openplx::cli
