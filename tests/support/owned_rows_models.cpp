#include "tests/support/owned_rows_models.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <vector>

#include "tools/cli/cli.h"

namespace openplx::testing {

std::filesystem::path write_model(const ScratchDir& dir, const std::string& text) {
  const std::filesystem::path file = dir / "model.openplx";
  std::ofstream(file) << text;
  return file;
}

std::filesystem::path emit(const ScratchDir& dir, const std::filesystem::path& source, double h,
                           const std::string& model) {
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

std::filesystem::path manifest_of(const std::filesystem::path& xml) {
  return openplx::cli::manifest_path(xml.string());
}

std::string gear_pair(double ratio) {
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

}  // namespace openplx::testing
