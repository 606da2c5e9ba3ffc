// Every file openplx2mjcf and openplx-sim write (MJCF, manifest, mesh folder, depfile, CSV) as one rule
// (tools/cli/output_set.h): never a file the run read, found by identity rather than by name; and all of
// them or none, with what was there before left as it was.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "mjcf_emitter/mesh_files.h"
#include "tests/support/cli_run.h"
#include "tests/support/scratch_dir.h"
#include "tests/support/tetrahedron_stl.h"
#include "tools/sim/sim.h"

namespace {

namespace fs = std::filesystem;
using openplx::testing::cli;
using openplx::testing::Conversion;
using openplx::testing::ScratchDir;

void write(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Every file and folder under `dir`, by relative path: a file's bytes, "<dir>" for a folder.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    const std::string name = fs::relative(entry.path(), dir).string();
    files[name] = entry.is_directory() ? "<dir>" : read(entry.path());
  }
  return files;
}

constexpr const char* kAsciiTetrahedron =
    "solid t\n"
    " facet normal 0 0 0\n  outer loop\n   vertex 0 0 0\n   vertex 0 0.1 0\n   vertex 0.1 0 0\n  endloop\n"
    " endfacet\n"
    " facet normal 0 0 0\n  outer loop\n   vertex 0 0 0\n   vertex 0.1 0 0\n   vertex 0 0 0.1\n  endloop\n"
    " endfacet\n"
    " facet normal 0 0 0\n  outer loop\n   vertex 0 0 0\n   vertex 0 0 0.1\n   vertex 0 0.1 0\n  endloop\n"
    " endfacet\n"
    " facet normal 0 0 0\n  outer loop\n   vertex 0.1 0 0\n   vertex 0 0.1 0\n   vertex 0 0 0.1\n  endloop\n"
    " endfacet\n"
    "endsolid t\n";

// The inputs of the cases: m.openplx imports part.openplx; u.openplx imports r.urdf, whose link draws m.stl;
// s.openplx draws an ASCII STL kept at out.meshes/a.stl, where -o out.xml would put its converted copy.
struct Inputs {
  ScratchDir dir;
  Inputs() {
    write(dir / "part.openplx", "Part is Physics3D.Bodies.RigidBody:\n    inertia.mass: 2.0\n");
    write(dir / "m.openplx", "import @\"part.openplx\"\n\nScene is Physics3D.System:\n    body is Part\n");
    write(dir / "r.urdf",
          "<robot name=\"r\">\n  <link name=\"base\">\n    <inertial><mass value=\"1\"/>"
          "<inertia ixx=\"0.1\" iyy=\"0.1\" izz=\"0.1\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial>\n"
          "    <visual><geometry><mesh filename=\"m.stl\"/></geometry></visual>\n  </link>\n</robot>\n");
    openplx::testing::write_tetrahedron(dir / "m.stl");
    write(dir / "u.openplx", "import @\"r.urdf\"\n\nRobot is r:\n    base.inertia.mass: 2.0\n");
    write(dir / "out.meshes/a.stl", kAsciiTetrahedron);
    write(dir / "s.openplx",
          "Scene is Physics3D.System:\n    body is Physics3D.Bodies.RigidBody:\n"
          "        inertia.mass: 1.0\n"
          "        shape is Physics3D.Geometries.ExternalTriMeshGeometry:\n"
          "            path: @\"out.meshes/a.stl\"\n");
  }
  std::string operator/(const std::string& name) const { return (dir / name).string(); }
};

// A refusal: exit 1, reported at `where` ("FILE: error: ..."), and not a byte changed or added.
void expect_refused(const Inputs& in, const std::vector<std::string>& args, const std::string& where) {
  SCOPED_TRACE(::testing::PrintToString(args));
  const auto before = snapshot(in.dir.path());
  const Conversion r = cli(args);
  EXPECT_EQ(r.status, 1) << r.errors;
  EXPECT_NE(r.errors.find(where + ": error: refusing to write"), std::string::npos) << r.errors;
  EXPECT_EQ(snapshot(in.dir.path()), before);
}

TEST(OutputFiles, NeverOverAFileTheRunRead) {
  const Inputs in;
  expect_refused(in, {in / "m.openplx", "-o", in / "out.xml", "--depfile", in / "m.openplx"},
                 in / "m.openplx");
  expect_refused(in, {in / "m.openplx", "-o", in / "out.xml", "--depfile", in / "part.openplx"},
                 in / "part.openplx");
  expect_refused(in, {in / "m.openplx", "-o", in / "part.openplx"}, in / "part.openplx");
  expect_refused(in, {in / "u.openplx", "-o", in / "r.urdf"}, in / "r.urdf");
  expect_refused(in, {in / "r.urdf", "-o", in / "m.stl"}, in / "m.stl");
  expect_refused(in, {in / "s.openplx", "-o", in / "out.xml"}, in / "out.meshes/a.stl");
  // Identity, not name: the imported file reached through another spelling and through a hard link.
  fs::create_directory(in.dir / "x");
  expect_refused(in, {in / "m.openplx", "-o", (in.dir / "." / "x" / ".." / "part.openplx").string()},
                 (in.dir / "." / "x" / ".." / "part.openplx").string());
  fs::create_hard_link(in.dir / "part.openplx", in.dir / "link.openplx");
  expect_refused(in, {in / "m.openplx", "-o", in / "link.openplx"}, in / "link.openplx");
}

TEST(OutputFiles, NoTwoOutputsAreOneFile) {
  const Inputs in;
  expect_refused(in, {in / "m.openplx", "-o", in / "out.xml", "--depfile", in / "out.xml"}, in / "out.xml");
  expect_refused(in, {in / "m.openplx", "-o", in / "out.xml", "--depfile", in / "out.signals.json"},
                 in / "out.signals.json");
}

TEST(OutputFiles, SimCsvNeverOverAnImport) {
  const Inputs in;
  const auto before = snapshot(in.dir.path());
  std::ostringstream out, err;
  EXPECT_EQ(
      openplx::sim::run_sim({in / "m.openplx", "--time", "0.01", "--csv", in / "part.openplx"}, out, err), 1);
  EXPECT_NE(err.str().find(in / "part.openplx" + ": error: refusing to write --csv"), std::string::npos)
      << err.str();
  EXPECT_EQ(snapshot(in.dir.path()), before);
  // Written, it is whole and alone: no temporary beside it.
  ASSERT_EQ(openplx::sim::run_sim({in / "m.openplx", "--time", "0.01", "--csv", in / "t.csv"}, out, err), 0)
      << err.str();
  EXPECT_EQ(read(in.dir / "t.csv").rfind("time\n", 0), 0u);
  EXPECT_EQ(snapshot(in.dir.path()).size(), before.size() + 1);
}

TEST(OutputFiles, AllOrNothing) {
  const Inputs in;
  // The manifest's place is a folder: neither the MJCF nor its mesh folder is left.
  fs::create_directory(in.dir / "o.signals.json");
  auto before = snapshot(in.dir.path());
  Conversion r = cli({in / "s.openplx", "-o", in / "o.xml"});
  EXPECT_EQ(r.status, 1) << r.errors;
  EXPECT_NE(r.errors.find(in / "o.signals.json" + ": error: is a directory"), std::string::npos) << r.errors;
  EXPECT_EQ(snapshot(in.dir.path()), before);
  fs::remove(in.dir / "o.signals.json");
  // A depfile in a folder that does not exist: no MJCF, no manifest, no meshes.
  before = snapshot(in.dir.path());
  r = cli({in / "s.openplx", "-o", in / "o.xml", "--depfile", in / "nodir/dep.d"});
  EXPECT_EQ(r.status, 1) << r.errors;
  EXPECT_NE(r.errors.find(in / "nodir/dep.d" + ": error:"), std::string::npos) << r.errors;
  EXPECT_EQ(snapshot(in.dir.path()), before);
  // Outputs of an earlier run stay as they were when the next one fails.
  ASSERT_EQ(cli({in / "s.openplx", "-o", in / "o.xml", "--depfile", in / "o.d"}).status, 0);
  before = snapshot(in.dir.path());
  r = cli({in / "s.openplx", "-o", in / "o.xml", "--prefix", "p/", "--depfile", in / "nodir/dep.d"});
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(snapshot(in.dir.path()), before);
}

// For random (inputs, output options) pairs drawn from the cases above: no input's bytes change, and either
// every output is there (and nothing else new) or the folder is exactly as it was.
TEST(OutputFiles, PropertyInputsKeptOutputsAllOrNone) {
  struct Model {
    const char* file;
    std::vector<std::string> reads;
    bool meshes;  // converted meshes go to OUT.meshes/
  };
  const std::vector<Model> models{{"m.openplx", {"m.openplx", "part.openplx"}, false},
                                  {"u.openplx", {"u.openplx", "r.urdf", "m.stl"}, false},
                                  {"r.urdf", {"r.urdf", "m.stl"}, false},
                                  {"s.openplx", {"s.openplx", "out.meshes/a.stl"}, true}};
  const std::vector<std::string> outputs{"out.xml",   "o.xml", "part.openplx", "r.urdf",     "m.stl",
                                         "m.openplx", "u.xml", "nodir/o.xml",  "we ird.xml", "s.openplx"};
  const std::vector<std::string> depfiles{
      "",       "dep.d",   "m.openplx", "part.openplx", "out.xml", "o.xml", "out.signals.json", "nodir/dep.d",
      "r.urdf", "a:b#$.d", "m.stl"};
  std::mt19937 random(46);
  int written_all = 0, refused = 0;
  for (int draw = 0; draw < 200; ++draw) {
    const Model& model = models[random() % models.size()];
    const std::string output = outputs[random() % outputs.size()];
    const std::string depfile = depfiles[random() % depfiles.size()];
    const bool manifest_is_folder = random() % 5 == 0, old_outputs = random() % 3 == 0;
    SCOPED_TRACE("draw " + std::to_string(draw) + ": " + model.file + " -o " + output + " --depfile '" +
                 depfile + "'" + (manifest_is_folder ? " (manifest a folder)" : "") +
                 (old_outputs ? " (old outputs)" : ""));
    const Inputs in;
    const std::string manifest = openplx::cli::manifest_path(output);
    std::vector<std::string> written{output, manifest};
    if (!depfile.empty()) written.push_back(depfile);
    if (model.meshes) written.push_back(openplx::mjcf::mesh_folder_for(output) + "/a.stl");
    if (old_outputs) {
      for (const std::string& w : written) {
        if (!fs::exists(in.dir / w) && fs::is_directory((in.dir / w).parent_path()))
          write(in.dir / w, "old\n");
      }
    }
    if (manifest_is_folder && !fs::exists(in.dir / manifest)) fs::create_directories(in.dir / manifest);
    const auto before = snapshot(in.dir.path());
    std::vector<std::string> args{in / model.file, "-o", in / output};
    if (!depfile.empty()) args.insert(args.end(), {"--depfile", in / depfile});
    const Conversion r = cli(args);
    const auto after = snapshot(in.dir.path());
    for (const std::string& input : model.reads) EXPECT_EQ(after.at(input), before.at(input)) << input;
    if (r.status != 0) {
      ++refused;
      EXPECT_EQ(after, before) << r.errors;
      continue;
    }
    ++written_all;
    for (const std::string& w : written) EXPECT_TRUE(after.count(w) && after.at(w) != "<dir>") << w;
    for (const auto& [name, bytes] : after) {
      const bool is_output = std::find(written.begin(), written.end(), name) != written.end() ||
                             (model.meshes && name == fs::path(written.back()).parent_path().string());
      if (is_output) continue;
      EXPECT_TRUE(before.count(name) && before.at(name) == bytes) << name << " is new or changed";
    }
  }
  // Both sides of the property were exercised.
  EXPECT_GT(written_all, 20);
  EXPECT_GT(refused, 20);
}

}  // namespace
