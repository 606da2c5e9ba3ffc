// MuJoCo's own URDF compiler given a robot the way tests/urdf/urdf_parity_test.cpp gives it one: every link
// kept as a body (no static fusing), visuals discarded, meshes found where the original finds them.
#pragma once

#include <mujoco/mujoco.h>

#include <filesystem>
#include <string>

namespace openplx::urdf_survey {

// The folder a `package://P/...` name stands for, as ROS (and our importer) finds it: an entry of
// ROS_PACKAGE_PATH that is P or holds P up to three folders down, else AMENT_PREFIX_PATH's share/P, else a
// folder P at or above the URDF's. Empty if none.
std::filesystem::path find_package(const std::string& package, const std::filesystem::path& urdf_dir);

// Loads `urdf` with MuJoCo's compiler through a copy written into `work_dir`. On failure returns null and
// sets `error` to MuJoCo's message.
mjModel* load_with_mujoco(const std::filesystem::path& urdf, const std::filesystem::path& work_dir,
                          std::string& error);

}  // namespace openplx::urdf_survey
