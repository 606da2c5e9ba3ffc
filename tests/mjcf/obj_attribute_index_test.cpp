// An OBJ face corner naming a texture coordinate or normal far past those given ("1/99999999") crashes MuJoCo
// 2.2.2 (mujoco-compile: SIGSEGV), which uses them unchecked. We never write a file naming such an OBJ: as a
// collision mesh it is a located error, as a visual one it is left out with a warning, and what is written
// loads.
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

std::string tetrahedron_obj(const std::string& first_corner) {
  return "v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nv 0 0 0.1\nvt 0 0\nvn 0 0 1\n"
         "f " +
         first_corner +
         " 3/1 2/1\n"
         "f 1/1 2/1 4/1\nf 1/1 4/1 3/1\nf 2/1 3/1 4/1\n";
}

// A one-link robot whose link holds the OBJ as `kind` (visual or collision) on line 4.
std::string robot(const std::string& kind) {
  return "<robot name=\"r\">\n"
         "  <link name=\"base\"/>\n"
         "  <link name=\"arm\"><inertial><mass value=\"1\"/><inertia ixx=\"1\" iyy=\"1\" izz=\"1\" ixy=\"0\" "
         "ixz=\"0\" iyz=\"0\"/></inertial>\n"
         "    <" +
         kind + "><geometry><mesh filename=\"m.obj\"/></geometry></" + kind +
         ">\n"
         "  </link>\n"
         "  <joint name=\"j\" type=\"continuous\"><parent link=\"base\"/><child link=\"arm\"/>"
         "<axis xyz=\"0 0 1\"/></joint>\n"
         "</robot>\n";
}

TEST(ObjAttributeIndex, FarOutOfRangeIndicesNeverReachMuJoCo) {
  const openplx::testing::ScratchDir dir;
  for (const char* corner : {"1/99999999", "1/0", "1/-7", "1//5", "1/1/9", "1/1/1/1"}) {
    SCOPED_TRACE(corner);
    std::ofstream(dir / "m.obj") << tetrahedron_obj(corner);
    for (const std::string kind : {"collision", "visual"}) {
      SCOPED_TRACE(kind);
      std::ofstream(dir / "r.urdf") << robot(kind);
      const fs::path xml = dir / "r.xml";
      fs::remove(xml);
      std::ostringstream out, err;
      const int status = openplx::cli::run({(dir / "r.urdf").string(), "-o", xml.string()}, out, err);
      const std::string at = (dir / "r.urdf").string() + ":4:";
      const std::string said = "names a texture coordinate or normal not given before it";
      EXPECT_NE(err.str().find(said), std::string::npos) << err.str();
      if (kind == "collision") {
        EXPECT_EQ(status, 1) << err.str();
        EXPECT_NE(err.str().find(at), std::string::npos) << err.str();
        EXPECT_FALSE(fs::exists(xml));
        continue;
      }
      ASSERT_EQ(status, 0) << err.str();
      EXPECT_NE(err.str().find("this visual geometry was left out"), std::string::npos) << err.str();
      char error[1000] = "";
      mjModel* m = mj_loadXML(xml.c_str(), nullptr, error, sizeof(error));
      EXPECT_NE(m, nullptr) << error;
      if (m) mj_deleteModel(m);
    }
  }
}

// Valid attribute indices, positive and counting back, keep the mesh.
TEST(ObjAttributeIndex, ValidIndicesKeepTheMesh) {
  const openplx::testing::ScratchDir dir;
  for (const char* corner : {"1/1", "1/-1", "1//1", "1/1/1", "1//-1", "1"}) {
    SCOPED_TRACE(corner);
    std::ofstream(dir / "m.obj") << tetrahedron_obj(corner);
    std::ofstream(dir / "r.urdf") << robot("collision");
    std::ostringstream out, err;
    EXPECT_EQ(openplx::cli::run({(dir / "r.urdf").string(), "-o", (dir / "r.xml").string()}, out, err), 0)
        << err.str();
    EXPECT_EQ(err.str().find("texture coordinate"), std::string::npos) << err.str();
  }
}

}  // namespace
