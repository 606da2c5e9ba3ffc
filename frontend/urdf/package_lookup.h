// Where a ROS package named in `package://P/...` lives, found as ROS tools find it.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace openplx::frontend {

// The folder of package `package`, looked up in this order:
//   1. ROS_PACKAGE_PATH (ROS 1): each entry is a package, or a folder holding packages up to three levels
//   down;
//   2. AMENT_PREFIX_PATH (ROS 2): `<prefix>/share/<package>` for each prefix;
//   3. a folder named `package` at or above `urdf_dir`, or beside one of those (robots shipped with their
//      meshes, no ROS installed).
// nullopt when none has it.
std::optional<std::filesystem::path> find_package(const std::string& package,
                                                  const std::filesystem::path& urdf_dir);

// A robot shipped without its package's folder name (a renamed checkout): the first of `urdf_dir` and the
// folders above it that holds the file `inside`, or nullopt.
std::optional<std::filesystem::path> find_beside_urdf(const std::string& inside,
                                                      const std::filesystem::path& urdf_dir);

// Where find_package looked for `package`, in words (for the diagnostic of a package found nowhere).
std::string package_search_text(const std::string& package, const std::string& inside,
                                const std::filesystem::path& urdf_dir);
// What the user can set so that `package` is found.
std::string package_setting_text(const std::string& package);

}  // namespace openplx::frontend
