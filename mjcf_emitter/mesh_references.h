// The files a mesh file names beside itself, checked as the mesh is (mesh_input_file.h) before any reader
// opens them: glTF buffers and images (a .gltf, or the JSON chunk of a .glb), COLLADA images (<image>'s
// <init_from>), OBJ material libraries (mtllib, which MuJoCo's own OBJ reader opens). A name that is no file
// here (missing, a URL, data: inline) is left to the reader. Other formats' references are not read here: the
// mesh reader module checks every file assimp opens (mesh_module.cpp), and reads in a child process with
// time and memory limits (mesh_reader_process.h).
#pragma once

#include <string>
#include <vector>

namespace openplx::mjcf {

// A file a mesh names: what it is to the mesh ("buffer", "image", "material library") and its name as
// written (a relative or absolute path, or a URI).
struct MeshReference {
  std::string role;
  std::string name;
};

// The references in a mesh file's bytes, by the format `ext` names (".gltf", ".glb", ".dae" or ".obj", in
// lower case; none for others). Damaged text yields what could be read before the damage.
std::vector<MeshReference> mesh_references(const std::string& ext, const std::string& bytes);

// Why a file the mesh file at `path` names must not be read ("the buffer it names, fifo.bin, is a FIFO, not
// a regular file"); empty when none. The mesh file itself must have passed mesh_input_file_problem.
std::string mesh_references_problem(const std::string& path);

}  // namespace openplx::mjcf
