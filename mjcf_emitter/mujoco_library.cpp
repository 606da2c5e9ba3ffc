#include "mjcf_emitter/mujoco_library.h"

#include <dlfcn.h>

#include <cstdio>
#include <mutex>

#include "frontend/platform/loadable_module.h"

#ifndef OPENPLX_MUJOCO_LIBRARY
#define OPENPLX_MUJOCO_LIBRARY "libmujoco.so.2.2.2"
#endif

namespace openplx::mjcf {

namespace {

// A variable of the library as its own code reaches it: a program that names the variable itself (linked
// with MuJoCo, as the runtime is) holds a copy the library's code uses instead of its own (a copy
// relocation), and only a global lookup finds that one; loaded by us alone, the library's own is the one.
template <typename Pointer>
bool find_variable(const frontend::LoadableModule& module, const char* name, Pointer& variable,
                   std::string& error) {
  if (void* copy = dlsym(RTLD_DEFAULT, name)) {
    variable = reinterpret_cast<Pointer>(copy);
    return true;
  }
  return module.find(name, variable, error);
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
  mujoco_support::jump_to_trap(text);
  Handler replaced = nullptr;
  {
    const std::lock_guard<std::mutex> lock(handlers_mutex);
    replaced = replaced_error;
  }
  if (replaced) replaced(text);  // another thread's MuJoCo call: its owner's handler (which does not return)
  mujoco_support::end_process(text);
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
    // Bound at once, so a library that cannot resolve its own dependencies fails here, not mid-call.
    const frontend::LoadableModule mujoco =
        frontend::load_module_by_soname("MuJoCo", OPENPLX_MUJOCO_LIBRARY, frontend::Binding::Now);
    if (!mujoco.handle) {
      load_error = mujoco.error;
      return;
    }
    loaded = mujoco.find("mj_loadXML", library.loadXML, load_error) &&
             mujoco.find("mj_deleteModel", library.deleteModel, load_error) &&
             mujoco.find("mj_makeData", library.makeData, load_error) &&
             mujoco.find("mj_deleteData", library.deleteData, load_error) &&
             mujoco.find("mj_forward", library.forward, load_error) &&
             mujoco.find("mj_step", library.step, load_error) &&
             mujoco.find("mj_resetData", library.resetData, load_error) &&
             mujoco.find("mj_resetDataKeyframe", library.resetDataKeyframe, load_error) &&
             mujoco.find("mj_name2id", library.name2id, load_error) &&
             mujoco.find("mj_id2name", library.id2name, load_error) &&
             mujoco.find("mj_solveM", library.solveM, load_error) &&
             find_variable(mujoco, "mju_user_warning", library.user_warning, load_error) &&
             find_variable(mujoco, "mju_user_error", library.user_error, load_error);
  });
  if (!loaded) error = load_error;
  return loaded ? &library : nullptr;
}

}  // namespace openplx::mjcf
