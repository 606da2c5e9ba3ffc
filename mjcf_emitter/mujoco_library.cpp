#include "mjcf_emitter/mujoco_library.h"

#include <dlfcn.h>

#include <mutex>

#ifndef OPENPLX_MUJOCO_LIBRARY
#define OPENPLX_MUJOCO_LIBRARY "libmujoco.so.2.2.2"
#endif

namespace openplx::mjcf {

namespace {

template <typename Function>
bool find(void* handle, const char* name, Function& function, std::string& error) {
  function = reinterpret_cast<Function>(dlsym(handle, name));
  if (!function) error = std::string("MuJoCo's library has no ") + name;
  return function != nullptr;
}

}  // namespace

const MuJoCoLibrary* mujoco_library(std::string& error) {
  static MuJoCoLibrary library;
  static std::string load_error;
  static bool loaded = false;
  static std::once_flag once;
  std::call_once(once, [] {
    void* handle = dlopen(OPENPLX_MUJOCO_LIBRARY, RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* why = dlerror();
      load_error = std::string("cannot load MuJoCo (" OPENPLX_MUJOCO_LIBRARY "): ") + (why ? why : "unknown");
      return;
    }
    // Never closed: the process may keep using models it made.
    loaded = find(handle, "mj_loadXML", library.loadXML, load_error) &&
             find(handle, "mj_deleteModel", library.deleteModel, load_error) &&
             find(handle, "mj_makeData", library.makeData, load_error) &&
             find(handle, "mj_deleteData", library.deleteData, load_error) &&
             find(handle, "mj_forward", library.forward, load_error) &&
             find(handle, "mj_name2id", library.name2id, load_error) &&
             find(handle, "mj_id2name", library.id2name, load_error);
  });
  if (!loaded) error = load_error;
  return loaded ? &library : nullptr;
}

}  // namespace openplx::mjcf
