// Bundle discovery (../shared/spec/openplx-language.md §15). A bundle is a folder holding `config.openplx`
// (`config is BundleConfig:` with name, version, dependencies); its sub-folders are namespaces.
//
// Search order: the project's own bundles/ (installed beside the executable, else the source tree), then
// each folder of OPENPLX_BUNDLE_PATH (':'-separated), then each -B folder. A folder is a bundle itself or
// a folder of bundles. When two bundles share a name, the first found wins.
//
// The project's own bundles are part of the converter's build: their folders and texts are compiled in
// (embedded_bundles.h) and read from there, though reported at their path on disk. To use edited ones without
// rebuilding, pass them as a user's: --no-default-bundles -B DIR.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "frontend/diagnostics/diagnostics.h"
#include "frontend/diagnostics/source.h"

namespace openplx::frontend {

namespace embedded {
struct Dir;
}

struct BundleDependency {
  std::string name;
  std::string version;  // empty when not pinned
};

struct BundleConfig {
  std::string name;
  std::string version;
  std::vector<BundleDependency> dependencies;
  std::string dir;  // absolute, normalised
  // Its folder in the copy this build carries (embedded_bundles.h), which is read instead of `dir`.
  const embedded::Dir* embedded = nullptr;
};

// A folder searched for bundles.
struct BundleRoot {
  std::string dir;        // absolute, normalised
  bool embedded = false;  // the project's bundles: read from the copy this build carries, shown at `dir`
};

// Reads `dir/config.openplx`. Problems are reported to `sink` at the config file's lines.
std::optional<BundleConfig> read_bundle_config(const std::string& dir, SourceManager& sources,
                                               DiagnosticSink& sink);

// The folders searched for bundles, in order: project bundles (unless `default_bundles` is false),
// OPENPLX_BUNDLE_PATH, then `extra_dirs`. Only the first, the project's, is `embedded`.
std::vector<BundleRoot> bundle_search_path(const std::vector<std::string>& extra_dirs,
                                           bool default_bundles = true);

// Every bundle under the search path (first of each name wins).
std::vector<BundleConfig> discover_bundles(const std::vector<BundleRoot>& search_path, SourceManager& sources,
                                           DiagnosticSink& sink);

// The enclosing bundle folder of `file` (the nearest ancestor folder with config.openplx), if any.
std::optional<std::string> enclosing_bundle_dir(const std::string& file);

// The running executable's folder (empty when /proc/self/exe cannot be read): installed files lie beside it.
std::string executable_dir();

// "Name" or "Name@1.2.3".
BundleDependency parse_dependency(const std::string& text);

}  // namespace openplx::frontend
