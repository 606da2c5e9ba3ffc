// Test support: the models of the owned-rows acceptance tests (tests/runtime/owned_rows_test.cpp) besides the
// N-link arm (tests/support/arm_chain.h) — the gear pair and the car on (elastic) wheels — and converting one
// the way openplx2mjcf does, so the same models can be run with the runtime (owned_rows_test) and as the MJCF
// alone in plain MuJoCo (bare_mjcf_rows_test).
#pragma once

#include <filesystem>
#include <string>

#include "tests/support/arm_chain.h"
#include "tests/support/car_model.h"
#include "tests/support/scratch_dir.h"

namespace openplx::testing {

// ---------------------------------------------------------------------------------------------------------
// Converting

// Writes `text` as dir/model.openplx; returns its path.
std::filesystem::path write_model(const ScratchDir& dir, const std::string& text);

// The converter's MJCF (and the manifest beside it) for `source` at time step h, as openplx2mjcf writes them
// (a test failure when it does not convert).
std::filesystem::path emit(const ScratchDir& dir, const std::filesystem::path& source, double h,
                           const std::string& model = "");

// The signal manifest beside the MJCF file `xml`.
std::filesystem::path manifest_of(const std::filesystem::path& xml);

// ---------------------------------------------------------------------------------------------------------
// A gear

// A 1-D drivetrain: a velocity motor `drive` (target 0, its AngularVelocity1DInput `speed`) on an input shaft
// `in` (1 kg m^2), a DriveTrain.Gear `gear` of `ratio` to an output shaft `out` (1 kg m^2). The convention
// (tests/runtime/rigid_coupling_test.cpp, drivetrain_parts_test.cpp): the output turns at input / ratio, the
// same way.
std::string gear_pair(double ratio);

// ---------------------------------------------------------------------------------------------------------
// A car: tests/support/car_model.h

}  // namespace openplx::testing
