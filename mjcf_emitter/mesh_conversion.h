// Mesh files MuJoCo 2.2.2 cannot read (COLLADA .dae, .ply, .gltf/.glb, .3ds, .fbx, .off, ASCII STL, ...) read
// with the Open Asset Import Library (assimp) into one triangle mesh, which the emitter gives MuJoCo inline
// (<mesh vertex face>) or as a file it reads (mesh_files.h). Files MuJoCo reads itself (OBJ, MSH, binary STL
// of up to 200000 triangles) are left to it: its own reader then computes the same mesh volumes as its URDF
// importer does, which mass parity depends on.
//
// How a file is read follows how ROS tools show it (RViz 2's assimp loader, Gazebo classic's COLLADA loader):
// every node transform is baked into the vertices (all the file's meshes merged into one), points and lines
// are dropped, polygons triangulated; COLLADA's <unit meter> scales the file to metres; glTF's Y up is turned
// onto Z, as RViz does. COLLADA's <up_axis> is read by the emitter (collada_up_axis below), not by assimp
// (which would turn a Z_UP file onto its own Y up).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace openplx::mjcf {

// A mesh as MuJoCo holds one: x y z of each vertex as 32-bit floats (the precision of MuJoCo's mesh readers,
// so the inline form, a written STL and a written OBJ give MuJoCo the same vertices) and three 0-based vertex
// indices per triangle.
struct TriangleMesh {
  std::vector<float> vertices;
  std::vector<uint32_t> faces;
  size_t triangle_count() const { return faces.size() / 3; }
};

// MuJoCo 2.2.2 reads at most this many triangles from an STL file.
inline constexpr size_t kMaxStlTriangles = 200000;

// Whether the file goes through assimp: any extension but .obj, .msh and .stl (compared case-insensitively),
// and an .stl that is ASCII (begins with `solid` and its size is no binary STL's) or binary with more than
// kMaxStlTriangles triangles. Other .obj, .msh and .stl files go to MuJoCo unchanged, checked first by
// asset_file_checks.h (a damaged binary STL is diagnosed there as such).
bool converted_with_assimp(const std::string& path);

// The limits of one mesh read (mesh_reader_process.h): past them the file is reported, not read.
struct MeshReaderLimits {
  unsigned seconds = 60;       // wall-clock time, and CPU time
  uint64_t memory_mib = 4096;  // address space the reader may add to the process's
};

// How read_mesh_with_assimp reads: in a child process within `limits`, or in this process (only for the
// fuzz target's second pass over a file a child read without failing).
struct MeshReading {
  bool isolated = true;
  MeshReaderLimits limits;
};

// Reads the file at `path` with assimp into `mesh`; empty on success, else why it cannot be read: the file
// or one it names must not be read (mesh_input_file.h, mesh_references.h), assimp's message, "it holds no
// triangles", the reader crashed, took too long or needed too much memory (mesh_reader_process.h), or why
// the reader module is missing. The mesh is not yet checked for being a solid (asset_file_checks.h). assimp
// lives in a module loaded on the first call (mesh_module_abi.h), found beside the executable
// (../lib/openplx2mjcf/), in the build, in the install prefix, or at a path registered here first (a package
// that installs it elsewhere).
std::string read_mesh_with_assimp(const std::string& path, TriangleMesh& mesh, const MeshReading& how = {});
void add_mesh_module_candidate(const std::string& path);

// The <up_axis> a COLLADA file declares ("X_UP", "Y_UP" or "Z_UP"), or "" when it is none or declares none
// (COLLADA's default is Y_UP, but files without one are written by tools that mean Z as a URDF does).
std::string collada_up_axis(const std::string& path);

// Turns a mesh so that the up axis `up` ("X_UP" or "Y_UP") becomes +Z, as COLLADA defines its axes
// (Y_UP: x right, y up, z toward the viewer; X_UP: -y right, x up, z toward the viewer; Z_UP: x right,
// z up, -y toward the viewer). A right-handed turn: volumes and face orientation are kept.
void turn_up_axis_onto_z(TriangleMesh& mesh, const std::string& up);

// The inline MJCF attributes <mesh vertex="..." face="...">: shortest text that reads back to the same
// floats, every triangle with its own three vertices, as MuJoCo 2.2.2 reads a binary STL (it checks face
// orientation only on shared vertices, so a written STL would load where a shared inline mesh would not).
std::string vertex_text(const TriangleMesh& mesh);
std::string face_text(const TriangleMesh& mesh);

// The mesh as a file MuJoCo 2.2.2 reads: binary STL when it has at most kMaxStlTriangles triangles, else OBJ
// (every triangle with its own vertices, as inline).
// The bytes depend on the mesh only (no date, no name), so the same input writes the same file.
const char* mesh_file_extension(const TriangleMesh& mesh);  // ".stl" or ".obj"
std::string mesh_file_bytes(const TriangleMesh& mesh);

}  // namespace openplx::mjcf
