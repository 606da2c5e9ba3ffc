// The body of the mesh fuzz target: the bytes as a mesh file, in the format they look like (COLLADA, PLY,
// glTF, .glb, STL, else OBJ), read as the converter reads a mesh a robot names: the checks of the file and
// the files it names, assimp in a child process, the solid checks; OBJ and binary STL through the checks
// made before MuJoCo reads them. Beside the file lie the files seeds and reproducers name: a sound buffer,
// material library and image, and hostile ones (a FIFO, a folder, /dev/zero, a 257 MiB sparse file).
// Shared by the libFuzzer entry point and the regression test.
#pragma once

#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "mjcf_emitter/asset_file_checks.h"
#include "mjcf_emitter/mesh_conversion.h"
#include "mjcf_emitter/mesh_input_file.h"
#include "mjcf_emitter/mesh_references.h"

namespace openplx::fuzz {

// The tetrahedron of the seeds' external buffer: 4 float vertices, then 12 uint16 indices (72 bytes).
inline std::string tetrahedron_buffer() {
  const float vertices[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const uint16_t indices[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  return std::string(reinterpret_cast<const char*>(vertices), sizeof(vertices)) +
         std::string(reinterpret_cast<const char*>(indices), sizeof(indices));
}

// The files beside the mesh, made once per folder.
inline void prepare_mesh_neighbours(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(dir / "tetrahedron.bin", ec)) return;
  std::ofstream(dir / "tetrahedron.bin", std::ios::binary) << tetrahedron_buffer();
  std::ofstream(dir / "tetrahedron.mtl") << "newmtl grey\nKd 0.5 0.5 0.5\n";
  std::ofstream(dir / "texture.png", std::ios::binary) << "\x89PNG\r\n\x1a\n";
  ::mkfifo((dir / "fifo.bin").c_str(), 0600);
  ::mkfifo((dir / "fifo.mtl").c_str(), 0600);
  fs::create_directory(dir / "folder.bin", ec);
  fs::create_symlink("/dev/zero", dir / "zero.bin", ec);
  std::ofstream(dir / "huge.bin").close();
  fs::resize_file(dir / "huge.bin", openplx::mjcf::kMaxMeshFileBytes + (1 << 20), ec);
}

// The extension of the format the bytes look like.
inline const char* mesh_extension(std::string_view bytes) {
  const std::string_view head = bytes.substr(0, 4096);
  const size_t first = head.find_first_not_of(" \t\r\n");
  const std::string_view text = first == std::string_view::npos ? std::string_view() : head.substr(first);
  if (head.substr(0, 4) == "glTF") return ".glb";
  if (head.substr(0, 3) == "ply") return ".ply";
  if (text.substr(0, 1) == "<") return ".dae";
  if (text.substr(0, 1) == "{") return ".gltf";
  if (text.substr(0, 5) == "solid") return ".stl";
  if (bytes.size() >= 84) {
    uint32_t triangles;
    std::memcpy(&triangles, bytes.data() + 80, 4);
    if (bytes.size() == 84 + 50 * static_cast<uint64_t>(triangles)) return ".stl";
  }
  return ".obj";
}

// Reads the bytes as a mesh in `dir`; what the converter would say of it ("" when it is a sound mesh).
inline std::string mesh_one(const uint8_t* data, size_t size, const std::filesystem::path& dir) {
  namespace mj = openplx::mjcf;
  prepare_mesh_neighbours(dir);
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const std::string path = (dir / (std::string("mesh") + mesh_extension(bytes))).string();
  std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(size));
  std::string problem;
  if (mj::converted_with_assimp(path)) {
    // A second's limit: a slow read is a problem, not a libFuzzer timeout (tools/fuzz.sh gives 2 s).
    const mj::MeshReading isolated{true, {1, 1024}};
    mj::TriangleMesh mesh;
    const auto start = std::chrono::steady_clock::now();
    problem = mj::read_mesh_with_assimp(path, mesh, isolated);
    const bool quick = std::chrono::steady_clock::now() - start < std::chrono::milliseconds(300);
    // A file the child read without failing, read again in this process: libFuzzer sees the module's
    // coverage, the sanitizers its faults, and both reads must agree.
    if (quick && problem.rfind("the mesh reader ", 0) != 0) {
      mj::TriangleMesh again;
      const std::string in_process = mj::read_mesh_with_assimp(path, again, {false, {}});
      if (in_process != problem || again.vertices != mesh.vertices || again.faces != mesh.faces) {
        std::fprintf(stderr, "the child read \"%s\", this process \"%s\"\n", problem.c_str(),
                     in_process.c_str());
        std::abort();
      }
    }
    if (problem.empty()) problem = mj::converted_mesh_problem(mesh);
    if (problem.empty()) mj::mesh_file_bytes(mesh);
  } else {
    problem = mj::mesh_input_file_problem(path);
    if (problem.empty()) problem = mj::mesh_references_problem(path);
    if (problem.empty()) problem = mj::mesh_file_problem(path);
  }
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
  return problem;
}

}  // namespace openplx::fuzz
