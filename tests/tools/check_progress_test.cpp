// A long --check shows how far its simulation is when stderr is a terminal ("\r--check: simulated 1.5 of
// 5 s", rewritten in place, a few times a second) and says nothing of it in a pipe or a file. The executable
// runs under script(1), which gives it a pseudo-terminal, and with stderr to a file.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/support/scratch_dir.h"

namespace {

namespace fs = std::filesystem;

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Most of a second of checking: 300 000 steps of 10 us.
std::string long_check() {
  return std::string(OPENPLX2MJCF_EXECUTABLE) + " " + OPENPLX_SAMPLES_DIR +
         "/pendulum.openplx --check --check-time 3 --timestep 1e-5";
}

TEST(CheckProgress, ShownOnATerminal) {
  const openplx::testing::ScratchDir dir;
  const fs::path typescript = dir / "terminal.txt";
  // script -e: its status is the command's; the terminal's output goes to stdout.
  const std::string command = "script -qec '" + long_check() + "' /dev/null > '" + typescript.string() + "'";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  const std::string shown = read(typescript);
  EXPECT_NE(shown.find("\r--check: simulated "), std::string::npos) << shown;
  EXPECT_NE(shown.find(" of 3 s"), std::string::npos) << shown;
  // A few times a second, not every step; and the line is blanked at the end.
  size_t lines = 0;
  for (size_t at = shown.find("--check: simulated"); at != std::string::npos;
       at = shown.find("--check: simulated", at + 1))
    ++lines;
  EXPECT_LE(lines, 200u);
  EXPECT_EQ(shown.back(), '\r') << shown;
}

TEST(CheckProgress, QuietInAFile) {
  const openplx::testing::ScratchDir dir;
  const fs::path errors = dir / "errors.txt";
  const std::string command = long_check() + " 2> '" + errors.string() + "' | cat";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  EXPECT_EQ(read(errors), "");
}

}  // namespace
