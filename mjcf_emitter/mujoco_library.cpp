#include "mjcf_emitter/mujoco_library.h"

#include <dlfcn.h>

#include <cstdio>
#include <cstdlib>
#include <mutex>

#ifndef OPENPLX_MUJOCO_LIBRARY
#define OPENPLX_MUJOCO_LIBRARY "libmujoco.so.2.2.2"
#endif

namespace openplx::mjcf {

namespace detail {
ErrorJump*& current_error_jump() {
  thread_local ErrorJump* jump = nullptr;
  return jump;
}
}  // namespace detail

namespace {

template <typename Function>
bool find(void* handle, const char* name, Function& function, std::string& error) {
  function = reinterpret_cast<Function>(dlsym(handle, name));
  if (!function) error = std::string("MuJoCo's library has no ") + name;
  return function != nullptr;
}

// A variable of the library as its own code reaches it: a program that names the variable itself (linked
// with MuJoCo, as the runtime is) holds a copy the library's code uses instead of its own (a copy
// relocation), and only a global lookup finds that one; loaded by us alone, the library's own is the one.
template <typename Pointer>
bool find_variable(void* handle, const char* name, Pointer& variable, std::string& error) {
  void* address = dlsym(RTLD_DEFAULT, name);
  if (!address) address = dlsym(handle, name);
  variable = reinterpret_cast<Pointer>(address);
  if (!variable) error = std::string("MuJoCo's library has no ") + name;
  return variable != nullptr;
}

using Handler = void (*)(const char*);

// The process's MuJoCoMessages: how many are alive, and the handlers they replaced.
std::mutex handlers_mutex;
int alive = 0;
Handler replaced_warning = nullptr;
Handler replaced_error = nullptr;

MuJoCoMessages*& current_messages() {
  thread_local MuJoCoMessages* messages = nullptr;
  return messages;
}

void handle_warning(const char* text) {
  if (MuJoCoMessages* messages = current_messages()) {
    if (messages->on_warning) messages->on_warning(text);
    messages->warnings.emplace_back(text);
    return;
  }
  Handler replaced = nullptr;
  {
    const std::lock_guard<std::mutex> lock(handlers_mutex);
    replaced = replaced_warning;
  }
  if (replaced) {
    replaced(text);
  } else {
    std::fprintf(stderr, "MuJoCo warning: %s\n", text);
  }
}

[[noreturn]] void handle_error(const char* text) {
  if (detail::ErrorJump* jump = detail::current_error_jump()) {
    std::snprintf(jump->message, sizeof(jump->message), "%s", text);
    siglongjmp(jump->target, 1);
  }
  Handler replaced = nullptr;
  {
    const std::lock_guard<std::mutex> lock(handlers_mutex);
    replaced = replaced_error;
  }
  if (replaced) replaced(text);  // another thread's MuJoCo call: its owner's handler (which does not return)
  // MuJoCo may not be returned to (it would go on with what failed), nor can anything above be unwound.
  std::fprintf(stderr, "MuJoCo error: %s\n", text);
  std::fflush(stderr);
  std::_Exit(EXIT_FAILURE);
}

}  // namespace

MuJoCoMessages::MuJoCoMessages(const MuJoCoLibrary& mj) : mj_(mj), outer_(current_messages()) {
  {
    const std::lock_guard<std::mutex> lock(handlers_mutex);
    if (alive++ == 0) {
      replaced_warning = *mj_.user_warning;
      replaced_error = *mj_.user_error;
      *mj_.user_warning = handle_warning;
      *mj_.user_error = handle_error;
    }
  }
  current_messages() = this;
}

MuJoCoMessages::~MuJoCoMessages() {
  current_messages() = outer_;
  const std::lock_guard<std::mutex> lock(handlers_mutex);
  if (--alive == 0) {
    // Put back only what is still ours: a handler set since (by the user) stays.
    if (*mj_.user_warning == handle_warning) *mj_.user_warning = replaced_warning;
    if (*mj_.user_error == handle_error) *mj_.user_error = replaced_error;
    replaced_warning = replaced_error = nullptr;
  }
}

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
             find(handle, "mj_step", library.step, load_error) &&
             find(handle, "mj_resetData", library.resetData, load_error) &&
             find(handle, "mj_resetDataKeyframe", library.resetDataKeyframe, load_error) &&
             find(handle, "mj_name2id", library.name2id, load_error) &&
             find(handle, "mj_id2name", library.id2name, load_error) &&
             find(handle, "mj_solveM", library.solveM, load_error) &&
             find_variable(handle, "mju_user_warning", library.user_warning, load_error) &&
             find_variable(handle, "mju_user_error", library.user_error, load_error);
  });
  if (!loaded) error = load_error;
  return loaded ? &library : nullptr;
}

}  // namespace openplx::mjcf
