#include "mujoco_support/error_trap.h"

#include <cstdio>
#include <cstdlib>

namespace openplx::mujoco_support {

ErrorTrap*& current_trap() {
  thread_local ErrorTrap* trap = nullptr;
  return trap;
}

void jump_to_trap(const char* text) {
  if (ErrorTrap* trap = current_trap()) {
    std::snprintf(trap->message, sizeof(trap->message), "%s", text);
    siglongjmp(trap->target, 1);
  }
}

void end_process(const char* text) {
  std::fprintf(stderr, "MuJoCo error: %s\n", text);
  std::fflush(stderr);
  std::exit(EXIT_FAILURE);
}

void trap_error(const char* text) {
  jump_to_trap(text);
  end_process(text);
}

}  // namespace openplx::mujoco_support
