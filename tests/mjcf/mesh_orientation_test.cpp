// Face orientation, which MuJoCo 2.2.2 checks on shared vertices only: it refuses an inline mesh or an OBJ
// whose faces run along one edge in the same direction (where it computes the geom's inertia from the mesh),
// and takes the same triangles from a binary STL (each triangle its own vertices). A converted mesh (assimp)
// reaches MuJoCo as such a triangle soup everywhere (inline, the written STL), so --check, `-o -` and the
// written file agree; an OBJ passed to MuJoCo untouched is checked by MuJoCo's own rule, which is held here
// to MuJoCo's verdict.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "mjcf_emitter/asset_file_checks.h"
#include "mjcf_emitter/mesh_conversion.h"
#include "tests/support/cli_run.h"
#include "tests/support/scratch_dir.h"
#include "tests/support/tetrahedron_stl.h"
#include "tools/cli/cli.h"

namespace {

namespace fs = std::filesystem;
using openplx::testing::ScratchDir;
using Corner = std::array<float, 3>;

void write(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A model MuJoCo 2.2.2 loaded, or why not.
struct Loaded {
  mjModel* m = nullptr;
  std::string error;
  explicit Loaded(const fs::path& xml) {
    char text[1000] = "";
    m = mj_loadXML(xml.c_str(), nullptr, text, sizeof(text));
    error = text;
  }
  ~Loaded() {
    if (m) mj_deleteModel(m);
  }
  Loaded(const Loaded&) = delete;
  Loaded& operator=(const Loaded&) = delete;
};

// One free body of one mesh asset given by `attributes` (file="..." or vertex="..." face="..."), its inertia
// MuJoCo 2.2.2's legacy one or, `exact`, the exact one (which refuses some meshes the legacy one takes).
std::string mesh_model(const std::string& attributes, bool exact = false) {
  return std::string("<mujoco><compiler exactmeshinertia=\"") + (exact ? "true" : "false") +
         "\"/><asset><mesh name=\"m\" " + attributes +
         "/></asset><worldbody><body name=\"b\"><freejoint/><geom type=\"mesh\" mesh=\"m\"/></body>"
         "</worldbody></mujoco>";
}

// An OBJ of these vertices and face lines (1-based, as written).
std::string obj(const std::vector<Corner>& vertices, const std::string& faces) {
  std::ostringstream text;
  for (const Corner& v : vertices) text << "v " << v[0] << ' ' << v[1] << ' ' << v[2] << '\n';
  return text.str() + faces;
}

const std::vector<Corner> kTetra = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
const std::string kTetraFaces = "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

// A unit cube's corners (index 4x + 2y + z) and its outward quads, 0-based.
std::vector<Corner> cube() {
  std::vector<Corner> c;
  for (int x = 0; x < 2; ++x)
    for (int y = 0; y < 2; ++y)
      for (int z = 0; z < 2; ++z) c.push_back({float(x), float(y), float(z)});
  return c;
}
const int kQuads[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};

std::string quad_faces(int flipped) {
  std::string text;
  for (int q = 0; q < 6; ++q) {
    text += 'f';
    for (int k = 0; k < 4; ++k) text += ' ' + std::to_string(kQuads[q][q == flipped ? 3 - k : k] + 1);
    text += '\n';
  }
  return text;
}

// Our rule against MuJoCo 2.2.2's own on OBJ files: both must call a mesh inconsistent, or neither. Each
// mesh is otherwise one MuJoCo loads, and `refused` says what MuJoCo does, so the cases mean what they say.
TEST(MeshOrientation, ObjRuleAgreesWithMuJoCo) {
  const ScratchDir dir;
  struct Case {
    const char* name;
    std::string text;
    bool refused;
  };
  std::vector<Corner> twice = kTetra;  // the tetrahedron's last three corners again, under new indices
  for (int k = 1; k < 4; ++k) twice.push_back(kTetra[k]);
  std::vector<Corner> two = kTetra;  // a second tetrahedron beside the first
  for (const Corner& v : kTetra) two.push_back({v[0] + 2, v[1], v[2]});
  const std::vector<Corner> kite = {{-2, 0, 0}, {0, -1, 0}, {2, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const std::vector<Case> cases = {
      {"closed", obj(kTetra, kTetraFaces), false},
      {"closed, one face flipped", obj(kTetra, "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 4 3\n"), true},
      {"open", obj(kTetra, "f 1 3 2\nf 1 2 4\nf 1 4 3\n"), false},
      {"open, one face flipped", obj(kTetra, "f 1 3 2\nf 1 4 2\nf 1 4 3\n"), true},
      {"a face given twice", obj(kTetra, kTetraFaces + "f 1 3 2\n"), true},
      {"a degenerate face along an edge", obj(kTetra, kTetraFaces + "f 1 1 2\n"), true},
      // Two solids, the second turned inside out as a whole: each is consistent in itself.
      {"two solids, one inside out", obj(two, kTetraFaces + "f 5 6 7\nf 5 8 6\nf 5 7 8\nf 6 8 7\n"), false},
      // The flipped face's corners are the same points under other indices: MuJoCo compares indices.
      {"a flipped face on copies of the corners", obj(twice, "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 5 7 6\n"), false},
      {"cube of quads", obj(cube(), quad_faces(-1)), false},
      {"cube of quads, one flipped", obj(cube(), quad_faces(2)), true},
      // A quad is split from its first corner (1-3 here, the longer diagonal): a face along 1->3 clashes,
      // one along 2->4 does not.
      {"quad split 1-3, a face along 1->3", obj(kite, "f 1 2 3 4\nf 1 3 5\n"), true},
      {"quad split 1-3, a face along 2->4", obj(kite, "f 1 2 3 4\nf 2 4 5\n"), false},
      // A pentagon is a fan from its first corner too.
      {"pentagon fan, a face along 1->3", obj(kite, "f 1 2 3 4 5\nf 1 3 5\n"), true},
      // MuJoCo reads the first object's faces only (`o` or `g` after faces starts another).
      {"flipped face in the second object",
       obj(two, "o a\n" + kTetraFaces + "o b\nf 5 7 6\nf 5 6 8\nf 5 8 7\nf 6 8 7\n"), false},
      {"flipped face in the second group",
       obj(two, "g a\n" + kTetraFaces + "g b\nf 5 7 6\nf 5 6 8\nf 5 8 7\nf 6 8 7\n"), false},
      {"flipped face in the first object",
       obj(two, "o a\nf 5 7 6\nf 5 6 8\nf 5 8 7\nf 6 8 7\no b\n" + kTetraFaces), true},
      {"a material change does not start an object",
       obj(two, kTetraFaces + "usemtl red\nf 5 7 6\nf 5 6 8\nf 5 8 7\nf 6 8 7\n"), true},
  };
  int n = 0;
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string stem = "mesh" + std::to_string(n++);
    write(dir / (stem + ".obj"), c.text);
    write(dir / (stem + ".xml"), mesh_model("file=\"" + stem + ".obj\""));
    const Loaded mujoco(dir / (stem + ".xml"));
    const bool mujoco_refuses = !mujoco.m;
    EXPECT_EQ(mujoco_refuses, c.refused) << mujoco.error;
    if (mujoco_refuses) {
      EXPECT_NE(mujoco.error.find("inconsistent orientation"), std::string::npos) << mujoco.error;
    }
    const std::string problem = openplx::mjcf::mesh_file_problem((dir / (stem + ".obj")).string());
    EXPECT_EQ(!problem.empty(), mujoco_refuses) << problem;
    if (!problem.empty()) {
      EXPECT_NE(problem.find("its faces have inconsistent orientation"), std::string::npos) << problem;
    }
  }
}

// The message names the two faces' lines and the edge they share, in the file's numbering.
TEST(MeshOrientation, ObjProblemNamesTheFacesAndTheEdge) {
  const ScratchDir dir;
  write(dir / "m.obj", obj(kTetra, "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 4 3\n"));
  EXPECT_EQ(openplx::mjcf::mesh_file_problem((dir / "m.obj").string()),
            "its faces have inconsistent orientation (MuJoCo 2.2.2 refuses it): the faces on lines 5 and 8 "
            "both run from vertex 3 to vertex 2, so one is turned inside out or given twice");
}

// A box as a converted mesh holds it (shared vertices), with triangle `flipped` turned (-1: none).
openplx::mjcf::TriangleMesh box_mesh(int flipped) {
  openplx::mjcf::TriangleMesh mesh;
  for (const Corner& c : cube())
    for (int a = 0; a < 3; ++a) mesh.vertices.push_back(c[a] * (0.1f + 0.1f * a));
  int t = 0;
  for (const auto& q : kQuads)
    for (const std::array<int, 3>& triangle : {std::array<int, 3>{q[0], q[1], q[2]}, {q[0], q[2], q[3]}}) {
      const bool turn = t++ == flipped;
      for (int k : {0, turn ? 2 : 1, turn ? 1 : 2}) mesh.faces.push_back(static_cast<uint32_t>(triangle[k]));
    }
  return mesh;
}

// The inline text is a triangle soup: MuJoCo 2.2.2 takes it where it refuses the shared-vertex form, and
// gets the same mass and inertia from it as from the shared form (when that loads) and from the STL written.
TEST(MeshOrientation, InlineSoupHasTheMassOfTheSharedFormAndOfTheStl) {
  const ScratchDir dir;
  using openplx::mjcf::TriangleMesh;
  for (int flipped : {-1, 5}) {
    SCOPED_TRACE(flipped);
    const TriangleMesh mesh = box_mesh(flipped);
    std::string shared_vertex, shared_face;
    for (float v : mesh.vertices) shared_vertex += std::to_string(v) + ' ';
    for (uint32_t f : mesh.faces) shared_face += std::to_string(f) + ' ';
    write(dir / "shared.xml",
          mesh_model("vertex=\"" + shared_vertex + "\" face=\"" + shared_face + "\"", true));
    write(dir / "soup.xml", mesh_model("vertex=\"" + openplx::mjcf::vertex_text(mesh) + "\" face=\"" +
                                           openplx::mjcf::face_text(mesh) + "\"",
                                       true));
    ASSERT_STREQ(openplx::mjcf::mesh_file_extension(mesh), ".stl");
    write(dir / "box.stl", openplx::mjcf::mesh_file_bytes(mesh));
    write(dir / "stl.xml", mesh_model("file=\"box.stl\"", true));
    const Loaded shared(dir / "shared.xml"), soup(dir / "soup.xml"), stl(dir / "stl.xml");
    ASSERT_NE(soup.m, nullptr) << soup.error;
    ASSERT_NE(stl.m, nullptr) << stl.error;
    EXPECT_EQ(soup.m->mesh_vertnum[0], 3 * 12);  // every triangle its own vertices
    EXPECT_NEAR(soup.m->body_mass[1], stl.m->body_mass[1], 1e-12);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(soup.m->body_inertia[3 + k], stl.m->body_inertia[3 + k], 1e-12);
    if (flipped < 0) {
      EXPECT_NEAR(soup.m->body_mass[1], 0.1 * 0.2 * 0.3 * 1000, 1e-5);  // single-precision vertices
      ASSERT_NE(shared.m, nullptr) << shared.error;
      EXPECT_NEAR(soup.m->body_mass[1], shared.m->body_mass[1], 1e-12);
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(soup.m->body_inertia[3 + k], shared.m->body_inertia[3 + k], 1e-12);
    } else {
      EXPECT_EQ(shared.m, nullptr);  // why the inline text is a soup
      EXPECT_NE(shared.error.find("inconsistent orientation"), std::string::npos) << shared.error;
    }
    EXPECT_EQ(openplx::mjcf::vertex_text(mesh),
              openplx::mjcf::vertex_text(box_mesh(flipped)));  // deterministic
  }
}

// The box as an ASCII STL (read with assimp, which MuJoCo 2.2.2 cannot read), triangle `flipped` turned.
std::string ascii_stl(int flipped) {
  const openplx::mjcf::TriangleMesh mesh = box_mesh(flipped);
  std::ostringstream out;
  out << "solid box\n";
  for (size_t f = 0; f < mesh.faces.size(); f += 3) {
    out << "facet normal 0 0 0\n outer loop\n";
    for (size_t k = f; k < f + 3; ++k) {
      const float* v = &mesh.vertices[3 * mesh.faces[k]];
      out << "  vertex " << v[0] << ' ' << v[1] << ' ' << v[2] << '\n';
    }
    out << " endloop\nendfacet\n";
  }
  return out.str() + "endsolid box\n";
}

// The box as an ASCII PLY of quads, quad `flipped` turned.
std::string ascii_ply(int flipped) {
  std::ostringstream out;
  out << "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 6\nproperty list uchar int vertex_indices\nend_header\n";
  for (const Corner& c : cube()) out << c[0] * 0.1 << ' ' << c[1] * 0.2 << ' ' << c[2] * 0.3 << '\n';
  for (int q = 0; q < 6; ++q) {
    out << 4;
    for (int k = 0; k < 4; ++k) out << ' ' << kQuads[q][q == flipped ? 3 - k : k];
    out << '\n';
  }
  return out.str();
}

// A robot whose arm collides with `collision` and carries a massless, visual-only link drawn with `visual`.
// MuJoCo 2.2.2 checks a mesh's orientation where it computes the geom's inertia: in a body without an
// <inertial>, as that link's.
std::string robot(const std::string& visual, const std::string& collision) {
  return "<?xml version=\"1.0\"?>\n"
         "<robot name=\"r\">\n"
         "  <link name=\"base\"/>\n"
         "  <link name=\"arm\">\n"
         "    <inertial><mass value=\"1\"/><inertia ixx=\"1\" iyy=\"1\" izz=\"1\" ixy=\"0\" ixz=\"0\" "
         "iyz=\"0\"/></inertial>\n"
         "    <collision><geometry><mesh filename=\"" +
         collision +
         "\"/></geometry></collision>\n"
         "  </link>\n"
         "  <link name=\"cover\">\n"
         "    <visual><geometry><mesh filename=\"" +
         visual +
         "\"/></geometry></visual>\n"
         "  </link>\n"
         "  <joint name=\"j\" type=\"revolute\"><parent link=\"base\"/><child link=\"arm\"/>"
         "<axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>\n"
         "  <joint name=\"fixed\" type=\"fixed\"><parent link=\"arm\"/><child link=\"cover\"/></joint>\n"
         "</robot>\n";
}

using openplx::testing::cli;
using openplx::testing::Conversion;

// The names in `dir`, sorted.
std::vector<std::string> listing(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// A converted visual whose faces are inconsistent once its equal corners are merged (MuJoCo 2.2.2 refused
// it inline): --check passes, the written MJCF loads with the visual, as does `-o -`; --check leaves nothing
// of its own beside the output, and the MJCF written is the same with and without it.
TEST(MeshOrientation, ConvertedVisualWithInconsistentFacesPassesCheckAndLoads) {
  const ScratchDir dir;
  openplx::testing::write_tetrahedron(dir / "tetra.stl");
  write(dir / "box.stl", ascii_stl(5));
  write(dir / "box.ply", ascii_ply(2));
  for (const char* visual : {"box.stl", "box.ply"}) {
    SCOPED_TRACE(visual);
    write(dir / "r.urdf", robot(visual, "tetra.stl"));
    const fs::path out_dir = dir / "out";
    fs::remove_all(out_dir);
    fs::create_directories(out_dir);
    const Conversion checked =
        cli({(dir / "r.urdf").string(), "-o", (out_dir / "r.xml").string(), "--check"});
    ASSERT_EQ(checked.status, 0) << checked.errors;
    EXPECT_EQ(checked.errors.find("orientation"), std::string::npos) << checked.errors;
    EXPECT_EQ(listing(out_dir), (std::vector<std::string>{"r.meshes", "r.signals.json", "r.xml"}));
    EXPECT_EQ(listing(out_dir / "r.meshes"), (std::vector<std::string>{"box.stl"}));
    const std::string written = read(out_dir / "r.xml");
    EXPECT_NE(written.find("file=\"r.meshes/box.stl\""), std::string::npos) << written;
    {
      const Loaded model(out_dir / "r.xml");
      ASSERT_NE(model.m, nullptr) << model.error;
      EXPECT_GE(mj_name2id(model.m, mjOBJ_GEOM, "cover.visual_0"), 0);
    }
    const Conversion unchecked = cli({(dir / "r.urdf").string(), "-o", (out_dir / "r.xml").string()});
    ASSERT_EQ(unchecked.status, 0) << unchecked.errors;
    EXPECT_EQ(read(out_dir / "r.xml"), written);
    // On stdout, inline: checked as such, and it loads too.
    const Conversion inline_form = cli({(dir / "r.urdf").string(), "-o", "-", "--check"});
    ASSERT_EQ(inline_form.status, 0) << inline_form.errors;
    write(dir / "inline.xml", inline_form.out);
    const Loaded model(dir / "inline.xml");
    ASSERT_NE(model.m, nullptr) << model.error;
    EXPECT_GE(mj_name2id(model.m, mjOBJ_GEOM, "cover.visual_0"), 0);
  }
}

// A check that fails (a spring far too stiff for the time step: the simulation blows up) on a model with a
// converted mesh leaves the output's folder as it was: no MJCF, no mesh folder, none of the check's files.
TEST(MeshOrientation, FailedCheckLeavesNoFileBehind) {
  const ScratchDir dir;
  write(dir / "box.stl", ascii_stl(5));
  write(dir / "spring.openplx",
        "Box is Physics3D.Bodies.RigidBody:\n"
        "    inertia.mass: 1.0\n"
        "    geometry is Physics3D.Geometries.Box:\n"
        "        size: {0.1, 0.1, 0.1}\n"
        "    look is Visuals.Geometries.ExternalTriMeshGeometry:\n"
        "        path: @\"box.stl\"\n"
        "    bottom is Physics3D.Interactions.MateConnector:\n"
        "        main_axis: Math.Vec3.Z_AXIS()\n"
        "        normal: Math.Vec3.Y_AXIS()\n"
        "\n"
        "StiffSpring is Physics3D.System:\n"
        "    anchor is Physics3D.Interactions.MateConnector:\n"
        "        main_axis: Math.Vec3.Z_AXIS()\n"
        "        normal: Math.Vec3.Y_AXIS()\n"
        "    box is Box\n"
        "    slide is Physics3D.Interactions.Prismatic:\n"
        "        connectors: [anchor, box.bottom]\n"
        "        initial_position: 0.1\n"
        "    spring is Physics3D.Interactions.LinearSpring:\n"
        "        connectors: slide.connectors\n"
        "        flexibility.stiffness: 100000000.0\n"
        "        dissipation becomes Physics.Interactions.Dissipation.MechanicalDamping:\n"
        "            damping_constant: 0\n");
  fs::create_directories(dir / "out");
  const std::vector<std::string> args{(dir / "spring.openplx").string(), "-o",
                                      (dir / "out" / "s.xml").string(), "--timestep", "0.01"};
  const Conversion unchecked = cli(args);  // the model converts, with its mesh written beside it
  ASSERT_EQ(unchecked.status, 0) << unchecked.errors;
  EXPECT_TRUE(fs::is_regular_file(dir / "out" / "s.meshes" / "box.stl"));
  fs::remove_all(dir / "out");
  fs::create_directories(dir / "out");
  std::vector<std::string> checked = args;
  checked.push_back("--check");
  const Conversion r = cli(checked);
  EXPECT_EQ(r.status, openplx::cli::kExitInputError);
  EXPECT_NE(r.errors.find("[mjcf-unstable]"), std::string::npos) << r.errors;
  EXPECT_TRUE(fs::is_empty(dir / "out")) << ::testing::PrintToString(listing(dir / "out"));
}

// The line and column of `part` in `text`, as the diagnostics print them.
std::string line_and_column(const std::string& text, const std::string& part) {
  const size_t at = text.find(part);
  const size_t line_start = text.rfind('\n', at) + 1;
  const long line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(at), '\n');
  return std::to_string(line) + ":" + std::to_string(at - line_start + 1);
}

// An OBJ MuJoCo reads itself, one face flipped: as a visual it is left out with a warning at its <mesh>,
// and the written file loads; as a collision mesh it is an error there, and nothing is written.
TEST(MeshOrientation, InconsistentObjVisualIsLeftOutCollisionIsAnError) {
  const ScratchDir dir;
  openplx::testing::write_tetrahedron(dir / "tetra.stl");
  write(dir / "flipped.obj", obj(kTetra, "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 4 3\n"));
  const std::string problem =
      " cannot be a MuJoCo mesh: its faces have inconsistent orientation (MuJoCo 2.2.2 refuses it)";

  std::string urdf = robot("flipped.obj", "tetra.stl");
  write(dir / "r.urdf", urdf);
  const Conversion visual = cli({(dir / "r.urdf").string(), "-o", (dir / "r.xml").string(), "--check"});
  ASSERT_EQ(visual.status, 0) << visual.errors;
  EXPECT_NE(
      visual.errors.find((dir / "r.urdf").string() + ":" +
                         line_and_column(urdf, "<mesh filename=\"flipped.obj\"") + ": warning: mesh file " +
                         (dir / "flipped.obj").string() + " of `cover.visual_0.path`" + problem),
      std::string::npos)
      << visual.errors;
  EXPECT_NE(visual.errors.find("; this visual geometry was left out"), std::string::npos) << visual.errors;
  {
    const Loaded model(dir / "r.xml");
    ASSERT_NE(model.m, nullptr) << model.error;
    EXPECT_EQ(mj_name2id(model.m, mjOBJ_GEOM, "cover.visual_0"), -1);
    EXPECT_GE(mj_name2id(model.m, mjOBJ_GEOM, "arm.collision_0"), 0);
  }
  for (const char* written : {"r.xml", "r.signals.json"}) fs::remove(dir / written);

  urdf = robot("tetra.stl", "flipped.obj");
  write(dir / "r.urdf", urdf);
  const Conversion collision = cli({(dir / "r.urdf").string(), "-o", (dir / "r.xml").string()});
  EXPECT_EQ(collision.status, openplx::cli::kExitInputError);
  EXPECT_NE(
      collision.errors.find((dir / "r.urdf").string() + ":" +
                            line_and_column(urdf, "<mesh filename=\"flipped.obj\"") + ": error: mesh file " +
                            (dir / "flipped.obj").string() + " of `arm.collision_0.path`" + problem),
      std::string::npos)
      << collision.errors;
  for (const char* written : {"r.xml", "r.signals.json", "r.meshes"})
    EXPECT_FALSE(fs::exists(dir / written)) << written;
}

}  // namespace
