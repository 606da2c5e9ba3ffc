// The one trap for MuJoCo's errors, used by the converter (which loads MuJoCo itself,
// mjcf_emitter/mujoco_library.h) and the runtime (linked with MuJoCo, runtime/mujoco_messages.h).
// mju_error must not return into MuJoCo (it would carry on with what failed) and an exception cannot cross
// MuJoCo's C frames, so a call we make into MuJoCo sets a jump target first and the error handler jumps
// back to it. The target is per thread and shared by both sides: nested calls land in the innermost.
// Nothing here calls MuJoCo: the converter's build links MuJoCo's headers only.
#pragma once

#include <mujoco/mujoco.h>

#include <csetjmp>
#include <string>

namespace openplx::mujoco_support {

struct ErrorTrap {
  sigjmp_buf target;
  char message[1024];  // MuJoCo's text; a fixed buffer, as nothing may be allocated on the way out
};
ErrorTrap*& current_trap();  // thread-local: the innermost call_trapped running on this thread

// Runs `call` (calls into MuJoCo holding nothing with a destructor: a jump may leave it) so that an
// mju_error inside it returns false with `error` set. MuJoCo may have left `d` half done: its stack
// pointer, left raised by the jump, is put back; the caller should not step it further.
template <typename Call>
bool call_trapped(mjData* d, Call&& call, std::string& error) {
  ErrorTrap trap;
  ErrorTrap* const outer = current_trap();
  const int stack = d ? d->pstack : 0;
  current_trap() = &trap;
  if (sigsetjmp(trap.target, 0) == 0) {
    call();
    current_trap() = outer;
    return true;
  }
  current_trap() = outer;
  if (d) d->pstack = stack;
  error = trap.message;
  return false;
}

// The error handlers' shared half. Jumps to this thread's trap with `text`; returns when there is none.
void jump_to_trap(const char* text);
// No trap to go back to (someone else's call into MuJoCo): prints the text to stderr and exits with
// EXIT_FAILURE through std::exit, as MuJoCo's own handler does, only without its MUJOCO_LOG.TXT.
[[noreturn]] void end_process(const char* text);
// Both in one: a handler for mju_user_error.
[[noreturn]] void trap_error(const char* text);

}  // namespace openplx::mujoco_support
