// `openplx2mjcf --check` simulates: a model that blows up is an error at the joint's line with a non-zero
// exit, collision geometry that overlaps at the start is a warning naming the pair (an error under
// --strict) that --exclude-initial-overlaps turns into an <exclude>, and MuJoCo's own messages never reach
// MUJOCO_LOG.TXT. The models are tests/check/stiff_spring.openplx (a spring far too stiff for the time step
// it is run at) and tests/check/overlapping_arms.urdf (two arms whose cylinders overlap by 2 cm).
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "mjcf_emitter/mujoco_library.h"
#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace {

namespace fs = std::filesystem;

const fs::path kModels = fs::path(OPENPLX_TEST_DATA_DIR) / "check";
const std::string kSpring = (kModels / "stiff_spring.openplx").string();
const std::string kArms = (kModels / "overlapping_arms.urdf").string();

int cli(const std::vector<std::string>& args, std::string* err) {
  std::ostringstream out, errors;
  const int status = openplx::cli::run(args, out, errors);
  *err = errors.str();
  return status;
}

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Runs in `dir` as the working folder, then goes back.
class WorkingFolder {
 public:
  explicit WorkingFolder(const fs::path& dir) : before_(fs::current_path()) { fs::current_path(dir); }
  ~WorkingFolder() { fs::current_path(before_); }

 private:
  fs::path before_;
};

// At --timestep 0.01 the spring (1e8 N/m on 1 kg: h sqrt(k/m) = 100) blows up in the third step.
TEST(CheckSimulation, DivergingModelIsAnErrorAtTheJointsLine) {
  const openplx::testing::ScratchDir scratch;
  std::string err;
  {
    const WorkingFolder here(scratch.path());
    EXPECT_EQ(cli({kSpring, "--timestep", "0.01", "--check", "-o", "out.xml"}, &err),
              openplx::cli::kExitInputError);
  }
  // At `slide is Physics3D.Interactions.Prismatic:`, when, which DOF and joint, the values, a hint.
  EXPECT_NE(err.find(kSpring + ":16:5: error: --check simulated the model"), std::string::npos) << err;
  EXPECT_NE(err.find("at t = 0.02 s"), std::string::npos) << err;
  EXPECT_NE(err.find("DOF 0, the translation of slide joint `slide` in body `box`"), std::string::npos)
      << err;
  EXPECT_NE(err.find("qacc -1e+10"), std::string::npos) << err;
  EXPECT_NE(err.find("hint: "), std::string::npos) << err;
  EXPECT_NE(err.find("[mjcf-unstable]"), std::string::npos) << err;
  // MuJoCo's warning went to our diagnostics, not to a log file in the working folder; nothing was written.
  EXPECT_FALSE(fs::exists(scratch / "MUJOCO_LOG.TXT"));
  EXPECT_FALSE(fs::exists(scratch / "out.xml"));
  EXPECT_TRUE(fs::is_empty(scratch.path()));
  // The handlers were put back as they were (none: this process never set any).
  EXPECT_EQ(mju_user_warning, nullptr);
  EXPECT_EQ(mju_user_error, nullptr);
}

// The same model at a step that resolves the spring (h sqrt(k/m) = 1) runs its second without a word.
TEST(CheckSimulation, StableModelPasses) {
  const openplx::testing::ScratchDir scratch;
  std::string err;
  EXPECT_EQ(cli({kSpring, "--timestep", "0.0001", "--check", "-o", (scratch / "out.xml").string()}, &err),
            openplx::cli::kExitOk)
      << err;
  EXPECT_EQ(err, "");
}

// --check-time bounds the span: one step of 0.01 s ends before the spring blows up at 0.02 s.
TEST(CheckSimulation, CheckTimeSetsTheSpan) {
  const openplx::testing::ScratchDir scratch;
  std::string err;
  EXPECT_EQ(cli({kSpring, "--timestep", "0.01", "--check", "--check-time", "0.01", "-o",
                 (scratch / "out.xml").string()},
                &err),
            openplx::cli::kExitOk)
      << err;
  EXPECT_EQ(cli({kSpring, "--timestep", "0.01", "--check", "--check-time=0.05", "-o", "-"}, &err),
            openplx::cli::kExitInputError);
}

TEST(CheckSimulation, CheckTimeIsValidated) {
  for (const char* bad : {"0", "-1", "nan", "inf", "1e300", "101", "", "1s", "0x"}) {
    SCOPED_TRACE(bad);
    std::string error;
    EXPECT_FALSE(openplx::cli::parse_options({"m.openplx", "--check", "--check-time", bad}, error));
    EXPECT_NE(error.find("--check-time takes a positive number of seconds up to 100"), std::string::npos)
        << error;
  }
  std::string error;
  const auto options = openplx::cli::parse_options({"m.openplx", "--check", "--check-time", "2.5"}, error);
  ASSERT_TRUE(options) << error;
  EXPECT_DOUBLE_EQ(options->check_time, 2.5);
  EXPECT_DOUBLE_EQ(openplx::cli::parse_options({"m.openplx"}, error)->check_time, 1.0);
  EXPECT_NE(openplx::cli::usage().find("--check-time T"), std::string::npos);
  EXPECT_NE(openplx::cli::usage().find("--exclude-initial-overlaps"), std::string::npos);
}

TEST(CheckInitialOverlap, PairIsReportedByNameAndDepth) {
  const openplx::testing::ScratchDir scratch;
  const std::string out = (scratch / "arms.xml").string();
  std::string err;
  EXPECT_EQ(cli({kArms, "--check", "-o", out}, &err), openplx::cli::kExitOk) << err;
  // At arm_left's <link>, both URDF names, the depth and what to do.
  EXPECT_NE(err.find(kArms + ":15:3: warning: `arm_left` and `arm_right` overlap by 2 cm at the start"),
            std::string::npos)
      << err;
  EXPECT_NE(err.find("--exclude-initial-overlaps"), std::string::npos) << err;
  EXPECT_NE(err.find("[mjcf-initial-overlap]"), std::string::npos) << err;
  EXPECT_EQ(err.find("base_link"), std::string::npos) << err;  // the base is clear of both arms
  EXPECT_EQ(read(out).find("<exclude"), std::string::npos);
  // Under --strict it is an error.
  EXPECT_EQ(cli({kArms, "--check", "--strict", "-o", out}, &err), openplx::cli::kExitInputError);
  EXPECT_NE(err.find("error: `arm_left` and `arm_right` overlap"), std::string::npos) << err;
}

TEST(CheckInitialOverlap, ExcludedOnRequestDeterministically) {
  const openplx::testing::ScratchDir scratch;
  const std::string first = (scratch / "first.xml").string(), second = (scratch / "second.xml").string();
  std::string err;
  ASSERT_EQ(cli({kArms, "--exclude-initial-overlaps", "--check", "--strict", "-o", first}, &err),
            openplx::cli::kExitOk)
      << err;
  EXPECT_NE(
      read(first).find("<contact>\n    <exclude body1=\"arm_left\" body2=\"arm_right\"/>\n  </contact>"),
      std::string::npos)
      << read(first);
  // A note says what was done; --check then finds nothing overlapping.
  EXPECT_NE(err.find(kArms + ":15:3: note: contacts between `arm_left` and `arm_right` are excluded"),
            std::string::npos)
      << err;
  EXPECT_EQ(err.find("[mjcf-initial-overlap]"), std::string::npos) << err;
  ASSERT_EQ(cli({kArms, "--exclude-initial-overlaps", "-o", second}, &err), openplx::cli::kExitOk) << err;
  EXPECT_EQ(read(first), read(second));
  // A model with nothing overlapping is left as it is.
  const std::string plain = (scratch / "plain.xml").string(), excluded = (scratch / "excluded.xml").string();
  ASSERT_EQ(cli({kSpring, "-o", plain}, &err), openplx::cli::kExitOk) << err;
  ASSERT_EQ(cli({kSpring, "--exclude-initial-overlaps", "-o", excluded}, &err), openplx::cli::kExitOk) << err;
  EXPECT_EQ(read(plain), read(excluded));
}

// MuJoCoMessages: warnings kept, an error returned from call() instead of ending the process, the handlers
// the process had before put back.
TEST(MuJoCoMessages, KeepWarningsAndReturnErrors) {
  std::string error;
  const openplx::mjcf::MuJoCoLibrary* mj = openplx::mjcf::mujoco_library(error);
  ASSERT_NE(mj, nullptr) << error;
  static int theirs = 0;
  mju_user_warning = [](const char*) { ++theirs; };
  {
    openplx::mjcf::MuJoCoMessages messages(*mj);
    mju_warning("first");
    {
      openplx::mjcf::MuJoCoMessages inner(*mj);
      mju_warning("inner");
      EXPECT_EQ(inner.warnings, std::vector<std::string>{"inner"});
    }
    mju_warning("second");
    EXPECT_EQ(messages.warnings, (std::vector<std::string>{"first", "second"}));
    EXPECT_FALSE(messages.call(
        nullptr, [] { mju_error("no room"); }, error));
    EXPECT_EQ(error, "no room");
    EXPECT_TRUE(messages.call(
        nullptr, [] {}, error));
  }
  EXPECT_EQ(theirs, 0);
  mju_warning("theirs again");
  EXPECT_EQ(theirs, 1);
  mju_user_warning = nullptr;
  EXPECT_EQ(mju_user_error, nullptr);
}

}  // namespace
