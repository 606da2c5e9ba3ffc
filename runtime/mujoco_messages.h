// MuJoCo's messages become the runtime's: its warning and error handlers (mju_user_warning, mju_user_error,
// global function pointers in MuJoCo 2.2.2) are installed when they are not set, so MuJoCo never writes
// MUJOCO_LOG.TXT nor prints on its own. runtime/README.md "MuJoCo's messages" gives the decisions:
// - a warning goes to the Simulation or bridge being stepped on this thread (MessageSink), which first
//   copies the state MuJoCo saw (its warning comes before the reset of mj_checkPos/Vel/Acc); with none, to
//   stderr;
// - an error may not return into MuJoCo (it would carry on with what failed): inside the runtime's own calls
//   (call_mujoco) it jumps back there with longjmp, over MuJoCo's C frames only, and becomes an exception;
//   outside them (a bridge user's own mj_step) it is printed to stderr and the process exits, as MuJoCo's
//   default handler does, without its log file;
// - a handler the user set before the runtime's first load or attach is left in place (and then neither
//   applies).
#pragma once

#include <mujoco/mujoco.h>

#include <string>
#include <utility>

#include "mujoco_support/error_trap.h"

namespace openplx::runtime {

void install_mujoco_handlers();
bool mujoco_handlers_installed();  // ours are the ones set now

// Whoever is stepping on this thread; MuJoCo's warnings are handed to it.
struct MessageSink {
  virtual void mujoco_warning(const char* text) = 0;

 protected:
  ~MessageSink() = default;
};
MessageSink*& current_sink();  // thread-local

// Calls `call` (calls into MuJoCo) so that an mju_error inside it returns false with `error` set: the trap
// the converter uses too (mujoco_support/error_trap.h, which says what `call` may hold).
template <typename Call>
bool call_mujoco(mjData* d, Call&& call, std::string& error) {
  return mujoco_support::call_trapped(d, std::forward<Call>(call), error);
}

}  // namespace openplx::runtime
