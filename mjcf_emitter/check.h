// `--check`: loads emitted MJCF with MuJoCo's own mj_loadXML, runs mj_forward, and compares every body's
// world pose with SNAP's and every equality constraint's residual with zero. mujoco-compile exits 0 on
// failure, so loading through the library is the only trustworthy test.
#pragma once

#include <string>
#include <vector>

#include "snap/snap.h"

namespace openplx::mjcf {

struct CheckResult {
  bool loaded = false;
  std::string load_error;             // MuJoCo's message when loading failed
  std::vector<std::string> problems;  // pose or constraint mismatches, one line each
  double max_position_error = 0.0;
  double max_rotation_error = 0.0;
  double max_equality_residual = 0.0;
};

// `xml_path` must be a file (mesh paths in it resolve against its folder). Body names are `prefix` + path.
CheckResult check_mjcf(const std::string& xml_path, const snap::ResolvedSystem& view,
                       const snap::SnapResult& snap, const std::string& prefix, const std::string& root_name,
                       double tolerance = 1e-9);

}  // namespace openplx::mjcf
