#include "mjcf_emitter/mesh_files.h"

#include <cctype>
#include <filesystem>
#include <map>
#include <set>

namespace openplx::mjcf {
namespace {

namespace fs = std::filesystem;

// A file name of letters, digits, '-', '_' and '.', whatever the source was called.
std::string safe_stem(const std::string& source) {
  std::string stem = fs::path(source).stem().string();
  for (char& c : stem) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') c = '_';
  }
  return stem.empty() || stem[0] == '.' ? "mesh" + stem : stem;
}

Element* mesh_asset(Element& document, const std::string& name) {
  Element* assets = document.child("asset");
  if (!assets) return nullptr;
  for (auto& child : assets->children()) {
    const std::string* n = child->get("name");
    if (child->name() == "mesh" && n && *n == name) return child.get();
  }
  return nullptr;
}

}  // namespace

std::string mesh_folder_for(const std::string& output) {
  fs::path path(output);
  if (path.extension() == ".xml") path.replace_extension();
  return path.filename().string() + ".meshes";
}

std::vector<MeshFile> move_meshes_to_files(Emitted& emitted, const std::string& folder) {
  std::vector<MeshFile> files;
  std::map<const TriangleMesh*, std::string> file_of;  // one file per source mesh
  std::set<std::string> taken;
  for (const ConvertedMesh& converted : emitted.converted_meshes) {
    auto [it, added] = file_of.emplace(converted.mesh.get(), std::string());
    if (added) {
      const std::string stem = safe_stem(converted.source), ext = mesh_file_extension(*converted.mesh);
      std::string name = stem + ext;
      for (int n = 2; !taken.insert(name).second; ++n) name = stem + "_" + std::to_string(n) + ext;
      it->second = folder + "/" + name;
      files.push_back({it->second, mesh_file_bytes(*converted.mesh)});
    }
    if (Element* mesh = mesh_asset(emitted.document, converted.asset)) {
      mesh->erase("vertex").erase("face");
      mesh->set("file", it->second);
    }
  }
  emitted.converted_meshes.clear();
  return files;
}

void move_mesh_folder(Element& document, std::vector<MeshFile>& files, const std::string& folder) {
  std::map<std::string, std::string> moved;  // a file's path -> its path under `folder`
  for (MeshFile& file : files) {
    std::string to = folder + "/" + fs::path(file.path).filename().string();
    moved.emplace(file.path, to);
    file.path = std::move(to);
  }
  Element* assets = document.child("asset");
  if (!assets) return;
  for (auto& child : assets->children()) {
    const std::string* file = child->get("file");
    if (child->name() != "mesh" || !file) continue;
    if (auto it = moved.find(*file); it != moved.end()) child->set("file", it->second);
  }
}

}  // namespace openplx::mjcf
