// Simulation::load (and openplx-sim, which calls it) on robots whose collision mesh is made to break the
// reader: each is a LoadError at the URDF's <mesh>, in the caller's process, which goes on; the reader ran in
// a child (mjcf_emitter/mesh_reader_process.h). tests/mjcf/hostile_meshes_test.cpp has the converter's side.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "openplx/runtime/simulation.h"
#include "tests/support/scratch_dir.h"

namespace {

namespace rt = openplx::runtime;
namespace fs = std::filesystem;
using openplx::testing::ScratchDir;

void write(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// A robot whose one link collides with `mesh`, named on line 4, column 26.
std::string robot(const std::string& mesh) {
  return R"(<robot name="r">
  <link name="a">
    <inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><mesh filename=")" +
         mesh + R"("/></geometry></collision>
  </link>
</robot>
)";
}

TEST(HostileMeshLoad, EachIsALocatedLoadError) {
  const ScratchDir dir;
  write(dir / "self.dae", R"(<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <library_visual_scenes><visual_scene id="s"><node id="n"><instance_node url="#n"/></node></visual_scene>
  </library_visual_scenes><scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
)");
  std::string nodes;
  for (int k = 0; k < 10000; ++k) nodes += "<node>";
  for (int k = 0; k < 10000; ++k) nodes += "</node>";
  write(
      dir / "deep.dae",
      R"(<COLLADA version="1.4.1"><library_visual_scenes><visual_scene id="s">)" + nodes +
          R"(</visual_scene></library_visual_scenes><scene><instance_visual_scene url="#s"/></scene></COLLADA>)");
  write(dir / "negative.ply",
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
        "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 -100000000\n");
  std::string short_ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 8\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n";
  short_ply.append(36, '\0');  // 3 vertices of the 8
  write(dir / "short.ply", short_ply);
  ASSERT_EQ(::mkfifo((dir / "fifo.bin").c_str(), 0600), 0);
  write(dir / "fifo.gltf",
        R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"buffers":[{"byteLength":36,"uri":"fifo.bin"}],
    "bufferViews":[{"buffer":0,"byteLength":36}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,1]}]})");
  for (const char* mesh : {"self.dae", "deep.dae", "negative.ply", "short.ply", "fifo.gltf"}) {
    SCOPED_TRACE(mesh);
    const std::string urdf = (dir / (std::string(mesh) + ".urdf")).string();
    write(urdf, robot(mesh));
    try {
      rt::Simulation::load(urdf);
      ADD_FAILURE() << "loaded";
    } catch (const rt::LoadError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(urdf + ":4:26: error: mesh file " + (dir / mesh).string()), std::string::npos)
          << what;
      EXPECT_NE(what.find("cannot be a MuJoCo mesh: "), std::string::npos) << what;
    }
  }
}

}  // namespace
