// The mesh reader module (mesh_module_abi.h): a mesh file read with assimp into one triangle mesh, as
// mesh_conversion.h describes.
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

#include "mjcf_emitter/mesh_conversion.h"
#include "mjcf_emitter/mesh_module_abi.h"

namespace openplx::mjcf {
namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

Eigen::Matrix4d to_eigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d e;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) e(r, c) = m[r][c];
  return e;
}

// Appends the triangles of `node` and its children, each mesh moved by the node's transform from the root.
// A mirroring transform (negative determinant) turns triangles inside out; their corners are swapped back so
// that MuJoCo's mesh volume stays positive.
void collect(const aiScene& scene, const aiNode& node, const Eigen::Matrix4d& parent, TriangleMesh& out) {
  const Eigen::Matrix4d transform = parent * to_eigen(node.mTransformation);
  const bool mirrored = transform.topLeftCorner<3, 3>().determinant() < 0;
  for (unsigned k = 0; k < node.mNumMeshes; ++k) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[k]];
    const auto first = static_cast<uint32_t>(out.vertices.size() / 3);
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D& p = mesh.mVertices[v];
      const Eigen::Vector4d moved = transform * Eigen::Vector4d(p.x, p.y, p.z, 1);
      for (int c = 0; c < 3; ++c) out.vertices.push_back(static_cast<float>(moved[c]));
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines (triangulation leaves only these)
      out.faces.push_back(first + face.mIndices[0]);
      out.faces.push_back(first + face.mIndices[mirrored ? 2 : 1]);
      out.faces.push_back(first + face.mIndices[mirrored ? 1 : 2]);
    }
  }
  for (unsigned k = 0; k < node.mNumChildren; ++k) collect(scene, *node.mChildren[k], transform, out);
}

// One vertex per position, and none that no triangle uses: MuJoCo wraps every vertex in the convex hull it
// collides with, so a vertex left by a dropped line or point would widen it. Positions are merged only when
// equal (assimp's own joining merges vertices up to 1e-5 apart, which folds fine meshes into inconsistent
// ones MuJoCo refuses).
void merge_vertices(TriangleMesh& mesh) {
  std::map<std::array<float, 3>, uint32_t> index_of;
  std::vector<float> kept;
  for (uint32_t& index : mesh.faces) {
    std::array<float, 3> p;
    for (int c = 0; c < 3; ++c) p[c] = mesh.vertices[3 * index + c] + 0.0f;  // -0 and 0 are one position
    auto [it, added] = index_of.emplace(p, static_cast<uint32_t>(kept.size() / 3));
    if (added) kept.insert(kept.end(), p.begin(), p.end());
    index = it->second;
  }
  mesh.vertices = std::move(kept);
}

std::string read(const std::string& path, TriangleMesh& mesh) {
  Assimp::Importer importer;
  // ROS tools take a COLLADA file's coordinates as written (RViz sets this too); assimp would turn Z_UP
  // files onto its own Y up. <unit meter> still scales the file (assimp's default, as RViz and Gazebo do).
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_SortByPType);
  if (!scene || !scene->mRootNode || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE)) {
    std::string why = importer.GetErrorString();
    return "the Open Asset Import Library cannot read it" + (why.empty() ? std::string() : " (" + why + ")");
  }
  Eigen::Matrix4d start = Eigen::Matrix4d::Identity();
  if (const std::string ext = lower_extension(path); ext == ".gltf" || ext == ".glb") {
    start.topLeftCorner<3, 3>() << 1, 0, 0, 0, 0, -1, 0, 1, 0;  // glTF's +Y up onto +Z, as RViz turns it
  }
  mesh = TriangleMesh{};
  collect(*scene, *scene->mRootNode, start, mesh);
  if (mesh.faces.empty()) return "it holds no triangles (only points or lines, or nothing)";
  merge_vertices(mesh);
  return {};
}

}  // namespace
}  // namespace openplx::mjcf

extern "C" __attribute__((visibility("default"))) void openplx_read_mesh_v1(const char* path,
                                                                            const OpenplxMeshSink* sink) {
  openplx::mjcf::TriangleMesh mesh;
  std::string problem;
  try {
    problem = openplx::mjcf::read(path, mesh);
  } catch (const std::exception& e) {  // nothing may cross the C interface; assimp throws on a few files
    problem = std::string("the Open Asset Import Library failed on it (") + e.what() + ")";
  }
  if (problem.empty()) {
    sink->mesh(sink->context, mesh.vertices.data(), mesh.vertices.size(), mesh.faces.data(),
               mesh.faces.size());
  } else {
    sink->problem(sink->context, problem.data(), problem.size());
  }
}
