#include "frontend/semantics/unknown_name_notes.h"

#include <algorithm>
#include <filesystem>
#include <vector>

#include "frontend/bundles/embedded_bundles.h"

namespace openplx::frontend {
namespace fs = std::filesystem;

namespace {

// "0.26.3", the version of our own bundles (every config of ours gives the same one).
std::string_view our_version(std::string_view bundle) {
  const embedded::Dir* dir = embedded::find_subdir(embedded::root(), bundle);
  return dir ? embedded::config_version(*dir) : std::string_view{};
}

std::string describe(const BundleConfig& release) {
  std::string text = release.name + " " + (release.version.empty() ? "(no version)" : release.version);
  return text + " (" + release.dir + "/config.openplx)";
}

}  // namespace

std::optional<std::string> newer_name_note(std::string_view qualified, const BundleConfig& release) {
  if (release.embedded || !embedded::declares(qualified)) return std::nullopt;
  return "`" + std::string(qualified) + "` is newer than the bundle release found, " + describe(release) +
         ": the converter's own bundles (" + std::string(our_version(release.name)) +
         ") have it; use a newer release, or drop --no-default-bundles";
}

std::optional<std::string> newer_bundle_note(std::string_view name, const std::deque<BundleConfig>& found) {
  if (found.empty() || !embedded::declares(name)) return std::nullopt;
  if (std::any_of(found.begin(), found.end(), [](const BundleConfig& b) { return b.embedded; }))
    return std::nullopt;
  // The release the others came with: the first found whose version is not the AGX bundle's own (1.0.0).
  const BundleConfig* release = &found.front();
  for (const BundleConfig& b : found) {
    if (embedded::find_subdir(embedded::root(), b.name) && b.name != "AGX") {
      release = &b;
      break;
    }
  }
  return "bundle `" + std::string(name) + "` is newer than the bundle release found, " + describe(*release) +
         ": the converter's own bundles (" + std::string(our_version(name)) +
         ") have it; use a newer release, or drop --no-default-bundles";
}

std::optional<std::string> sibling_bundle_note(const std::string& model_file, std::string_view name) {
  std::error_code ec;
  const fs::path folder = fs::absolute(model_file, ec).parent_path();
  if (ec || !fs::is_directory(folder, ec)) return std::nullopt;
  std::vector<fs::path> candidates;
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    if (entry.is_directory(ec) && fs::is_regular_file(entry.path() / "config.openplx", ec))
      candidates.push_back(entry.path());
  }
  std::sort(candidates.begin(), candidates.end());  // directory order is not deterministic
  for (const fs::path& dir : candidates) {
    // Its name as its config gives it (`name: "Test"`); the folder's own name may differ (TestBundle).
    SourceManager sources;
    DiagnosticSink quiet;
    std::optional<BundleConfig> config = read_bundle_config(dir.string(), sources, quiet);
    if (!config || config->name != name) continue;
    // The folder as the user reaches it: beside the model's path as they wrote it.
    const std::string shown = (fs::path(model_file).parent_path() / dir.filename()).generic_string();
    return "the folder `" + dir.filename().string() + "` beside this model holds bundle `" + config->name +
           "` (its config.openplx), which was not passed: add `-B " + shown + "`";
  }
  return std::nullopt;
}

void add_note(Diagnostic& d, const std::optional<std::string>& note) {
  if (note && std::find(d.notes.begin(), d.notes.end(), *note) == d.notes.end()) d.notes.push_back(*note);
}

std::optional<std::string> missing_member_note(const BundleConfig* bundle, std::string_view ns_qualified,
                                               std::string_view name) {
  if (!bundle || ns_qualified.empty()) return std::nullopt;
  return newer_name_note(std::string(ns_qualified) + "." + std::string(name), *bundle);
}

}  // namespace openplx::frontend
