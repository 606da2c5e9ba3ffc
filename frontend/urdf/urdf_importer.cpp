#include "frontend/urdf/urdf_importer.h"

#include <string>
#include <vector>

#include "frontend/platform/loadable_module.h"
#include "frontend/urdf/urdf_module_abi.h"

#ifdef OPENPLX_URDF_LINKED
#include "frontend/urdf/urdf_import.h"
#endif

namespace openplx::frontend {

namespace {

// This build's module, then the install prefix's.
std::vector<std::string> configured_paths() {
  std::vector<std::string> paths;
#ifdef OPENPLX_URDF_MODULE_BUILT
  paths.emplace_back(OPENPLX_URDF_MODULE_BUILT);
#endif
#ifdef OPENPLX_URDF_MODULE_INSTALLED
  paths.emplace_back(OPENPLX_URDF_MODULE_INSTALLED);
#endif
  return paths;
}

PluginSearch& module_search() {
  static PluginSearch search("libopenplx_urdf.so", configured_paths());
  return search;
}

struct LoadedModule {
  OpenplxUrdfImportFunction import = nullptr;
  std::string error;
};

[[maybe_unused]] const LoadedModule& loaded_module() {  // not in fuzz builds (OPENPLX_URDF_LINKED)
  static const LoadedModule module = [] {
    LoadedModule m;
    // Lazy binding: only what a URDF import calls gets bound.
    const LoadableModule library = load_first_module("the URDF importer", module_search().file_name(),
                                                     module_search().candidates(), Binding::Lazy);
    if (!library.handle)
      m.error = library.error;
    else
      library.find(OPENPLX_URDF_IMPORT_SYMBOL, m.import, m.error);
    return m;
  }();
  return module;
}

UrdfImport& as_import(void* context) {
  return *static_cast<UrdfImport*>(context);
}

[[maybe_unused]] constexpr OpenplxUrdfSink sink_for(UrdfImport* result) {
  return OpenplxUrdfSink{
      result,
      [](void* c, const char* data, size_t size) { as_import(c).text.emplace(data, size); },
      [](void* c, const uint32_t* offsets, size_t count) {
        as_import(c).line_origins.assign(offsets, offsets + count);
      },
      [](void* c, int error, uint32_t offset, const char* message, size_t size) {
        as_import(c).findings.push_back({error != 0, offset, std::string(message, size), {}});
      },
      [](void* c, const char* data, size_t size) {
        if (!as_import(c).findings.empty()) as_import(c).findings.back().notes.emplace_back(data, size);
      },
      [](void* c, const char* data, size_t size) { as_import(c).robot_name.assign(data, size); },
  };
}

}  // namespace

void add_urdf_module_candidate(const std::string& path) {
  module_search().add(path);
}

UrdfImport import_urdf(const std::string& path, const std::string& urdf_text, const std::string& model_name,
                       const UrdfImportOptions& options) {
#ifdef OPENPLX_URDF_LINKED  // fuzz builds link the importer in, so its code is instrumented with theirs
  return convert_urdf(path, urdf_text, model_name, options);
#else
  UrdfImport result;
  const LoadedModule& module = loaded_module();
  if (!module.import) {
    result.findings.push_back({true, 0, module.error, {}});
    return result;
  }
  const OpenplxUrdfSink sink = sink_for(&result);
  module.import(path.c_str(), urdf_text.data(), urdf_text.size(), model_name.c_str(),
                options.packages_final ? OPENPLX_URDF_PACKAGES_FINAL : 0u, &sink);
  return result;
#endif
}

}  // namespace openplx::frontend
