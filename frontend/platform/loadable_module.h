// Shared libraries opened when first needed (dlopen): the URDF importer, the mesh reader and, for the
// converter, MuJoCo. A conversion that needs none of them then maps none of them, nor their dependencies.
#pragma once

#include <mutex>
#include <string>
#include <string_view>
#include <vector>

namespace openplx::frontend {

enum class Binding { Lazy, Now };  // RTLD_LAZY binds only what is called; RTLD_NOW all at once

// An opened library, never closed: its code may still be on a stack, or its data in use, at exit.
struct LoadableModule {
  void* handle = nullptr;
  // As messages call it: "the mesh reader /x/libopenplx_meshes.so", "MuJoCo (libmujoco.so.2.2.2)".
  std::string name;
  std::string error;  // why handle is null

  void* address(const char* symbol) const;  // nullptr when the library has no such symbol
  // `symbol` as `Pointer`; false with `why` = "<name> has no <symbol>" when it is missing.
  template <typename Pointer>
  bool find(const char* symbol, Pointer& pointer, std::string& why) const {
    pointer = reinterpret_cast<Pointer>(address(symbol));
    if (!pointer) why = name + " has no " + symbol;
    return pointer != nullptr;
  }
};

// Opens the first of `candidates` that is a regular file. `what` ("the URDF importer") and `file_name`
// ("libopenplx_urdf.so") word the errors; with none found, the error lists every path tried.
LoadableModule load_first_module(std::string_view what, std::string_view file_name,
                                 const std::vector<std::string>& candidates, Binding binding);
// Opens `soname` where the dynamic loader finds it: a program linked with that library gets its own copy.
LoadableModule load_module_by_soname(std::string_view what, const std::string& soname, Binding binding);

// Where one of our plug-ins is looked for, in order: beside an installed executable
// (<bin>/../lib/openplx2mjcf/<file>), the paths the build configured (this build's, the install prefix's),
// then those added at run time (a program with its own layout).
class PluginSearch {
 public:
  PluginSearch(std::string file_name, std::vector<std::string> configured);
  const std::string& file_name() const { return file_name_; }
  void add(const std::string& path);
  std::vector<std::string> candidates() const;

 private:
  std::string file_name_;
  std::vector<std::string> configured_;
  mutable std::mutex mutex_;
  std::vector<std::string> added_;
};

}  // namespace openplx::frontend
