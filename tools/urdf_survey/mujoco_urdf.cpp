#include "tools/urdf_survey/mujoco_urdf.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <vector>

namespace openplx::urdf_survey {

namespace fs = std::filesystem;

namespace {

fs::path holding(const fs::path& dir, const std::string& package, int depth) {
  std::error_code ec;
  if (dir.filename() == package && fs::is_directory(dir, ec)) return dir;
  if (depth == 0 || !fs::is_directory(dir, ec)) return {};
  if (fs::is_directory(dir / package, ec)) return dir / package;
  std::vector<fs::path> children;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    if (entry.is_directory(ec)) children.push_back(entry.path());
  }
  std::sort(children.begin(), children.end());  // the same answer on every machine
  for (const fs::path& child : children) {
    if (fs::path found = holding(child, package, depth - 1); !found.empty()) return found;
  }
  return {};
}

// `package://P/` names rewritten to folders (MuJoCo's compiler knows no packages).
std::string without_packages(std::string xml, const fs::path& urdf_dir) {
  const std::string scheme = "package://";
  for (size_t at = xml.find(scheme); at != std::string::npos; at = xml.find(scheme, at + 1)) {
    const size_t name = at + scheme.size(), slash = xml.find('/', name);
    if (slash == std::string::npos) break;
    const fs::path folder = find_package(xml.substr(name, slash - name), urdf_dir);
    if (!folder.empty()) xml.replace(at, slash - at, folder.string());
  }
  return xml;
}

}  // namespace

fs::path find_package(const std::string& package, const fs::path& urdf_dir) {
  // ROS's order, which our importer follows too (docs/urdf.md): ROS_PACKAGE_PATH, AMENT_PREFIX_PATH, then
  // a folder named P at or above the URDF's.
  if (const char* path = std::getenv("ROS_PACKAGE_PATH")) {
    std::stringstream entries(path);
    for (std::string entry; std::getline(entries, entry, ':');) {
      if (entry.empty()) continue;
      if (fs::path found = holding(fs::path(entry), package, 3); !found.empty()) return found;
    }
  }
  if (const char* path = std::getenv("AMENT_PREFIX_PATH")) {
    std::stringstream entries(path);
    for (std::string entry; std::getline(entries, entry, ':');) {
      std::error_code ec;
      if (!entry.empty() && fs::is_directory(fs::path(entry) / "share" / package, ec))
        return fs::path(entry) / "share" / package;
    }
  }
  for (fs::path d = urdf_dir; d.has_relative_path(); d = d.parent_path()) {
    if (d.filename() == package) return d;
  }
  return {};
}

mjModel* load_with_mujoco(const fs::path& urdf, const fs::path& work_dir, std::string& error) {
  std::ifstream in(urdf, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  std::string xml = without_packages(text.str(), urdf.parent_path());
  const size_t robot = xml.find("<robot");
  const size_t open_end = robot == std::string::npos ? robot : xml.find('>', robot);
  if (open_end == std::string::npos) {
    error = "no <robot> element";
    return nullptr;
  }
  xml.insert(open_end + 1,
             "<mujoco><compiler fusestatic=\"false\" strippath=\"false\" discardvisual=\"true\" meshdir=\"" +
                 urdf.parent_path().string() + "\"/></mujoco>");
  const fs::path copy = work_dir / (urdf.stem().string() + ".mujoco.urdf");
  std::ofstream(copy, std::ios::binary) << xml;
  char message[1000] = "";
  mjModel* m = mj_loadXML(copy.c_str(), nullptr, message, sizeof(message));
  if (!m) error = message;
  return m;
}

}  // namespace openplx::urdf_survey
