// Meshes in the formats robots ship (COLLADA, ASCII STL, PLY, ...) reach MuJoCo: read with assimp, node
// transforms baked, COLLADA's unit honoured and its up axis taken as RViz and Gazebo take it (ignored), then
// written beside the MJCF (binary STL, or OBJ past MuJoCo's 200000-triangle STL limit) or inline on stdout.
// Masses are checked against closed forms and against MuJoCo reading the same solid from a binary STL; a
// visual mesh that is missing or unreadable is a located warning (the robot loads), a collision one an error
// that writes nothing.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/cli_run.h"
#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace {

namespace fs = std::filesystem;
using openplx::testing::ScratchDir;

// A box [0, size] moved by `offset` as 8 corners (index 4x + 2y + z) and 6 outward quads.
const int kQuads[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};

std::vector<Eigen::Vector3d> corners(const Eigen::Vector3d& size, const Eigen::Vector3d& offset) {
  std::vector<Eigen::Vector3d> c;
  for (int x = 0; x < 2; ++x)
    for (int y = 0; y < 2; ++y)
      for (int z = 0; z < 2; ++z)
        c.push_back(offset + Eigen::Vector3d(x * size.x(), y * size.y(), z * size.z()));
  return c;
}

// The box in a COLLADA file: quads (assimp triangulates them), placed by a node's <translate>, with a stray
// line to a far point (points and lines are dropped: it must not widen the mesh).
std::string collada(const std::string& unit, const std::string& up, const Eigen::Vector3d& size,
                    const Eigen::Vector3d& translate) {
  std::ostringstream positions, polys;
  for (const Eigen::Vector3d& p : corners(size, Eigen::Vector3d::Zero()))
    positions << p.x() << ' ' << p.y() << ' ' << p.z() << ' ';
  positions << 50 * size.x() << " 0 0";
  for (const auto& q : kQuads) polys << q[0] << ' ' << q[1] << ' ' << q[2] << ' ' << q[3] << ' ';
  return R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit meter=")" +
         unit + R"(" name="unit"/><up_axis>)" + up + R"(</up_axis></asset>
  <library_geometries>
    <geometry id="box" name="box"><mesh>
      <source id="box-positions">
        <float_array id="box-array" count="27">)" +
         positions.str() + R"(</float_array>
        <technique_common><accessor source="#box-array" count="9" stride="3">
          <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
        </accessor></technique_common>
      </source>
      <vertices id="box-vertices"><input semantic="POSITION" source="#box-positions"/></vertices>
      <polylist count="6"><input semantic="VERTEX" source="#box-vertices" offset="0"/>
        <vcount>4 4 4 4 4 4</vcount><p>)" +
         polys.str() + R"(</p></polylist>
      <lines count="1"><input semantic="VERTEX" source="#box-vertices" offset="0"/><p>0 8</p></lines>
    </mesh></geometry>
  </library_geometries>
  <library_visual_scenes><visual_scene id="scene"><node id="part" name="part">
    <translate>)" +
         std::to_string(translate.x()) + ' ' + std::to_string(translate.y()) + ' ' +
         std::to_string(translate.z()) +
         R"(</translate><instance_geometry url="#box"/></node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
)";
}

std::vector<std::array<int, 3>> box_triangles() {
  std::vector<std::array<int, 3>> t;
  for (const auto& q : kQuads) {
    t.push_back({q[0], q[1], q[2]});
    t.push_back({q[0], q[2], q[3]});
  }
  return t;
}

std::string ascii_stl(const Eigen::Vector3d& size) {
  const auto c = corners(size, Eigen::Vector3d::Zero());
  std::ostringstream out;
  out << "solid box\n";
  for (const auto& t : box_triangles()) {
    out << "  facet normal 0 0 0\n    outer loop\n";
    for (int k : t) out << "      vertex " << c[k].x() << ' ' << c[k].y() << ' ' << c[k].z() << "\n";
    out << "    endloop\n  endfacet\n";
  }
  out << "endsolid box\n";
  return out.str();
}

std::string binary_stl(const std::vector<Eigen::Vector3d>& c,
                       const std::vector<std::array<int, 3>>& triangles) {
  std::string bytes(80, '\0');
  auto put = [&](auto value) { bytes.append(reinterpret_cast<const char*>(&value), sizeof(value)); };
  put(static_cast<uint32_t>(triangles.size()));
  for (const auto& t : triangles) {
    for (int k = 0; k < 3; ++k) put(0.0f);
    for (int k : t)
      for (int a = 0; a < 3; ++a) put(static_cast<float>(c[k][a]));
    put(uint16_t{0});
  }
  return bytes;
}

std::string ascii_ply(const Eigen::Vector3d& size) {
  std::ostringstream out;
  out << "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 6\nproperty list uchar int vertex_indices\nend_header\n";
  for (const Eigen::Vector3d& p : corners(size, Eigen::Vector3d::Zero()))
    out << p.x() << ' ' << p.y() << ' ' << p.z() << "\n";
  for (const auto& q : kQuads) out << "4 " << q[0] << ' ' << q[1] << ' ' << q[2] << ' ' << q[3] << "\n";
  return out.str();
}

std::string base64(const std::string& bytes) {
  static const char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string text;
  for (size_t k = 0; k < bytes.size(); k += 3) {
    uint32_t v = static_cast<unsigned char>(bytes[k]) << 16;
    if (k + 1 < bytes.size()) v |= static_cast<unsigned char>(bytes[k + 1]) << 8;
    if (k + 2 < bytes.size()) v |= static_cast<unsigned char>(bytes[k + 2]);
    const size_t n = std::min<size_t>(3, bytes.size() - k);  // bytes in this group: n + 1 digits
    for (size_t d = 0; d < 4; ++d) text += d <= n ? kDigits[(v >> (18 - 6 * d)) & 63] : '=';
  }
  return text;
}

// The box as glTF (Y up by the standard), its buffer inline.
std::string gltf(const Eigen::Vector3d& size) {
  std::string buffer;
  for (const Eigen::Vector3d& p : corners(size, Eigen::Vector3d::Zero()))
    for (int a = 0; a < 3; ++a) {
      const float f = static_cast<float>(p[a]);
      buffer.append(reinterpret_cast<const char*>(&f), 4);
    }
  for (const auto& t : box_triangles())
    for (int k : t) {
      const uint16_t index = static_cast<uint16_t>(k);
      buffer.append(reinterpret_cast<const char*>(&index), 2);
    }
  std::ostringstream out;
  out << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
      << R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
      << R"("buffers":[{"byteLength":168,"uri":"data:application/octet-stream;base64,)" << base64(buffer)
      << R"("}],)"
      << R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":96},{"buffer":0,"byteOffset":96,"byteLength":72}],)"
      << R"("accessors":[{"bufferView":0,"componentType":5126,"count":8,"type":"VEC3","min":[0,0,0],"max":[)"
      << size.x() << ',' << size.y() << ',' << size.z() << R"(]},)"
      << R"({"bufferView":1,"componentType":5123,"count":36,"type":"SCALAR"}]})";
  return out.str();
}

void write(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A free body whose mass comes from its collision mesh (water's density), with the same file as its look.
std::string scene(const std::string& file, const std::string& scale = "{1, 1, 1}") {
  return "Scene is Physics3D.System:\n"
         "    body is Physics3D.Bodies.RigidBody:\n"
         "        shape is Physics3D.Geometries.ExternalTriMeshGeometry:\n"
         "            path: @\"" +
         file + "\"\n            scale: " + scale +
         "\n"
         "        look is Visuals.Geometries.ExternalTriMeshGeometry:\n"
         "            path: @\"" +
         file + "\"\n";
}

using openplx::testing::cli;
using openplx::testing::Conversion;

struct Model {
  mjModel* m = nullptr;
  mjData* d = nullptr;
  explicit Model(const fs::path& xml) {
    char error[1000] = "";
    m = mj_loadXML(xml.c_str(), nullptr, error, sizeof(error));
    EXPECT_NE(m, nullptr) << error << "\n" << read(xml);
    if (m) {
      d = mj_makeData(m);
      mj_forward(m, d);
    }
  }
  ~Model() {
    if (d) mj_deleteData(d);
    if (m) mj_deleteModel(m);
  }
  double mass(const char* body) const { return m->body_mass[mj_name2id(m, mjOBJ_BODY, body)]; }
  // The world box around a mesh geom's vertices (MuJoCo keeps them centred in their inertia frame).
  std::pair<Eigen::Vector3d, Eigen::Vector3d> extents(const char* geom) const {
    const int g = mj_name2id(m, mjOBJ_GEOM, geom);
    EXPECT_GE(g, 0) << geom;
    return extents(g);
  }
  std::pair<Eigen::Vector3d, Eigen::Vector3d> extents(int g) const {
    const int mesh = m->geom_dataid[g];
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
    const Eigen::Map<const Eigen::Matrix<mjtNum, 3, 3, Eigen::RowMajor>> rotation(d->geom_xmat + 9 * g);
    const Eigen::Map<const Eigen::Vector3d> position(d->geom_xpos + 3 * g);
    for (int v = 0; v < m->mesh_vertnum[mesh]; ++v) {
      const float* p = m->mesh_vert + 3 * (m->mesh_vertadr[mesh] + v);
      const Eigen::Vector3d world = position + rotation * Eigen::Vector3d(p[0], p[1], p[2]);
      lo = lo.cwiseMin(world);
      hi = hi.cwiseMax(world);
    }
    return {lo, hi};
  }
};

// How often `part` occurs in `text`.
size_t occurrences(const std::string& text, const std::string& part) {
  size_t count = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++count;
  return count;
}

// A 100 x 200 x 300 box in millimetres at (10, 20, 30) mm: 0.1 x 0.2 x 0.3 m, 6 kg of water, its corner at
// (0.01, 0.02, 0.03) m as written. Coordinates are taken as written by default, as RViz and Gazebo show
// them, whatever the <up_axis>; --collada-up-axis turns it onto +Z as COLLADA defines it (Y_UP: (x, y, z) ->
// (x, -z, y); X_UP: (x, y, z) -> (-y, -z, x)). A file whose <up_axis> is not Z_UP gets one note, however
// many geometries name it (here a collision and a visual one).
TEST(MeshConversion, ColladaUnitAndUpAxisAreHonoured) {
  const ScratchDir dir;
  using V = Eigen::Vector3d;
  struct Case {
    const char* up;
    bool turn;
    V lo, hi;
  };
  const V written_lo(0.01, 0.02, 0.03), written_hi(0.11, 0.22, 0.33);
  for (const Case& c :
       {Case{"Z_UP", false, written_lo, written_hi}, Case{"Z_UP", true, written_lo, written_hi},
        Case{"Y_UP", true, V(0.01, -0.33, 0.02), V(0.11, -0.03, 0.22)},
        Case{"X_UP", true, V(-0.22, -0.33, 0.01), V(-0.02, -0.03, 0.11)},
        Case{"Y_UP", false, written_lo, written_hi}, Case{"X_UP", false, written_lo, written_hi}}) {
    SCOPED_TRACE(std::string(c.up) + (c.turn ? " turned" : " as written"));
    write(dir / "box.dae", collada("0.001", c.up, {100, 200, 300}, {10, 20, 30}));
    write(dir / "scene.openplx", scene("box.dae"));
    std::vector<std::string> args{(dir / "scene.openplx").string(), "-o", (dir / "scene.xml").string(),
                                  "--check", "--strict"};
    if (c.turn) args.push_back("--collada-up-axis");
    const Conversion r = cli(args);
    ASSERT_EQ(r.status, 0) << r.errors;  // a note, not a warning: --strict passes
    if (std::string(c.up) == "Z_UP") {
      EXPECT_EQ(r.errors, "");
    } else {
      EXPECT_EQ(occurrences(r.errors, "declares <up_axis>"), 1u) << r.errors;
      EXPECT_NE(r.errors.find(std::string("note: mesh file ") + (dir / "box.dae").string() +
                              " declares <up_axis>" + c.up),
                std::string::npos)
          << r.errors;
      EXPECT_NE(r.errors.find(c.turn ? "turned so that its up axis is +Z" : "taken as written"),
                std::string::npos)
          << r.errors;
    }
    EXPECT_TRUE(fs::is_regular_file(dir / "scene.meshes" / "box.stl"));
    EXPECT_NE(read(dir / "scene.xml").find("file=\"scene.meshes/box.stl\""), std::string::npos);
    const Model model(dir / "scene.xml");
    if (!model.m) continue;
    EXPECT_NEAR(model.mass("body"), 0.1 * 0.2 * 0.3 * 1000, 1e-4);  // a proper turn keeps the volume
    for (const char* geom : {"body.shape", "body.look"}) {
      const auto [lo, hi] = model.extents(geom);
      EXPECT_LT((lo - c.lo).norm(), 1e-6) << geom << " " << lo.transpose();
      EXPECT_LT((hi - c.hi).norm(), 1e-6) << geom << " " << hi.transpose();
    }
  }
}

// The box as a binary STL: two triangles per quad, outward.
std::string box_stl(const Eigen::Vector3d& size) {
  const std::vector<Eigen::Vector3d> c = corners(size, Eigen::Vector3d::Zero());
  std::string bytes(80, '\0');
  const uint32_t count = 12;
  bytes.append(reinterpret_cast<const char*>(&count), 4);
  for (const auto& q : kQuads) {
    for (const std::array<int, 3>& t : {std::array<int, 3>{q[0], q[1], q[2]}, {q[0], q[2], q[3]}}) {
      const float zero[3] = {0, 0, 0};
      bytes.append(reinterpret_cast<const char*>(zero), sizeof(zero));
      for (int k : t) {
        const float p[3] = {float(c[k].x()), float(c[k].y()), float(c[k].z())};
        bytes.append(reinterpret_cast<const char*>(p), sizeof(p));
      }
      bytes.append(2, '\0');
    }
  }
  return bytes;
}

// A URDF robot drawn for RViz: its link's visual is a COLLADA box, its collision the same box as an STL.
// Whatever the COLLADA file's <up_axis> (Z_UP, Y_UP, X_UP), the visual sits on its collision twin by default,
// as RViz and Gazebo show it.
TEST(MeshConversion, UrdfColladaVisualMatchesItsCollisionTwinByDefault) {
  const ScratchDir dir;
  write(dir / "box.stl", box_stl({0.1, 0.2, 0.3}));
  write(dir / "robot.urdf", R"(<robot name="arm">
  <link name="base"/>
  <link name="box">
    <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><origin xyz="0.5 0 0"/><geometry><mesh filename="box.dae"/></geometry></visual>
    <collision><origin xyz="0.5 0 0"/><geometry><mesh filename="box.stl"/></geometry></collision>
  </link>
  <joint name="hinge" type="revolute"><parent link="base"/><child link="box"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
)");
  for (const char* up : {"Z_UP", "Y_UP", "X_UP"}) {
    SCOPED_TRACE(up);
    write(dir / "box.dae", collada("1", up, {0.1, 0.2, 0.3}, {0, 0, 0}));
    const Conversion r = cli({(dir / "robot.urdf").string(), "-o", (dir / "robot.xml").string(), "--check"});
    ASSERT_EQ(r.status, 0) << r.errors;
    EXPECT_EQ(occurrences(r.errors, "declares <up_axis>"), std::string(up) == "Z_UP" ? 0u : 1u) << r.errors;
    const Model model(dir / "robot.xml");
    if (!model.m) continue;
    std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> boxes;
    for (int g = 0; g < model.m->ngeom; ++g)
      if (model.m->geom_type[g] == mjGEOM_MESH) boxes.push_back(model.extents(g));
    ASSERT_EQ(boxes.size(), 2u);
    EXPECT_LT((boxes[0].first - boxes[1].first).norm(), 1e-6) << boxes[0].first.transpose();
    EXPECT_LT((boxes[0].second - boxes[1].second).norm(), 1e-6) << boxes[0].second.transpose();
    EXPECT_LT((boxes[0].second - Eigen::Vector3d(0.6, 0.2, 0.3)).norm(), 1e-6) << boxes[0].second.transpose();
  }
}

// glTF is Y up by its standard: turned onto Z as RViz turns it, (x, y, z) -> (x, -z, y).
TEST(MeshConversion, GltfYUpIsTurnedOntoZ) {
  const ScratchDir dir;
  write(dir / "box.gltf", gltf({0.1, 0.2, 0.3}));
  write(dir / "scene.openplx", scene("box.gltf"));
  const Conversion r = cli({(dir / "scene.openplx").string(), "-o", (dir / "scene.xml").string()});
  ASSERT_EQ(r.status, 0) << r.errors;
  const Model model(dir / "scene.xml");
  if (!model.m) return;
  EXPECT_NEAR(model.mass("body"), 6, 1e-4);
  const auto [lo, hi] = model.extents("body.shape");
  EXPECT_LT((lo - Eigen::Vector3d(0, -0.3, 0)).norm(), 1e-6) << lo.transpose();
  EXPECT_LT((hi - Eigen::Vector3d(0.1, 0, 0.2)).norm(), 1e-6) << hi.transpose();
}

// A cube of side 1 in a file whose unit is the millimetre is 1 mm; the mesh's scale applies on top.
TEST(MeshConversion, ScaleAppliesOnTopOfTheUnit) {
  const ScratchDir dir;
  write(dir / "cube.dae", collada("0.001", "Z_UP", {1, 1, 1}, {0, 0, 0}));
  write(dir / "scene.openplx", scene("cube.dae", "{100, 100, 100}"));
  const Conversion r = cli({(dir / "scene.openplx").string(), "-o", (dir / "scene.xml").string()});
  ASSERT_EQ(r.status, 0) << r.errors;
  const Model model(dir / "scene.xml");
  if (!model.m) return;
  EXPECT_NEAR(model.mass("body"), 0.1 * 0.1 * 0.1 * 1000, 1e-6);
  const auto [lo, hi] = model.extents("body.shape");
  EXPECT_LT((hi - lo - Eigen::Vector3d::Constant(0.1)).norm(), 1e-6) << (hi - lo).transpose();
}

// ASCII STL (MuJoCo 2.2.2 reads binary STL only) and PLY: the same masses and inertias as MuJoCo reading the
// same box from a binary STL itself.
TEST(MeshConversion, AsciiStlAndPlyMatchMuJoCoReadingABinaryStl) {
  const ScratchDir dir;
  const Eigen::Vector3d size(0.1, 0.2, 0.3);
  write(dir / "box.stl", binary_stl(corners(size, Eigen::Vector3d::Zero()), box_triangles()));
  write(dir / "reference.xml",
        "<mujoco><compiler exactmeshinertia=\"true\"/><asset><mesh name=\"box\" file=\"box.stl\"/></asset>"
        "<worldbody><body name=\"body\"><freejoint/><geom type=\"mesh\" mesh=\"box\"/></body></worldbody>"
        "</mujoco>");
  const Model reference(dir / "reference.xml");
  ASSERT_NE(reference.m, nullptr);
  write(dir / "ascii.STL", ascii_stl(size));  // the extension in capitals, as Windows exporters write it
  write(dir / "box.ply", ascii_ply(size));
  for (const char* file : {"ascii.STL", "box.ply"}) {
    SCOPED_TRACE(file);
    write(dir / "scene.openplx", scene(file));
    const Conversion r = cli({(dir / "scene.openplx").string(), "-o", (dir / "scene.xml").string()});
    ASSERT_EQ(r.status, 0) << r.errors;
    const Model model(dir / "scene.xml");
    if (!model.m) continue;
    const int body = mj_name2id(model.m, mjOBJ_BODY, "body");
    EXPECT_NEAR(model.mass("body"), 6, 1e-4);
    EXPECT_NEAR(model.m->body_mass[body], reference.m->body_mass[1], 1e-9);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(model.m->body_inertia[3 * body + k], reference.m->body_inertia[3 + k], 1e-9);
  }
}

// On stdout the converted mesh is inline (<mesh vertex face>): the same model as with files.
TEST(MeshConversion, StdoutHoldsTheMeshInline) {
  const ScratchDir dir;
  write(dir / "box.dae", collada("0.01", "Z_UP", {10, 20, 30}, {0, 0, 0}));
  write(dir / "scene.openplx", scene("box.dae"));
  const Conversion r = cli({(dir / "scene.openplx").string(), "-o", "-"});
  ASSERT_EQ(r.status, 0) << r.errors;
  EXPECT_NE(r.out.find("vertex=\""), std::string::npos);
  EXPECT_EQ(r.out.find("file=\""), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "scene.meshes"));
  write(dir / "inline.xml", r.out);
  const Model model(dir / "inline.xml");
  if (model.m) {
    EXPECT_NEAR(model.mass("body"), 6, 1e-4);
  }
}

// The same input writes the same bytes, under the same names.
TEST(MeshConversion, OutputIsByteForByteTheSameOverRuns) {
  const ScratchDir dir;
  fs::create_directories(dir / "visual");
  fs::create_directories(dir / "collision");
  write(dir / "visual" / "part.dae", collada("0.001", "Z_UP", {100, 200, 300}, {0, 0, 0}));
  write(dir / "collision" / "part.dae", collada("0.001", "Z_UP", {100, 100, 100}, {0, 0, 0}));
  write(dir / "scene.openplx",
        "Scene is Physics3D.System:\n"
        "    body is Physics3D.Bodies.RigidBody:\n"
        "        shape is Physics3D.Geometries.ExternalTriMeshGeometry:\n"
        "            path: @\"collision/part.dae\"\n"
        "        look is Visuals.Geometries.ExternalTriMeshGeometry:\n"
        "            path: @\"visual/part.dae\"\n");
  std::vector<std::string> runs;
  for (int k = 0; k < 2; ++k) {
    const Conversion r = cli({(dir / "scene.openplx").string(), "-o", (dir / "scene.xml").string()});
    ASSERT_EQ(r.status, 0) << r.errors;
    std::string all = read(dir / "scene.xml");
    for (const auto& entry : fs::directory_iterator(dir / "scene.meshes"))
      all += "\n" + entry.path().filename().string() + "\n" + read(entry.path());
    runs.push_back(all);
    fs::remove_all(dir / "scene.meshes");
  }
  EXPECT_EQ(runs[0], runs[1]);
  // Two files of one name each get their own.
  EXPECT_NE(runs[0].find("scene.meshes/part.stl"), std::string::npos);
  EXPECT_NE(runs[0].find("scene.meshes/part_2.stl"), std::string::npos);
}

// Past MuJoCo 2.2.2's 200000 STL triangles, the mesh is written as OBJ (a binary STL that big is converted
// too): a box whose top is a fan of 200004 triangles.
TEST(MeshConversion, MoreTrianglesThanMuJoCoReadsFromStlBecomeObj) {
  const ScratchDir dir;
  std::vector<Eigen::Vector3d> c = corners({0.1, 0.2, 0.3}, Eigen::Vector3d::Zero());
  std::vector<std::array<int, 3>> triangles;
  for (const auto& t : box_triangles()) {
    if (c[t[0]].z() > 0 && c[t[1]].z() > 0 && c[t[2]].z() > 0) continue;  // the top, replaced by the fan
    triangles.push_back(t);
  }
  const int n = 50001;  // points per top edge
  c.emplace_back(0.05, 0.1, 0.3);
  const int centre = static_cast<int>(c.size()) - 1, first = static_cast<int>(c.size());
  const std::array<Eigen::Vector3d, 4> top = {Eigen::Vector3d(0, 0, 0.3), Eigen::Vector3d(0.1, 0, 0.3),
                                              Eigen::Vector3d(0.1, 0.2, 0.3), Eigen::Vector3d(0, 0.2, 0.3)};
  for (int e = 0; e < 4; ++e)
    for (int k = 0; k < n; ++k) c.push_back(top[e] + (top[(e + 1) % 4] - top[e]) * k / n);
  const int ring = 4 * n;
  for (int k = 0; k < ring; ++k) triangles.push_back({centre, first + k, first + (k + 1) % ring});
  ASSERT_GT(triangles.size(), 200000u);
  write(dir / "big.stl", binary_stl(c, triangles));
  write(dir / "scene.openplx", scene("big.stl"));
  const Conversion r = cli({(dir / "scene.openplx").string(), "-o", (dir / "scene.xml").string()});
  ASSERT_EQ(r.status, 0) << r.errors;
  EXPECT_EQ(r.errors, "");
  EXPECT_TRUE(fs::is_regular_file(dir / "scene.meshes" / "big.obj"));
  const Model model(dir / "scene.xml");
  if (model.m) {
    EXPECT_NEAR(model.mass("body"), 6, 1e-4);
  }
}

// A URDF robot with COLLADA meshes; a missing visual mesh is a warning at its URDF <mesh> element and the
// robot loads without it; a missing collision mesh is an error there, and nothing is written.
std::string urdf(const std::string& arm_visual, const std::string& arm_collision) {
  return "<?xml version=\"1.0\"?>\n"
         "<robot name=\"r\">\n"
         "  <link name=\"base\">\n"
         "    <visual><geometry><mesh filename=\"meshes/part.dae\"/></geometry></visual>\n"
         "  </link>\n"
         "  <link name=\"arm\">\n"
         "    <inertial><mass value=\"1\"/><inertia ixx=\"0.01\" iyy=\"0.01\" izz=\"0.01\" ixy=\"0\" "
         "ixz=\"0\" "
         "iyz=\"0\"/></inertial>\n"
         "    <visual><geometry><mesh filename=\"" +
         arm_visual +
         "\"/></geometry></visual>\n"
         "    <collision><geometry><mesh filename=\"" +
         arm_collision +
         "\"/></geometry></collision>\n"
         "  </link>\n"
         "  <joint name=\"j\" type=\"revolute\"><parent link=\"base\"/><child link=\"arm\"/><axis xyz=\"0 0 "
         "1\"/>"
         "<limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>\n"
         "</robot>\n";
}

TEST(MeshConversion, UrdfMissingVisualMeshWarnsAtItsElementAndTheRobotLoads) {
  const ScratchDir dir;
  fs::create_directories(dir / "meshes");
  write(dir / "meshes" / "part.DAE", collada("1", "Z_UP", {0.1, 0.1, 0.1}, {0, 0, 0}));
  write(dir / "meshes" / "part.dae", collada("1", "Z_UP", {0.1, 0.1, 0.1}, {0, 0, 0}));
  write(dir / "r.urdf", urdf("meshes/gone.dae", "meshes/part.DAE"));
  const Conversion r = cli({(dir / "r.urdf").string(), "-o", (dir / "r.xml").string(), "--check"});
  ASSERT_EQ(r.status, 0) << r.errors;
  EXPECT_NE(r.errors.find((dir / "r.urdf").string() + ":8:23: warning: mesh file " +
                          (dir / "meshes" / "gone.dae").string() +
                          " of `arm.visual_0` not found; this visual geometry was left out"),
            std::string::npos)
      << r.errors;
  const Model model(dir / "r.xml");
  if (!model.m) return;
  EXPECT_EQ(mj_name2id(model.m, mjOBJ_GEOM, "arm.visual_0"), -1);
  EXPECT_GE(mj_name2id(model.m, mjOBJ_GEOM, "arm.collision_0"), 0);
  EXPECT_GE(mj_name2id(model.m, mjOBJ_GEOM, "base.visual_0"), 0);
  EXPECT_NEAR(model.mass("arm"), 1, 1e-12);  // the URDF's <inertial>
}

TEST(MeshConversion, UnreadableVisualMeshWarnsAndCollisionMeshIsAnErrorWritingNothing) {
  const ScratchDir dir;
  fs::create_directories(dir / "meshes");
  write(dir / "meshes" / "part.dae", collada("1", "Z_UP", {0.1, 0.1, 0.1}, {0, 0, 0}));
  write(dir / "meshes" / "broken.dae", "<COLLADA/>");
  // Unreadable on a visual: a warning naming the file and the geometry.
  write(dir / "r.urdf", urdf("meshes/broken.dae", "meshes/part.dae"));
  Conversion r = cli({(dir / "r.urdf").string(), "-o", (dir / "r.xml").string()});
  ASSERT_EQ(r.status, 0) << r.errors;
  EXPECT_NE(r.errors.find((dir / "r.urdf").string() + ":8:23: warning: mesh file " +
                          (dir / "meshes" / "broken.dae").string() +
                          " of `arm.visual_0.path` cannot be a MuJoCo mesh"),
            std::string::npos)
      << r.errors;
  fs::remove(dir / "r.xml");
  fs::remove(dir / "r.signals.json");
  fs::remove_all(dir / "r.meshes");
  // Missing or unreadable on a collision geometry: an error at its element, and no file at all.
  for (const char* collision : {"meshes/gone.dae", "meshes/broken.dae"}) {
    SCOPED_TRACE(collision);
    write(dir / "r.urdf", urdf("meshes/part.dae", collision));
    r = cli({(dir / "r.urdf").string(), "-o", (dir / "r.xml").string()});
    EXPECT_EQ(r.status, openplx::cli::kExitInputError);
    EXPECT_NE(r.errors.find((dir / "r.urdf").string() + ":9:26: error: mesh file "), std::string::npos)
        << r.errors;
    for (const char* written : {"r.xml", "r.signals.json", "r.meshes"})
      EXPECT_FALSE(fs::exists(dir / written)) << written;
  }
}

// When the MJCF cannot be written, the mesh files written before it are taken back.
TEST(MeshConversion, AFailedWriteLeavesNoMeshFiles) {
  const ScratchDir dir;
  write(dir / "box.dae", collada("1", "Z_UP", {0.1, 0.1, 0.1}, {0, 0, 0}));
  write(dir / "scene.openplx", scene("box.dae"));
  fs::create_directories(dir / "scene.xml" / "in_the_way");  // a folder where the MJCF should go
  const Conversion r = cli({(dir / "scene.openplx").string(), "-o", (dir / "scene.xml").string()});
  EXPECT_EQ(r.status, openplx::cli::kExitInputError) << r.errors;
  EXPECT_FALSE(fs::exists(dir / "scene.meshes"));
  EXPECT_FALSE(fs::exists(dir / "scene.signals.json"));
}

}  // namespace
