// The mesh reader module (mesh_module_abi.h): a mesh file read with assimp into one triangle mesh, as
// mesh_conversion.h describes.
#include <assimp/DefaultIOSystem.h>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <sys/stat.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <map>
#include <new>
#include <string>
#include <vector>

#include "mjcf_emitter/mesh_conversion.h"
#include "mjcf_emitter/mesh_input_file.h"
#include "mjcf_emitter/mesh_module_abi.h"

namespace openplx::mjcf {
namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// Every file assimp opens, the mesh and whatever it names (glTF buffers, X3D inlines, ...), in any format,
// passes the checks the converter makes on the mesh (mesh_input_file.h); the first one refused is the
// problem when the read fails.
class CheckedFiles : public Assimp::DefaultIOSystem {
 public:
  // assimp's own opens the file to see it is there, which blocks on a FIFO.
  bool Exists(const char* file) const override {
    struct stat st {};
    return ::stat(file, &st) == 0;
  }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (std::string problem = mesh_input_file_problem(file); !problem.empty()) {
      if (refused_file_.empty()) {
        refused_file_ = file;
        refused_problem_ = problem;
      }
      return nullptr;
    }
    return DefaultIOSystem::Open(file, mode);
  }
  // Why the read failed when a file was refused: "" when none was.
  std::string refusal(const std::string& mesh) const {
    if (refused_file_.empty()) return {};
    if (refused_file_ == mesh) return "it " + refused_problem_;
    return "the file it names, " + refused_file_ + ", " + refused_problem_;
  }

 private:
  std::string refused_file_, refused_problem_;
};

Eigen::Matrix4d to_eigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d e;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) e(r, c) = m[r][c];
  return e;
}

// Past these the file is hostile or broken, not a robot part: deeper node trees than any exporter writes,
// and a bound on the walk, since a node tree a reader got wrong may share or loop back to its nodes.
constexpr size_t kMaxNodeDepth = 1024;
constexpr size_t kMaxNodeVisits = 1000000;

// Appends the triangles of `mesh` moved by `transform`. Indices are checked: a reader passes a file's face
// indices on as they are (a PLY's negative index arrives as a huge one).
std::string append_mesh(const aiMesh& mesh, const Eigen::Matrix4d& transform, TriangleMesh& out) {
  if (mesh.mNumVertices > 0 && !mesh.mVertices) return "a mesh of it has no vertex positions";
  const size_t first = out.vertices.size() / 3;
  if (first + mesh.mNumVertices > UINT32_MAX) return "it has more than 2^32 vertices";
  // A mirroring transform (negative determinant) turns triangles inside out; their corners are swapped back
  // so that MuJoCo's mesh volume stays positive.
  const bool mirrored = transform.topLeftCorner<3, 3>().determinant() < 0;
  for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
    const aiVector3D& p = mesh.mVertices[v];
    const Eigen::Vector4d moved = transform * Eigen::Vector4d(p.x, p.y, p.z, 1);
    for (int c = 0; c < 3; ++c) out.vertices.push_back(static_cast<float>(moved[c]));
  }
  for (unsigned f = 0; f < mesh.mNumFaces && mesh.mFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    if (face.mNumIndices != 3 || !face.mIndices) continue;  // points and lines (triangulation leaves these)
    for (int k = 0; k < 3; ++k) {
      if (face.mIndices[k] >= mesh.mNumVertices)
        return "a face names vertex " + std::to_string(face.mIndices[k]) + " of a mesh of " +
               std::to_string(mesh.mNumVertices) + " vertices";
    }
    const auto at = static_cast<uint32_t>(first);
    out.faces.push_back(at + face.mIndices[0]);
    out.faces.push_back(at + face.mIndices[mirrored ? 2 : 1]);
    out.faces.push_back(at + face.mIndices[mirrored ? 1 : 2]);
  }
  return {};
}

// Appends the triangles of every node under `root`, each mesh moved by its node's transform from the root.
// Walked with a stack of our own, not recursion: the depth is the file's to choose.
std::string collect(const aiScene& scene, const aiNode& root, const Eigen::Matrix4d& start,
                    TriangleMesh& out) {
  struct Visit {
    const aiNode* node;
    Eigen::Matrix4d parent;
    size_t depth;
  };
  std::vector<Visit> stack{{&root, start, 0}};
  for (size_t visits = 0; !stack.empty(); ++visits) {
    if (visits == kMaxNodeVisits)
      return "its node tree has more than " + std::to_string(kMaxNodeVisits) + " nodes";
    const Visit visit = std::move(stack.back());
    stack.pop_back();
    const aiNode& node = *visit.node;
    const Eigen::Matrix4d transform = visit.parent * to_eigen(node.mTransformation);
    for (unsigned k = 0; k < node.mNumMeshes; ++k) {
      if (node.mMeshes[k] >= scene.mNumMeshes || !scene.mMeshes[node.mMeshes[k]])
        return "a node names mesh " + std::to_string(node.mMeshes[k]) + " of " +
               std::to_string(scene.mNumMeshes);
      if (std::string problem = append_mesh(*scene.mMeshes[node.mMeshes[k]], transform, out);
          !problem.empty())
        return problem;
    }
    if (node.mNumChildren > 0 && visit.depth + 1 >= kMaxNodeDepth)
      return "its nodes nest more than " + std::to_string(kMaxNodeDepth) + " deep";
    // Children pushed last first, so the triangles come in the file's order, as a recursive walk gives them.
    for (unsigned k = node.mNumChildren; k-- > 0;)
      if (node.mChildren[k]) stack.push_back({node.mChildren[k], transform, visit.depth + 1});
  }
  return {};
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
  auto* files = new CheckedFiles;  // the importer owns it
  importer.SetIOHandler(files);
  // ROS tools take a COLLADA file's coordinates as written (RViz sets this too); assimp would turn Z_UP
  // files onto its own Y up. <unit meter> still scales the file (assimp's default, as RViz and Gazebo do).
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  // A file without meshes is an error here; assimp would draw its nodes as pyramids instead.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true);
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_SortByPType);
  if (!scene || !scene->mRootNode || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE)) {
    if (std::string refusal = files->refusal(path); !refusal.empty()) return refusal;
    std::string why = importer.GetErrorString();
    if (why == std::bad_alloc().what()) return OPENPLX_MESH_OUT_OF_MEMORY;  // assimp catches it itself
    return "the Open Asset Import Library cannot read it" + (why.empty() ? std::string() : " (" + why + ")");
  }
  Eigen::Matrix4d start = Eigen::Matrix4d::Identity();
  if (const std::string ext = lower_extension(path); ext == ".gltf" || ext == ".glb") {
    start.topLeftCorner<3, 3>() << 1, 0, 0, 0, 0, -1, 0, 1, 0;  // glTF's +Y up onto +Z, as RViz turns it
  }
  mesh = TriangleMesh{};
  if (std::string problem = collect(*scene, *scene->mRootNode, start, mesh); !problem.empty()) return problem;
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
  } catch (const std::bad_alloc&) {
    problem = OPENPLX_MESH_OUT_OF_MEMORY;
    mesh = openplx::mjcf::TriangleMesh{};  // what it holds is given back before the sink is called
  } catch (const std::exception& e) {      // nothing may cross the C interface; assimp throws on a few files
    problem = std::string("the Open Asset Import Library failed on it (") + e.what() + ")";
  }
  if (problem.empty()) {
    sink->mesh(sink->context, mesh.vertices.data(), mesh.vertices.size(), mesh.faces.data(),
               mesh.faces.size());
  } else {
    sink->problem(sink->context, problem.data(), problem.size());
  }
}
