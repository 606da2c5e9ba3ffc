// Test support: the models of the owned-rows acceptance tests (tests/runtime/owned_rows_test.cpp) besides the
// N-link arm (tests/support/arm_chain.h) — the gear pair and the car on (elastic) wheels — and converting one
// the way openplx2mjcf does, so the same models can be run with the runtime (owned_rows_test) and as the MJCF
// alone in plain MuJoCo (bare_mjcf_rows_test).
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/arm_chain.h"
#include "tests/support/car_model.h"
#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace openplx::testing {

// ---------------------------------------------------------------------------------------------------------
// Converting

inline std::filesystem::path write_model(const ScratchDir& dir, const std::string& text) {
  const std::filesystem::path file = dir / "model.openplx";
  std::ofstream(file) << text;
  return file;
}

// The converter's MJCF (and the manifest beside it) for `source` at time step h, as openplx2mjcf writes them.
inline std::filesystem::path emit(const ScratchDir& dir, const std::filesystem::path& source, double h,
                                  const std::string& model = "") {
  const std::filesystem::path xml = dir / "model.xml";
  std::vector<std::string> args{source.string(), "-o", xml.string(), "--timestep", arm_number(h)};
  if (!model.empty()) {
    args.push_back("--model");
    args.push_back(model);
  }
  std::ostringstream out, err;
  EXPECT_EQ(openplx::cli::run(args, out, err), openplx::cli::kExitOk) << err.str();
  return xml;
}

inline std::filesystem::path manifest_of(const std::filesystem::path& xml) {
  return openplx::cli::manifest_path(xml.string());
}

// ---------------------------------------------------------------------------------------------------------
// A gear

// A 1-D drivetrain: a velocity motor `drive` (target 0, its AngularVelocity1DInput `speed`) on an input shaft
// `in` (1 kg m^2), a DriveTrain.Gear `gear` of `ratio` to an output shaft `out` (1 kg m^2). The convention
// (tests/runtime/rigid_coupling_test.cpp, drivetrain_parts_test.cpp): the output turns at input / ratio, the
// same way.
inline std::string gear_pair(double ratio) {
  return "Pair is Physics3D.System:\n"
         "    in is DriveTrain.Shaft:\n"
         "        inertia.inertia: 1\n"
         "    out is DriveTrain.Shaft:\n"
         "        inertia.inertia: 1\n"
         "    drive is Physics1D.Interactions.RotationalVelocityMotor:\n"
         "        connectors: [in.input]\n"
         "        target_speed: 0\n"
         "    gear is DriveTrain.Gear:\n"
         "        connectors: [in.output, out.input]\n"
         "        ratio: " +
         arm_number(ratio) +
         "\n"
         "    speed is Physics.Signals.AngularVelocity1DInput:\n"
         "        source: drive\n";
}

// ---------------------------------------------------------------------------------------------------------
// A car

}  // namespace openplx::testing
