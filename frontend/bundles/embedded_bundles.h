// The standard bundles (the source tree's bundles/ folder) as this build was made with them, carried in the
// executable: a conversion takes their folders and texts from here instead of listing, opening and reading
// ~100 small files (bundles.cpp decides when). Generated at build time by
// frontend/bundles/embedded/embed_bundles.cpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "frontend/bundles/bundle_index.h"

namespace openplx::frontend::embedded {

struct File {
  std::string_view name;
  std::string_view text;
  // What scan_declarations (bundle_index.h) finds in the text, found at build time: kDeclaredNames from
  // first_name on, and whether they are complete and lazy.
  bool complete, lazy;
  uint32_t first_name, name_count;
};

// A folder: its sub-folders and .openplx files, each in byte order of their names (as the loader sorts).
struct Dir {
  std::string_view name;  // "" for the root
  uint32_t first_dir, dir_count, first_file, file_count;
};

// The generated tables: kDirs[0] is the root; each folder's sub-folders and files are neighbours.
extern const File kFiles[];
extern const std::string_view kDeclaredNames[];
extern const Dir kDirs[];
extern const size_t kDirCount;

inline const Dir& root() {
  return kDirs[0];
}
inline std::span<const Dir> subdirs(const Dir& dir) {
  return {kDirs + dir.first_dir, dir.dir_count};
}
inline std::span<const File> files(const Dir& dir) {
  return {kFiles + dir.first_file, dir.file_count};
}
// As scan_declarations gives them.
FileDeclarations declarations(const File& file);

const Dir* find_subdir(const Dir& dir, std::string_view name);
const File* find_file(const Dir& dir, std::string_view name);

// Whether this build's own bundles have `qualified` ("Visuals.Materials.SurfaceFeatures"): a bundle, a
// folder of one, or a name a file of that folder declares (as far as scan_declarations finds them). Used to
// say that a name a user's bundle release lacks belongs to a newer release.
bool declares(std::string_view qualified);
// The version a bundle folder's config.openplx gives (`version: "0.26.3"`), or "" when it gives none.
std::string_view config_version(const Dir& bundle);

}  // namespace openplx::frontend::embedded
