#include "frontend/platform/loadable_module.h"

#include <dlfcn.h>

#include <filesystem>
#include <utility>

#include "frontend/bundles/bundles.h"

namespace openplx::frontend {

namespace {

int dlopen_flags(Binding binding) {
  return (binding == Binding::Lazy ? RTLD_LAZY : RTLD_NOW) | RTLD_LOCAL;
}

LoadableModule open(const std::string& file, std::string name, Binding binding) {
  LoadableModule module;
  module.name = std::move(name);
  module.handle = dlopen(file.c_str(), dlopen_flags(binding));
  if (!module.handle) {
    const char* why = dlerror();
    module.error = "cannot load " + module.name + ": " + (why ? why : "unknown error");
  }
  return module;
}

}  // namespace

void* LoadableModule::address(const char* symbol) const {
  return handle ? dlsym(handle, symbol) : nullptr;
}

LoadableModule load_first_module(std::string_view what, std::string_view file_name,
                                 const std::vector<std::string>& candidates, Binding binding) {
  std::string tried;
  for (const std::string& path : candidates) {
    std::error_code ec;
    if (std::filesystem::is_regular_file(path, ec))
      return open(path, std::string(what) + " " + path, binding);
    tried += (tried.empty() ? "" : ", ") + path;
  }
  LoadableModule missing;
  missing.name = std::string(what) + " " + std::string(file_name);
  missing.error = "cannot find " + missing.name + " (tried " + tried + ")";
  return missing;
}

LoadableModule load_module_by_soname(std::string_view what, const std::string& soname, Binding binding) {
  return open(soname, std::string(what) + " (" + soname + ")", binding);
}

PluginSearch::PluginSearch(std::string file_name, std::vector<std::string> configured)
    : file_name_(std::move(file_name)), configured_(std::move(configured)) {}

void PluginSearch::add(const std::string& path) {
  const std::lock_guard lock(mutex_);
  added_.push_back(path);
}

std::vector<std::string> PluginSearch::candidates() const {
  namespace fs = std::filesystem;
  std::vector<std::string> paths;
  if (const fs::path dir = executable_dir(); !dir.empty())
    paths.push_back((dir / "../lib/openplx2mjcf" / file_name_).lexically_normal());
  paths.insert(paths.end(), configured_.begin(), configured_.end());
  const std::lock_guard lock(mutex_);
  paths.insert(paths.end(), added_.begin(), added_.end());
  return paths;
}

}  // namespace openplx::frontend
