// The JavaScript reference client of the signal manifest (signal_client.mjs) drives cart_pole and
// vehicle_circle by signal names in current MuJoCo (npm's mujoco-js), from the MJCF and manifest alone, and
// checks what they do (drive_samples.mjs: the cart moves the way the push says, the car drives forward and
// turns with the steering's sign on about its Ackermann circle, the engine's throttle is said to need the
// runtime). ./test.sh installs Node and the module (tools/install-deps.sh --tests); without them this fails.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace {

namespace fs = std::filesystem;

TEST(JsSignalClient, DrivesTheSamplesByTheirManifestsAlone) {
  const fs::path here = fs::path(OPENPLX_TEST_DATA_DIR) / "current_mujoco";
  ASSERT_TRUE(fs::exists(here / "node_modules" / "mujoco-js" / "package.json"))
      << "mujoco-js is not installed in " << here << ": run tools/install-deps.sh --tests";
  const openplx::testing::ScratchDir dir;
  for (const char* sample : {"cart_pole", "vehicle_circle", "drivetrain_machine"}) {
    std::ostringstream text, errors;
    const std::vector<std::string> args{
        (fs::path(OPENPLX_SAMPLES_DIR) / (std::string(sample) + ".openplx")).string(), "-o",
        (dir / (std::string(sample) + ".xml")).string()};
    ASSERT_EQ(openplx::cli::run(args, text, errors), 0) << errors.str();
  }
  const std::string command =
      "node '" + (here / "drive_samples.mjs").string() + "' '" + dir.path().string() + "' 2>&1";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  ASSERT_TRUE(pipe) << "cannot run node";
  std::string output;
  char buffer[4096];
  while (size_t n = fread(buffer, 1, sizeof(buffer), pipe.get())) output.append(buffer, n);
  const int status = pclose(pipe.release());
  std::cout << output;
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << output;
  EXPECT_NE(output.find("all checks passed"), std::string::npos) << output;
}

}  // namespace
