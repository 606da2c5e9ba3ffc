// Import plugins (spec §14): an imported asset file becomes one model type. Each plugin describes the asset
// as generated OpenPLX text, which the program reads like any other document.
#pragma once

#include <optional>
#include <string>

namespace openplx::frontend {

// OpenPLX source declaring model `model_name` for the asset at `path` (absolute), or nullopt with `error`
// naming why the extension cannot be imported.
std::optional<std::string> import_plugin_source(const std::string& path, const std::string& model_name,
                                                std::string& error);

}  // namespace openplx::frontend
