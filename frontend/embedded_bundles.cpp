#include "frontend/embedded_bundles.h"

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

}  // namespace openplx::frontend::embedded
