// MuJoCo 2.2.2 refuses a moving body whose mass or principal moments, summed with those of the jointless
// bodies welded to it, fall below mjMINVAL. The converter applies the same rule to what it writes: for each
// case, MuJoCo's own verdict on the inertia as written decides whether we warn, and our output always loads.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace {

namespace fs = std::filesystem;
using openplx::testing::ScratchDir;

std::string inertia(const std::string& izz) {
  return "<inertial><mass value=\"1\"/><inertia ixx=\"1\" iyy=\"1\" izz=\"" + izz +
         "\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial>";
}

// A rod on a hinge about x, its moment about its own axis (z) `izz`; with `welded`, a link fixed below it.
std::string robot(const std::string& izz, bool welded) {
  std::string text =
      "<robot name=\"rod\">\n  <link name=\"base\"/>\n  <link name=\"rod\">" + inertia(izz) +
      "</link>\n"
      "  <joint name=\"hinge\" type=\"revolute\"><parent link=\"base\"/><child link=\"rod\"/>"
      "<axis xyz=\"1 0 0\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>\n";
  if (welded)
    text += "  <link name=\"tip\">" + inertia("1") +
            "</link>\n  <joint name=\"fixed\" type=\"fixed\"><parent link=\"rod\"/><child link=\"tip\"/>"
            "<origin xyz=\"0 0 1\"/></joint>\n";
  return text + "</robot>\n";
}

// MuJoCo's verdict on the same numbers written as MJCF by hand.
bool mujoco_accepts(const fs::path& dir, const std::string& izz, bool welded) {
  const std::string inertial = "<inertial pos=\"0 0 0\" mass=\"1\" diaginertia=\"1 1 " + izz + "\"/>";
  std::ofstream(dir / "raw.xml") << "<mujoco><worldbody><body><joint type=\"hinge\" axis=\"1 0 0\"/>"
                                 << inertial
                                 << (welded ? "<body pos=\"0 0 1\"><inertial pos=\"0 0 0\" mass=\"1\" "
                                              "diaginertia=\"1 1 1\"/></body>"
                                            : "")
                                 << "</body></worldbody></mujoco>";
  char error[1000] = "";
  mjModel* m = mj_loadXML((dir / "raw.xml").c_str(), nullptr, error, sizeof(error));
  if (m) mj_deleteModel(m);
  return m != nullptr;
}

TEST(MovingBodyInertia, OurRuleIsMuJoCosAndTheOutputAlwaysLoads) {
  const ScratchDir dir;
  for (const char* izz : {"0", "1.7e-23", "1e-16", "9.99e-16", "1e-15", "5e-15", "1e-14", "1e-3"}) {
    for (bool welded : {false, true}) {
      SCOPED_TRACE(std::string(izz) + (welded ? " welded" : ""));
      std::ofstream(dir / "rod.urdf") << robot(izz, welded);
      std::ostringstream out, err;
      const fs::path xml = dir / "rod.xml";
      ASSERT_EQ(openplx::cli::run({(dir / "rod.urdf").string(), "-o", xml.string()}, out, err), 0)
          << err.str();
      const bool warned = err.str().find("below 1e-15, the smallest MuJoCo accepts") != std::string::npos;
      EXPECT_EQ(warned, !mujoco_accepts(dir.path(), izz, welded)) << err.str();
      char error[1000] = "";
      mjModel* m = mj_loadXML(xml.c_str(), nullptr, error, sizeof(error));
      EXPECT_NE(m, nullptr) << error;
      if (!m) continue;
      const int rod = mj_name2id(m, mjOBJ_BODY, "rod");
      ASSERT_GE(rod, 0);
      EXPECT_GE(m->body_inertia[3 * rod + 2], warned ? mjMINVAL : 0.0);
      mj_deleteModel(m);
    }
  }
}

}  // namespace
