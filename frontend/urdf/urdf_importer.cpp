#include "frontend/urdf/urdf_importer.h"

#include <dlfcn.h>

#include <filesystem>
#include <mutex>
#include <vector>

#include "frontend/bundles/bundles.h"
#include "frontend/urdf/urdf_module_abi.h"

#ifdef OPENPLX_URDF_LINKED
#include "frontend/urdf/urdf_import.h"
#endif

namespace openplx::frontend {

namespace {

std::mutex candidates_mutex;
std::vector<std::string>& extra_candidates() {
  static std::vector<std::string> paths;
  return paths;
}

// Beside an installed executable, then this build's, then the configured install prefix's, then registered.
std::vector<std::string> module_candidates() {
  namespace fs = std::filesystem;
  std::vector<std::string> paths;
  if (const fs::path dir = executable_dir(); !dir.empty())
    paths.push_back((dir / "../lib/openplx2mjcf/libopenplx_urdf.so").lexically_normal());
#ifdef OPENPLX_URDF_MODULE_BUILT
  paths.emplace_back(OPENPLX_URDF_MODULE_BUILT);
#endif
#ifdef OPENPLX_URDF_MODULE_INSTALLED
  paths.emplace_back(OPENPLX_URDF_MODULE_INSTALLED);
#endif
  std::lock_guard lock(candidates_mutex);
  paths.insert(paths.end(), extra_candidates().begin(), extra_candidates().end());
  return paths;
}

struct LoadedModule {
  OpenplxUrdfImportFunction import = nullptr;
  std::string error;
};

[[maybe_unused]] const LoadedModule& loaded_module() {  // not in fuzz builds (OPENPLX_URDF_LINKED)
  static const LoadedModule module = [] {
    LoadedModule m;
    std::string tried;
    for (const std::string& path : module_candidates()) {
      std::error_code ec;
      if (!std::filesystem::is_regular_file(path, ec)) {
        tried += (tried.empty() ? "" : ", ") + path;
        continue;
      }
      // Never closed: its code may still be on a stack when the process ends.
      void* handle = dlopen(path.c_str(), RTLD_LAZY | RTLD_LOCAL);  // lazy: binds only what a URDF uses
      if (!handle) {
        const char* why = dlerror();
        m.error = "cannot load the URDF importer " + path + ": " + (why ? why : "unknown error");
        return m;
      }
      m.import = reinterpret_cast<OpenplxUrdfImportFunction>(dlsym(handle, OPENPLX_URDF_IMPORT_SYMBOL));
      if (!m.import) m.error = "the URDF importer " + path + " has no " OPENPLX_URDF_IMPORT_SYMBOL;
      return m;
    }
    m.error = "cannot find the URDF importer libopenplx_urdf.so (tried " + tried + ")";
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
  std::lock_guard lock(candidates_mutex);
  extra_candidates().push_back(path);
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
