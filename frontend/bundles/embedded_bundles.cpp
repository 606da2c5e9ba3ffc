#include "frontend/bundles/embedded_bundles.h"

#include <algorithm>

namespace openplx::frontend::embedded {
namespace {

// Binary search by name (the tables are sorted by it).
template <typename T>
const T* find(std::span<const T> entries, std::string_view name) {
  auto it = std::lower_bound(entries.begin(), entries.end(), name,
                             [](const T& entry, std::string_view n) { return entry.name < n; });
  return it != entries.end() && it->name == name ? &*it : nullptr;
}

}  // namespace

FileDeclarations declarations(const File& file) {
  FileDeclarations result;
  result.complete = file.complete;
  result.lazy = file.lazy;
  result.names.assign(kDeclaredNames + file.first_name, kDeclaredNames + file.first_name + file.name_count);
  return result;
}

const Dir* find_subdir(const Dir& dir, std::string_view name) {
  return find(subdirs(dir), name);
}

const File* find_file(const Dir& dir, std::string_view name) {
  return find(files(dir), name);
}

bool declares(std::string_view qualified) {
  const Dir* dir = &root();
  while (!qualified.empty()) {
    const size_t dot = qualified.find('.');
    const std::string_view part = qualified.substr(0, dot);
    qualified.remove_prefix(dot == std::string_view::npos ? qualified.size() : dot + 1);
    if (const Dir* sub = find_subdir(*dir, part)) {
      dir = sub;
      continue;
    }
    if (dir == &root()) return false;
    for (const File& file : files(*dir)) {
      const auto* names = kDeclaredNames + file.first_name;
      if (std::find(names, names + file.name_count, part) != names + file.name_count) return true;
    }
    return false;  // what follows a declared name is a member: not looked for
  }
  return dir != &root();
}

std::string_view config_version(const Dir& bundle) {
  const File* config = find_file(bundle, "config.openplx");
  if (!config) return {};
  // The configs are ours: one `version: "..."` line each.
  constexpr std::string_view kKey = "version: \"";
  const size_t at = config->text.find(kKey);
  if (at == std::string_view::npos) return {};
  const size_t begin = at + kKey.size();
  const size_t end = config->text.find('"', begin);
  return end == std::string_view::npos ? std::string_view{} : config->text.substr(begin, end - begin);
}

}  // namespace openplx::frontend::embedded
