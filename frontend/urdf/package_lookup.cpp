#include "frontend/urdf/package_lookup.h"

#include <algorithm>
#include <cstdlib>
#include <sstream>
#include <vector>

namespace openplx::frontend {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> path_list(const char* variable) {
  std::vector<fs::path> entries;
  const char* value = std::getenv(variable);
  if (!value) return entries;
  std::istringstream in(value);
  for (std::string entry; std::getline(in, entry, ':');) {
    if (!entry.empty()) entries.emplace_back(entry);
  }
  return entries;
}

bool is_dir(const fs::path& p) {
  std::error_code ec;
  return fs::is_directory(p, ec);
}

// A folder named `package` at most `depth` levels below `root` (first in name order, so the result does
// not depend on the file system's listing order); hidden folders are skipped, as rospack does.
std::optional<fs::path> below(const fs::path& root, const std::string& package, int depth) {
  if (is_dir(root / package)) return root / package;
  if (depth == 0) return std::nullopt;
  std::vector<fs::path> children;
  std::error_code ec;
  for (fs::directory_iterator it(root, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (!name.empty() && name[0] != '.' && is_dir(it->path())) children.push_back(it->path());
  }
  std::sort(children.begin(), children.end());
  for (const fs::path& child : children) {
    if (std::optional<fs::path> found = below(child, package, depth - 1)) return found;
  }
  return std::nullopt;
}

}  // namespace

std::optional<fs::path> find_package(const std::string& package, const fs::path& urdf_dir) {
  for (const fs::path& entry : path_list("ROS_PACKAGE_PATH")) {
    if (entry.filename() == package && is_dir(entry)) return entry;
    if (std::optional<fs::path> found = below(entry, package, 3)) return found;
  }
  for (const fs::path& prefix : path_list("AMENT_PREFIX_PATH")) {
    if (is_dir(prefix / "share" / package)) return prefix / "share" / package;
  }
  for (fs::path dir = urdf_dir; !dir.empty(); dir = dir.parent_path()) {
    if (dir.filename() == package) return dir;
    if (is_dir(dir / package)) return dir / package;
    if (dir == dir.parent_path()) break;
  }
  return std::nullopt;
}

std::optional<fs::path> find_beside_urdf(const std::string& inside, const fs::path& urdf_dir) {
  if (inside.empty()) return std::nullopt;
  for (fs::path dir = urdf_dir; !dir.empty(); dir = dir.parent_path()) {
    std::error_code ec;
    if (fs::is_regular_file(dir / inside, ec)) return dir;
    if (dir == dir.parent_path()) break;
  }
  return std::nullopt;
}

std::string package_search_text(const std::string& package, const std::string& inside,
                                const fs::path& urdf_dir) {
  auto listed = [](const char* variable, const std::string& suffix) {
    const std::vector<fs::path> entries = path_list(variable);
    std::string text = std::string(variable);
    if (entries.empty()) return text + " (not set)";
    text += " (";
    for (size_t k = 0; k < entries.size(); ++k) {
      const fs::path entry = suffix.empty() ? entries[k] : entries[k] / suffix;
      text += (k ? ", " : "") + entry.lexically_normal().generic_string();
    }
    return text + ")";
  };
  return "looked in " + listed("ROS_PACKAGE_PATH", "") + ", " + listed("AMENT_PREFIX_PATH", "share") +
         ", and " + urdf_dir.generic_string() + " and the folders above it (for a folder named " + package +
         (inside.empty() ? std::string() : " or holding " + inside) + ")";
}

std::string package_setting_text(const std::string& package) {
  return "set ROS_PACKAGE_PATH (ROS 1) or AMENT_PREFIX_PATH (ROS 2) so that `" + package +
         "` is found, or import this URDF from an OpenPLX file that declares a Urdf.PackagePath with name "
         "\"" +
         package + "\" and the package's folder as path";
}

}  // namespace openplx::frontend
