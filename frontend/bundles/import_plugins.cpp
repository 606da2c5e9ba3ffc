#include "frontend/bundles/import_plugins.h"

#include <algorithm>
#include <filesystem>

namespace openplx::frontend {

std::string lowercase_extension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

bool is_urdf_extension(const std::string& lowercase_extension) {
  return lowercase_extension == ".urdf" || lowercase_extension == ".xacro";
}

std::optional<std::string> import_plugin_source(const std::string& path, const std::string& model_name,
                                                std::string& error) {
  const std::string extension = lowercase_extension(path);
  // Path strings take no escapes, so a path with a quote cannot be written back as one.
  if (path.find('"') != std::string::npos || path.find('\n') != std::string::npos) {
    error = "cannot import a file whose path contains a quote or a newline: " + path;
    return std::nullopt;
  }
  if (extension == ".obj" || extension == ".stl") {
    // A mesh: a visual geometry reading the file (the Visuals bundle is always on the bundle path).
    return "`" + model_name + "` is Visuals.Geometries.ExternalTriMeshGeometry:\n    path: @\"" + path +
           "\"\n";
  }
  if (extension == ".png") {
    // An image: a texture reading the file (MuJoCo loads PNG textures itself).
    return "`" + model_name + "` is Visuals.Textures.Texture:\n    path: @\"" + path + "\"\n";
  }
  if (extension == ".jpg" || extension == ".jpeg") {
    error = "JPEG images cannot be imported: MuJoCo 2.2.2 reads PNG textures only; convert the image to PNG";
    return std::nullopt;
  }
  if (extension == ".agx") {
    error =
        "AGX archives (.agx) cannot be imported: they are a binary AGX Dynamics format with no OpenPLX or "
        "MuJoCo "
        "equivalent; export the model to OpenPLX or URDF instead";
    return std::nullopt;
  }
  error = "No plugin registered for extension '" + extension + "'";
  return std::nullopt;
}

}  // namespace openplx::frontend
