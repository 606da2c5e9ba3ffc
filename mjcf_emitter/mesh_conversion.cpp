#include "mjcf_emitter/mesh_conversion.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "frontend/platform/loadable_module.h"
#include "mjcf_emitter/mesh_input_file.h"
#include "mjcf_emitter/mesh_module_abi.h"
#include "mjcf_emitter/mesh_reader_process.h"
#include "mjcf_emitter/mesh_references.h"

namespace openplx::mjcf {
namespace {

namespace fs = std::filesystem;

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// This build's module, then the install prefix's.
std::vector<std::string> configured_paths() {
  std::vector<std::string> paths;
#ifdef OPENPLX_MESH_MODULE_BUILT
  paths.emplace_back(OPENPLX_MESH_MODULE_BUILT);
#endif
#ifdef OPENPLX_MESH_MODULE_INSTALLED
  paths.emplace_back(OPENPLX_MESH_MODULE_INSTALLED);
#endif
  return paths;
}

frontend::PluginSearch& module_search() {
  static frontend::PluginSearch search("libopenplx_meshes.so", configured_paths());
  return search;
}

struct LoadedModule {
  OpenplxReadMeshFunction read = nullptr;
  std::string error;
};

// Loaded on the first mesh that needs it, once per process.
const LoadedModule& loaded_module() {
  static const LoadedModule module = [] {
    LoadedModule m;
    const frontend::LoadableModule library =
        frontend::load_first_module("the mesh reader", module_search().file_name(),
                                    module_search().candidates(), frontend::Binding::Lazy);
    if (!library.handle)
      m.error = library.error;
    else
      library.find(OPENPLX_READ_MESH_SYMBOL, m.read, m.error);
    return m;
  }();
  return module;
}

void append_float(std::string& out, float value) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof(text), value).ptr;  // shortest that reads back
  out.append(text, end);
}

template <typename T>
void put(std::string& bytes, T value) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));  // little-endian, as STL is, on the platforms we build for
  bytes.append(raw, sizeof(T));
}

std::string stl_bytes(const TriangleMesh& mesh) {
  std::string bytes(80, '\0');  // an empty header: no date or name, the same bytes every run
  put(bytes, static_cast<uint32_t>(mesh.triangle_count()));
  for (size_t f = 0; f < mesh.faces.size(); f += 3) {
    std::array<Eigen::Vector3f, 3> corner;
    for (int k = 0; k < 3; ++k) corner[k] = Eigen::Vector3f(&mesh.vertices[3 * mesh.faces[f + k]]);
    const Eigen::Vector3f normal = (corner[1] - corner[0]).cross(corner[2] - corner[0]).normalized();
    for (int c = 0; c < 3; ++c) put(bytes, std::isfinite(normal[c]) ? normal[c] : 0.0f);
    for (const Eigen::Vector3f& p : corner)
      for (int c = 0; c < 3; ++c) put(bytes, p[c]);
    put(bytes, uint16_t{0});
  }
  return bytes;
}

// A triangle soup, as the inline form (vertex_text): MuJoCo's OBJ reader gives every triangle its own
// vertices anyway, but checks orientation on the file's shared ones.
std::string obj_bytes(const TriangleMesh& mesh) {
  std::string text;
  for (uint32_t corner : mesh.faces) {
    text += 'v';
    for (int c = 0; c < 3; ++c) (text += ' '), append_float(text, mesh.vertices[3 * corner + c]);
    text += '\n';
  }
  for (size_t f = 0; f < mesh.faces.size(); f += 3)
    text += "f " + std::to_string(f + 1) + ' ' + std::to_string(f + 2) + ' ' + std::to_string(f + 3) + '\n';
  return text;
}

}  // namespace

std::string collada_up_axis(const std::string& path) {
  if (lower_extension(path) != ".dae") return {};
  std::ifstream in(path, std::ios::binary);
  std::string head(1 << 16, '\0');  // <asset> comes first in a COLLADA document
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  const size_t open = head.find("<up_axis>");
  if (open == std::string::npos) return {};
  const size_t close = head.find("</up_axis>", open);
  if (close == std::string::npos) return {};
  std::string axis = head.substr(open + 9, close - open - 9);
  axis.erase(0, axis.find_first_not_of(" \t\r\n"));
  axis.erase(axis.find_last_not_of(" \t\r\n") + 1);
  return axis == "X_UP" || axis == "Y_UP" || axis == "Z_UP" ? axis : "";
}

void turn_up_axis_onto_z(TriangleMesh& mesh, const std::string& up) {
  for (size_t v = 0; v + 2 < mesh.vertices.size(); v += 3) {
    const float x = mesh.vertices[v], y = mesh.vertices[v + 1], z = mesh.vertices[v + 2];
    if (up == "Y_UP") {  // right +x stays, up +y -> +z, toward the viewer +z -> -y
      mesh.vertices[v + 1] = -z;
      mesh.vertices[v + 2] = y;
    } else if (up == "X_UP") {  // right -y -> +x, up +x -> +z, toward the viewer +z -> -y
      mesh.vertices[v] = -y;
      mesh.vertices[v + 1] = -z;
      mesh.vertices[v + 2] = x;
    }
  }
}

bool converted_with_assimp(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".obj" || ext == ".msh") return false;
  if (ext != ".stl") return true;
  std::ifstream in(path, std::ios::binary);
  char head[84] = {};
  in.read(head, sizeof(head));
  const std::streamsize got = in.gcount();
  std::error_code ec;
  const uintmax_t size = fs::file_size(path, ec);
  if (ec) return false;
  if (got == 84) {
    uint32_t triangles;
    std::memcpy(&triangles, head + 80, 4);
    if (size == 84 + 50 * static_cast<uintmax_t>(triangles)) return triangles > kMaxStlTriangles;
  }
  size_t at = 0;
  while (at < static_cast<size_t>(got) && std::isspace(static_cast<unsigned char>(head[at]))) ++at;
  return static_cast<size_t>(got) >= at + 5 && std::strncmp(head + at, "solid", 5) == 0;
}

void add_mesh_module_candidate(const std::string& path) {
  module_search().add(path);
}

std::string read_mesh_with_assimp(const std::string& path, TriangleMesh& mesh, const MeshReading& how) {
  mesh = TriangleMesh{};
  // The files are checked here, before the reader opens any; the module checks what assimp opens again.
  if (std::string problem = mesh_input_file_problem(path); !problem.empty()) return "it " + problem;
  if (std::string problem = mesh_references_problem(path); !problem.empty()) return problem;
  const LoadedModule& module = loaded_module();  // loaded here, before the child is forked
  if (!module.read) return module.error;
  return how.isolated ? read_mesh_in_child(module.read, path, mesh, how.limits)
                      : read_mesh_in_process(module.read, path, mesh);
}

// Each triangle with its own three vertices, as MuJoCo 2.2.2's STL reader gives it: that reader meets no
// shared edge, so it never finds faces of inconsistent orientation, which the inline form (and OBJ) would
// refuse. Mass and inertia come from the triangles alone, so they are the same.
std::string vertex_text(const TriangleMesh& mesh) {
  std::string text;
  text.reserve(mesh.faces.size() * 30);
  for (size_t k = 0; k < mesh.faces.size(); ++k) {
    for (int c = 0; c < 3; ++c) {
      if (k || c) text += ' ';
      append_float(text, mesh.vertices[3 * mesh.faces[k] + c]);
    }
  }
  return text;
}

std::string face_text(const TriangleMesh& mesh) {
  std::string text;
  text.reserve(mesh.faces.size() * 8);
  for (size_t k = 0; k < mesh.faces.size(); ++k) {
    if (k) text += ' ';
    text += std::to_string(k);
  }
  return text;
}

const char* mesh_file_extension(const TriangleMesh& mesh) {
  return mesh.triangle_count() <= kMaxStlTriangles ? ".stl" : ".obj";
}

std::string mesh_file_bytes(const TriangleMesh& mesh) {
  return mesh.triangle_count() <= kMaxStlTriangles ? stl_bytes(mesh) : obj_bytes(mesh);
}

}  // namespace openplx::mjcf
