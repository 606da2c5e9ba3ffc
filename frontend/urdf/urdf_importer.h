// Imports a URDF through the importer module (libopenplx_urdf.so), loaded on the first URDF a process reads:
// urdfdom, tinyxml2 and console_bridge then cost nothing to conversions that never see a URDF. A module that
// cannot be found or loaded gives one error finding that names it.
#pragma once

#include <string>

#include "frontend/urdf/urdf_result.h"

namespace openplx::frontend {

// Imports the URDF at `path` whose text is `urdf_text` as model `model_name`.
UrdfImport import_urdf(const std::string& path, const std::string& urdf_text, const std::string& model_name,
                       const UrdfImportOptions& options = {});

// Adds a file tried for the module after the ones beside the executable and in this build (the installed
// CMake package registers its own through the runtime's public header).
void add_urdf_module_candidate(const std::string& path);

}  // namespace openplx::frontend
