// Large URDF robots convert correctly (their time is bench/scaling.sh's to show, not a test's): every link a
// body, a chain deeper than MuJoCo reads a located error, a URDF written on one line the same robot, a loop
// closed at the end of a long chain found.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace {

namespace fs = std::filesystem;

// N links; each hangs from the previous one, or (every `branch` links, when given) from link0.
std::string robot(int n, int branch, const std::string& newline = "\n") {
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>" << newline << "<robot name=\"big\">" << newline;
  for (int i = 0; i < n; ++i) {
    out << "  <link name=\"link" << i << "\">" << newline
        << "    <inertial><mass value=\"1\"/><inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" "
           "iyz=\"0\" "
           "izz=\"0.01\"/></inertial>"
        << newline << "    <collision><geometry><box size=\"0.1 0.1 0.1\"/></geometry></collision>" << newline
        << "  </link>" << newline;
    if (i == 0) continue;
    const int parent = branch > 0 && (i - 1) % branch == 0 ? 0 : i - 1;
    out << "  <joint name=\"joint" << i << "\" type=\"revolute\">" << newline << "    <parent link=\"link"
        << parent << "\"/><child link=\"link" << i << "\"/>" << newline << "    <origin xyz=\""
        << (branch > 0 && parent == 0 ? 0.2 * ((i - 1) / branch) : 0.0) << " 0 0.1\"/><axis xyz=\"0 1 0\"/>"
        << newline << "    <limit lower=\"-1\" upper=\"1\" effort=\"10\" velocity=\"1\"/>" << newline
        << "  </joint>" << newline;
  }
  out << "</robot>" << newline;
  return out.str();
}

size_t occurrences(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

class UrdfScaling : public ::testing::Test {
 protected:
  std::string write(const std::string& name, const std::string& text) {
    const fs::path path = scratch_.path() / name;
    std::ofstream(path, std::ios::binary) << text;
    return path.string();
  }
  // Converts `path` to MJCF on stdout; returns the exit status.
  int convert(const std::string& path, std::string& mjcf, std::string& err) {
    std::ostringstream out, errors;
    const int status = openplx::cli::run({path, "-o", "-"}, out, errors);
    mjcf = out.str();
    err = errors.str();
    return status;
  }
  openplx::testing::ScratchDir scratch_;
};

TEST_F(UrdfScaling, ForestOf300LinksHasEveryLinkAsABodyWithItsJoint) {
  std::string mjcf, err;
  ASSERT_EQ(convert(write("forest.urdf", robot(300, 30)), mjcf, err), 0) << err;
  EXPECT_EQ(occurrences(mjcf, "<body "), 300u);
  EXPECT_EQ(occurrences(mjcf, "<joint "), 299u);
  EXPECT_NE(mjcf.find("name=\"link299\""), std::string::npos);
  EXPECT_NE(mjcf.find("name=\"joint299\""), std::string::npos);
  EXPECT_EQ(occurrences(mjcf, "range=\"-1 1\""), 299u);
}

TEST_F(UrdfScaling, ChainDeeperThanMujocoReadsIsALocatedError) {
  const std::string text = robot(200, 0);
  const std::string path = write("chain.urdf", text);
  std::string mjcf, err;
  EXPECT_EQ(convert(path, mjcf, err), openplx::cli::kExitInputError);
  // At link90's line of the URDF.
  const size_t at = text.find("<link name=\"link90\">");
  const size_t line = 1 + static_cast<size_t>(std::count(text.begin(), text.begin() + at, '\n'));
  EXPECT_NE(err.find(path + ":" + std::to_string(line) + ":3: error: the body chain reaches link90"),
            std::string::npos)
      << err.substr(0, 2000);
  EXPECT_NE(err.find("[mjcf-too-deep]"), std::string::npos);
  // Nothing after it about the joints and ranges of the bodies left out: one error per body too deep.
  EXPECT_EQ(occurrences(err, "warning:"), 0u) << err.substr(0, 2000);
  EXPECT_EQ(occurrences(err, "error:"), occurrences(err, "[mjcf-too-deep]")) << err.substr(0, 2000);
}

TEST_F(UrdfScaling, UrdfOnOneLineIsTheSameRobot) {
  // Same file name (the model's name comes from it), one folder each.
  fs::create_directories(scratch_.path() / "lines");
  fs::create_directories(scratch_.path() / "one_line");
  std::string lines, one_line, err;
  ASSERT_EQ(convert(write("lines/robot.urdf", robot(120, 40)), lines, err), 0) << err;
  ASSERT_EQ(convert(write("one_line/robot.urdf", robot(120, 40, "")), one_line, err), 0) << err;
  EXPECT_EQ(occurrences(one_line, "<body "), 120u);
  EXPECT_TRUE(one_line == lines);  // not EXPECT_EQ: a difference would print both files whole
}

TEST_F(UrdfScaling, ErrorsInAOneLineUrdfPointAtTheirOwnElement) {
  // The 51st <limit> of the line is the bad one: the column is its own, not the first <limit>'s.
  std::string text = robot(60, 0, "");
  const std::string limit = "<limit lower=\"-1\"";
  size_t at = 0;
  for (int k = 0; k < 51; ++k) at = text.find(limit, at + 1);
  text.replace(at, limit.size(), "<limit lower=\"x\"");
  std::string mjcf, err;
  EXPECT_EQ(convert(write("bad.urdf", text), mjcf, err), openplx::cli::kExitInputError);
  EXPECT_NE(err.find(":1:" + std::to_string(at + 1) + ": error: <limit> lower=\"x\" is not a number"),
            std::string::npos)
      << err.substr(0, 2000);
}

TEST_F(UrdfScaling, LoopClosedAtTheEndOfALongChainIsFound) {
  std::string text = robot(500, 0);
  text.replace(text.rfind("</robot>"), 8,
               "  <joint name=\"closing\" type=\"fixed\">\n    <parent link=\"link499\"/><child "
               "link=\"link0\"/>\n  </joint>\n</robot>");
  std::string mjcf, err;
  EXPECT_EQ(convert(write("loop.urdf", text), mjcf, err), openplx::cli::kExitInputError);
  EXPECT_NE(err.find("error: joint `closing` closes a loop (joint1 → "), std::string::npos)
      << err.substr(0, 2000);
  EXPECT_NE(err.find("joint499 → closing → joint1); a URDF must be a tree"), std::string::npos)
      << err.substr(0, 2000);
}

}  // namespace
