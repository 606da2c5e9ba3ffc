// Import plugins (spec §14): an imported asset file becomes one model type. Each plugin describes the asset
// as generated OpenPLX text, which the program reads like any other document.
#pragma once

#include <optional>
#include <string>

namespace openplx::frontend {

// The file name's extension in lower case (`.urdf` for `robot.URDF`): imports and inputs are told apart by
// it whatever case a file system or an exporter gave it.
std::string lowercase_extension(const std::string& path);

// Whether a file is read as a URDF: `.urdf`, or a xacro template (`.xacro`, `.urdf.xacro`), which the URDF
// import recognises and asks to be expanded first.
bool is_urdf_extension(const std::string& lowercase_extension);

// OpenPLX source declaring model `model_name` for the asset at `path` (absolute), or nullopt with `error`
// naming why the extension cannot be imported.
std::optional<std::string> import_plugin_source(const std::string& path, const std::string& model_name,
                                                std::string& error);

}  // namespace openplx::frontend
