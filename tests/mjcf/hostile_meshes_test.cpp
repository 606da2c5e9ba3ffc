// Mesh files made to break the reader, each brought as a user's robot brings one: a URDF naming it as a
// collision mesh. Every one is an error at the URDF's <mesh> with exit 1, and nothing is written, not even a
// temporary file: the reader runs in a child process with limits (mesh_reader_process.h), and the files a
// mesh names are checked before any reader opens them (mesh_references.h).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <csignal>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "mjcf_emitter/mesh_conversion.h"
#include "mjcf_emitter/mesh_input_file.h"
#include "mjcf_emitter/mesh_reader_process.h"
#include "mjcf_emitter/mesh_references.h"
#include "tests/support/cli_run.h"
#include "tests/support/scratch_dir.h"
#include "tools/cli/cli.h"

namespace {

namespace fs = std::filesystem;
namespace mj = openplx::mjcf;
using openplx::testing::ScratchDir;

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitized = true;
#elif defined(__has_feature)
constexpr bool kSanitized = __has_feature(address_sanitizer);
#else
constexpr bool kSanitized = false;
#endif

void write(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// The reproducers of issue 44, small.

// A COLLADA node that instances itself: assimp resolves it without end.
const char* const kSelfInstancingNode = R"(<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <library_visual_scenes><visual_scene id="s"><node id="n"><instance_node url="#n"/></node></visual_scene>
  </library_visual_scenes><scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
)";

// 10,000 <node>s, each inside the one before: assimp's parser recurses once per level.
std::string nested_nodes(int levels) {
  std::string nodes;
  for (int k = 0; k < levels; ++k) nodes += "<node>";
  for (int k = 0; k < levels; ++k) nodes += "</node>";
  return R"(<?xml version="1.0"?><COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">)"
         R"(<library_visual_scenes><visual_scene id="s">)" +
         nodes +
         R"(</visual_scene></library_visual_scenes><scene><instance_visual_scene url="#s"/></scene>)"
         "</COLLADA>\n";
}

// A PLY face with a negative vertex index, which assimp passes on as a huge unsigned one.
const char* const kNegativeFaceIndex =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 -100000000\n";

// A binary PLY that declares 8 vertices and holds 3, and no faces.
std::string short_binary_ply() {
  std::string bytes =
      "ply\nformat binary_little_endian 1.0\nelement vertex 8\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n";
  for (int k = 0; k < 9; ++k) {
    const float f = static_cast<float>(k);
    bytes.append(reinterpret_cast<const char*>(&f), 4);
  }
  return bytes;
}

// A glTF triangle whose buffer is `uri`.
std::string gltf_with_buffer(const std::string& uri) {
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
         R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
         R"("buffers":[{"byteLength":36,"uri":")" +
         uri +
         R"("}],"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36}],)"
         R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",)"
         R"("min":[0,0,0],"max":[1,1,1]}]})";
}

void make_fifo(const fs::path& path) {
  ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0) << path;
}

// Every file under `dir`, with its size, so that a file left behind (or grown) shows.
std::set<std::string> listing(const fs::path& dir) {
  std::set<std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    std::error_code ec;
    const auto size = entry.is_regular_file(ec) ? entry.file_size(ec) : 0;
    files.insert(entry.path().lexically_relative(dir).string() + " " + std::to_string(size));
  }
  return files;
}

// The URDF's <mesh> is on line 4, column 26.
std::string robot(const std::string& mesh, const char* role = "collision") {
  return std::string(R"(<robot name="r">
  <link name="a">
    <inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
    <)") +
         role + R"(><geometry><mesh filename=")" + mesh + R"("/></geometry></)" + role + R"(>
  </link>
</robot>
)";
}

using openplx::testing::cli;
using openplx::testing::Conversion;

// Converts a robot whose collision mesh is `mesh` (already in `dir`), to a file and to stdout: exit 1, the
// error at the <mesh> with `why`, and nothing written.
void expect_located_error(const ScratchDir& dir, const std::string& mesh, const std::string& why) {
  SCOPED_TRACE(mesh);
  write(dir / "robot.urdf", robot(mesh));
  const std::set<std::string> before = listing(dir.path());
  const Conversion r = cli({(dir / "robot.urdf").string(), "-o", (dir / "robot.xml").string()});
  EXPECT_EQ(r.status, 1) << r.errors;
  const std::string at = (dir / "robot.urdf").string() + ":4:26: error: mesh file " + (dir / mesh).string() +
                         " of `a.collision_0.path` cannot be a MuJoCo mesh: ";
  EXPECT_NE(r.errors.find(at), std::string::npos) << r.errors;
  EXPECT_NE(r.errors.find(why), std::string::npos) << r.errors;
  EXPECT_EQ(listing(dir.path()), before);
  const Conversion to_stdout = cli({(dir / "robot.urdf").string(), "-o", "-"});
  EXPECT_EQ(to_stdout.status, 1) << to_stdout.errors;
  EXPECT_EQ(to_stdout.out, "");
  EXPECT_EQ(listing(dir.path()), before);
}

TEST(HostileMeshes, SelfInstancingColladaNodeIsALocatedError) {
  const ScratchDir dir;
  write(dir / "self.dae", kSelfInstancingNode);
  expect_located_error(dir, "self.dae", "the mesh reader crashed on it (signal 11, SIGSEGV)");
}

TEST(HostileMeshes, TenThousandNestedColladaNodesAreALocatedError) {
  const ScratchDir dir;
  write(dir / "deep.dae", nested_nodes(10000));
  expect_located_error(dir, "deep.dae", "the mesh reader crashed on it (signal 11, SIGSEGV)");
}

TEST(HostileMeshes, NegativePlyFaceIndexIsALocatedError) {
  const ScratchDir dir;
  write(dir / "negative.ply", kNegativeFaceIndex);
  expect_located_error(dir, "negative.ply", "a face names vertex 4194967296 of a mesh of 4 vertices");
}

TEST(HostileMeshes, BinaryPlyShortOfItsVerticesIsALocatedError) {
  const ScratchDir dir;
  write(dir / "short.ply", short_binary_ply());
  expect_located_error(dir, "short.ply", "the Open Asset Import Library cannot read it");
}

TEST(HostileMeshes, GltfBufferThatIsAFifoIsALocatedError) {
  const ScratchDir dir;
  make_fifo(dir / "fifo.bin");
  write(dir / "fifo.gltf", gltf_with_buffer("fifo.bin"));
  expect_located_error(dir, "fifo.gltf", "the buffer it names, fifo.bin, is a FIFO, not a regular file");
}

// The same checks for every file a mesh names, however it names it.
TEST(HostileMeshes, EveryFileAMeshNamesIsChecked) {
  const ScratchDir dir;
  make_fifo(dir / "fifo.bin");
  write(dir / "absolute.gltf", gltf_with_buffer("file://" + (dir / "fifo.bin").string()));
  expect_located_error(dir, "absolute.gltf", ", is a FIFO, not a regular file");
  make_fifo(dir / "odd name.bin");
  write(dir / "encoded.gltf", gltf_with_buffer("odd%20name.bin"));
  expect_located_error(dir, "encoded.gltf", "the buffer it names, odd%20name.bin, is a FIFO");
  write(dir / "zero.gltf", gltf_with_buffer("/dev/zero"));
  expect_located_error(dir, "zero.gltf", "the buffer it names, /dev/zero, is a character device");
  write(dir / "proc.gltf", gltf_with_buffer("/proc/self/environ"));
  expect_located_error(dir, "proc.gltf", "lies in a kernel file system (proc)");
  // A sparse file: its size is what matters, and it takes no disk.
  std::ofstream(dir / "huge.bin").close();
  fs::resize_file(dir / "huge.bin", mj::kMaxMeshFileBytes + 1);
  write(dir / "huge.gltf", gltf_with_buffer("huge.bin"));
  expect_located_error(dir, "huge.gltf",
                       "the buffer it names, huge.bin, is 268435457 bytes, more than the 256 MiB");
  write(dir / "image.gltf", R"({"asset":{"version":"2.0"},"images":[{"uri":"fifo.bin"}]})");
  expect_located_error(dir, "image.gltf", "the image it names, fifo.bin, is a FIFO");
  write(dir / "image.dae", R"(<COLLADA><library_images><image id="i"><init_from>fifo.bin</init_from></image>
    </library_images></COLLADA>)");
  expect_located_error(dir, "image.dae", "the image it names, fifo.bin, is a FIFO");
}

// An OBJ goes to MuJoCo untouched, whose reader opens the material library it names: a FIFO there hangs
// MuJoCo's own load (reproduced with mujoco-compile), so it is refused as assimp's inputs are; an oversized
// or device OBJ likewise.
TEST(HostileMeshes, FilesMuJoCosOwnReaderOpensAreChecked) {
  const ScratchDir dir;
  make_fifo(dir / "fifo.mtl");
  write(dir / "m.obj",
        "mtllib fifo.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  expect_located_error(dir, "m.obj", "the material library it names, fifo.mtl, is a FIFO");
  std::ofstream(dir / "huge.obj").close();
  fs::resize_file(dir / "huge.obj", mj::kMaxMeshFileBytes + 1);
  expect_located_error(dir, "huge.obj", "it is 268435457 bytes, more than the 256 MiB");
}

// The mesh itself: a large sparse PLY, and one named through a link to a device.
TEST(HostileMeshes, TheMeshFileItselfIsChecked) {
  const ScratchDir dir;
  std::ofstream(dir / "huge.ply").close();
  fs::resize_file(dir / "huge.ply", mj::kMaxMeshFileBytes + 1);
  expect_located_error(dir, "huge.ply", "it is 268435457 bytes, more than the 256 MiB a mesh file may be");
  fs::create_symlink("/dev/zero", dir / "zero.ply");
  // assets.cpp finds no regular file there first.
  write(dir / "robot.urdf", robot("zero.ply"));
  const Conversion r = cli({(dir / "robot.urdf").string(), "-o", (dir / "robot.xml").string()});
  EXPECT_EQ(r.status, 1) << r.errors;
  EXPECT_NE(r.errors.find(":4:26: error: mesh file "), std::string::npos) << r.errors;
}

// A visual mesh only changes the look: the same files are a located warning, and the robot converts.
TEST(HostileMeshes, AVisualHostileMeshIsLeftOutWithAWarning) {
  const ScratchDir dir;
  write(dir / "self.dae", kSelfInstancingNode);
  write(dir / "robot.urdf", robot("self.dae", "visual"));
  const Conversion r = cli({(dir / "robot.urdf").string(), "-o", (dir / "robot.xml").string()});
  EXPECT_EQ(r.status, 0) << r.errors;
  EXPECT_NE(r.errors.find(":4:23: warning: mesh file "), std::string::npos) << r.errors;
  EXPECT_NE(r.errors.find("the mesh reader crashed on it"), std::string::npos) << r.errors;
  EXPECT_TRUE(fs::is_regular_file(dir / "robot.xml"));
}

// What the converter does not look into, the module's checks catch: glTF under a name assimp does not
// know is read by its content, and the FIFO its buffer names is refused where assimp opens it.
TEST(HostileMeshes, FilesAssimpOpensAreCheckedToo) {
  const ScratchDir dir;
  make_fifo(dir / "fifo.bin");
  write(dir / "part.shape", gltf_with_buffer("fifo.bin"));
  expect_located_error(
      dir, "part.shape",
      "the file it names, " + (dir / "fifo.bin").string() + ", is a FIFO, not a regular file");
}

// The child's failures, each worded as a problem with the file.
TEST(MeshReaderProcess, ACrashIsReported) {
  const mj::ChildRun run = mj::run_in_child([](int) { std::raise(SIGSEGV); }, {});
  EXPECT_EQ(run.failure, "the mesh reader crashed on it (signal 11, SIGSEGV)");
  const mj::ChildRun abort = mj::run_in_child([](int) { std::abort(); }, {});
  EXPECT_EQ(abort.failure, "the mesh reader crashed on it (signal 6, SIGABRT)");
}

TEST(MeshReaderProcess, AHangIsKilledAtTheDeadline) {
  const auto start = std::chrono::steady_clock::now();
  const mj::ChildRun blocked = mj::run_in_child([](int) { ::pause(); }, {1, 4096});
  EXPECT_EQ(blocked.failure, "the mesh reader took longer than 1 s on it");
  const mj::ChildRun busy = mj::run_in_child(
      [](int) {
        volatile uint64_t spins = 0;
        for (;;) spins = spins + 1;
      },
      {1, 4096});
  EXPECT_NE(busy.failure.find("the mesh reader took longer than 1 s"), std::string::npos) << busy.failure;
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
}

TEST(MeshReaderProcess, MemoryIsLimited) {
  if (kSanitized) GTEST_SKIP() << "no memory limit under sanitizers";
  const mj::ChildRun run = mj::run_in_child(
      [](int fd) {
        try {
          std::vector<char> block(size_t{1} << 30, 1);
          ::write(fd, "got it", 6);
        } catch (const std::bad_alloc&) {
          ::write(fd, "refused", 7);
        }
      },
      {10, 64});
  EXPECT_EQ(run.failure, "");
  EXPECT_EQ(run.output, "refused");
}

TEST(MeshReaderProcess, TheAnswerIsBounded) {
  // Under ASan the child's resident memory is watched against the same 2 MiB, and on a loaded machine its
  // sampled memory (shadow pages included) reached the bound first once in a full parallel run; the answer's
  // bound is the same code in every build, so it is checked where memory is not sampled.
  if (kSanitized)
    GTEST_SKIP() << "the child's memory is sampled under sanitizers and can reach the bound first";
  const mj::ChildRun run = mj::run_in_child(
      [](int fd) {
        // A small buffer written many times: the child's own memory stays far below the bound (under ASan,
        // where its resident memory is watched too, a 1 MiB block and its shadow reached it first).
        static const char block[1 << 16] = {};
        for (int k = 0; k < 48; ++k) ::write(fd, block, sizeof(block));
      },
      {10, 2});
  EXPECT_EQ(run.failure, "the mesh reader answered with more than 2 MiB");
}

TEST(MeshReaderProcess, AnExceptionEndsTheChildNotTheTest) {
  const mj::ChildRun run = mj::run_in_child([](int) { throw std::runtime_error("x"); }, {});
  EXPECT_EQ(run.failure, "the mesh reader failed on it (exit status 4)");
}

// A PLY that declares 100 million vertices: assimp asks for gigabytes, and the reader says it needed more.
TEST(MeshReaderProcess, AReaderOutOfMemoryIsSaidSo) {
  if (kSanitized) GTEST_SKIP() << "no memory limit under sanitizers";
  const ScratchDir dir;
  write(dir / "big.ply",
        "ply\nformat ascii 1.0\nelement vertex 100000000\nproperty float x\nproperty float y\n"
        "property float z\nend_header\n0 0 0\n");
  mj::TriangleMesh mesh;
  const std::string problem = mj::read_mesh_with_assimp((dir / "big.ply").string(), mesh, {true, {20, 64}});
  EXPECT_NE(problem.find("the mesh reader needed more than 64 MiB for it"), std::string::npos) << problem;
}

// A sound mesh reads the same in the child as in this process.
TEST(MeshReaderProcess, ASoundMeshReadsTheSameInTheChild) {
  const ScratchDir dir;
  write(dir / "box.ply",
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 4\nproperty list uchar int vertex_indices\nend_header\n"
        "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
  mj::TriangleMesh isolated, in_process;
  EXPECT_EQ(mj::read_mesh_with_assimp((dir / "box.ply").string(), isolated), "");
  EXPECT_EQ(mj::read_mesh_with_assimp((dir / "box.ply").string(), in_process, {false, {}}), "");
  EXPECT_EQ(isolated.vertices, in_process.vertices);
  EXPECT_EQ(isolated.faces, in_process.faces);
  EXPECT_EQ(isolated.triangle_count(), 4u);
}

// The names each format gives, and what is no file name.
TEST(MeshReferences, NamesAreFoundInEachFormat) {
  auto names = [](const std::string& ext, const std::string& bytes) {
    std::vector<std::string> out;
    for (const mj::MeshReference& r : mj::mesh_references(ext, bytes)) out.push_back(r.role + ":" + r.name);
    return out;
  };
  using V = std::vector<std::string>;
  EXPECT_EQ(names(".gltf", R"({"buffers":[{"uri":"a.bin","extras":{"uri":"no"}},{"byteLength":4}],
    "images":[{"uri":"i.png"}],"uri":"top","meshes":[{"uri":"no"}]})"),
            (V{"buffer:a.bin", "image:i.png"}));
  EXPECT_EQ(names(".gltf", R"({"buffers":{"b":{"uri":"v1.bin"}}})"), (V{"buffer:v1.bin"}));  // glTF 1
  EXPECT_EQ(names(".gltf", R"({"buffers":[{"uri":"a.bin"}], "images": [{"uri": )"), (V{"buffer:a.bin"}));
  EXPECT_EQ(names(".gltf", std::string(100000, '[')), V{});
  EXPECT_EQ(names(".dae", R"(<COLLADA><!-- <image><init_from>c.png</init_from></image> -->
    <library_images><image id="a" name="x>y"><init_from> a&amp;b.png </init_from></image>
    <image id="b"><init_from><ref>file:///t/b.png</ref></init_from></image></library_images>
    <library_effects><effect><newparam><surface><init_from>a</init_from></surface></newparam></effect>
    </library_effects></COLLADA>)"),
            (V{"image:a&b.png", "image:file:///t/b.png"}));
  EXPECT_EQ(names(".obj", "# mtllib no.mtl\nv 0 0 0\n  mtllib a.mtl  b.mtl\r\nmtllibx c\n"),
            (V{"material library:a.mtl", "material library:b.mtl"}));
  // A .glb's JSON chunk.
  std::string glb = "glTF";
  const std::string json = R"({"buffers":[{"uri":"g.bin"}]})";
  auto put = [&](uint32_t v) { glb.append(reinterpret_cast<const char*>(&v), 4); };
  put(2), put(static_cast<uint32_t>(20 + json.size())), put(static_cast<uint32_t>(json.size())),
      put(0x4E4F534A);
  EXPECT_EQ(names(".glb", glb + json), (V{"buffer:g.bin"}));
}

// MuJoCo's own OBJ reader opens the material library: a FIFO there would block it.
TEST(MeshReferences, ObjMaterialLibraryIsChecked) {
  const ScratchDir dir;
  make_fifo(dir / "fifo.mtl");
  write(dir / "part.obj", "mtllib missing.mtl fifo.mtl\nv 0 0 0\n");
  EXPECT_EQ(mj::mesh_references_problem((dir / "part.obj").string()),
            "the material library it names, fifo.mtl, is a FIFO, not a regular file");
  write(dir / "fine.obj", "mtllib missing.mtl\nv 0 0 0\n");
  EXPECT_EQ(mj::mesh_references_problem((dir / "fine.obj").string()), "");
  write(dir / "inline.gltf", gltf_with_buffer("data:application/octet-stream;base64,AAAA"));
  EXPECT_EQ(mj::mesh_references_problem((dir / "inline.gltf").string()), "");
}

}  // namespace
