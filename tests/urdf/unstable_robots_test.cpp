// Robots with the traits of the Kinova Jaco/Mico and Valkyrie files that MuJoCo found unstable at rest
// (tests/urdf/robots/unstable/README.md says which trait each holds). Each must now pass --check's simulation
// under gravity for 2 s, saying what was done about the trait.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>

#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace {

namespace fs = std::filesystem;

struct Case {
  const char* file;
  const char* said;  // what the conversion says about the trait ("" for nothing)
};

class UnstableRobots : public ::testing::TestWithParam<Case> {};

TEST_P(UnstableRobots, SimulateAtRestUnderGravity) {
  const openplx::testing::ScratchDir dir;
  const fs::path urdf = fs::path(OPENPLX_TEST_DATA_DIR) / "urdf" / "robots" / "unstable" / GetParam().file;
  std::ostringstream out, err;
  const int status = openplx::cli::run(
      {urdf.string(), "-o", (dir / "robot.xml").string(), "--check", "--check-time", "2"}, out, err);
  EXPECT_EQ(status, 0) << err.str();
  EXPECT_EQ(err.str().find("error:"), std::string::npos) << err.str();
  EXPECT_NE(err.str().find(GetParam().said), std::string::npos) << err.str();
}

// A Jaco's joint_2 and joint_3 exclude zero: started at 0, MuJoCo's limit rows throw them into range and
// fling the 10 g fingers (1e5 rad/s). They start at the middle of their ranges, as joint_state_publisher
// shows them. A hand whose many small shapes start with 116 contacts needs more than MuJoCo's default 100.
INSTANTIATE_TEST_SUITE_P(Traits, UnstableRobots,
                         ::testing::Values(Case{"jaco_zero_outside_limits.urdf",
                                                "zero lies outside its limits [0.820305"},
                                           Case{"jaco_folded_overlaps.urdf", "it starts at their middle"},
                                           Case{"jaco_one_finger_whip.urdf", "it starts at their middle"},
                                           Case{"hand_contact_buffer.urdf", ""}),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           std::string name = info.param.file;
                           return name.substr(0, name.find('.'));
                         });

}  // namespace
