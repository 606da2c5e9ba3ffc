// The converter needs MuJoCo only to compile a draft (mesh mass properties, soft equalities) and for
// --check. Loading libmujoco then, instead of at process start, spares every other conversion the time
// MuJoCo and its dependencies take to map and relocate (about as long as a small model's whole conversion).
// Programs that link MuJoCo themselves (the runtime, openplx-sim) get the library they already have.
//
// MuJoCo's messages are the converter's: every call into MuJoCo runs inside a MuJoCoMessages, which installs
// MuJoCo's warning and error handlers (mju_user_warning, mju_user_error: global function pointers in 2.2.2)
// for as long as one is alive, so MuJoCo never writes MUJOCO_LOG.TXT into the user's folder nor prints on its
// own; its warnings are kept for our diagnostics and its errors come back from MuJoCoMessages::call.
#pragma once

#include <mujoco/mujoco.h>

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "mujoco_support/error_trap.h"

namespace openplx::mjcf {

struct MuJoCoLibrary {
  decltype(&mj_loadXML) loadXML = nullptr;
  decltype(&mj_deleteModel) deleteModel = nullptr;
  decltype(&mj_makeData) makeData = nullptr;
  decltype(&mj_deleteData) deleteData = nullptr;
  decltype(&mj_forward) forward = nullptr;
  decltype(&mj_step) step = nullptr;
  decltype(&mj_resetData) resetData = nullptr;
  decltype(&mj_resetDataKeyframe) resetDataKeyframe = nullptr;
  decltype(&mj_name2id) name2id = nullptr;
  decltype(&mj_id2name) id2name = nullptr;
  decltype(&mj_solveM) solveM = nullptr;
  // The handler variables themselves (their addresses in the library).
  decltype(&mju_user_warning) user_warning = nullptr;
  decltype(&mju_user_error) user_error = nullptr;
};

// Loaded on first use; nullptr when it cannot be, with `error` saying why.
const MuJoCoLibrary* mujoco_library(std::string& error);

// While one is alive on a thread, MuJoCo's warnings raised on that thread are kept in `warnings` (nested
// ones: the innermost). Handlers are installed when the first one in the process starts and the ones before
// them (a user's, the runtime's) are put back when the last one ends; a warning from another thread meanwhile
// goes to those (else to stderr).
class MuJoCoMessages {
 public:
  explicit MuJoCoMessages(const MuJoCoLibrary& mj);
  ~MuJoCoMessages();
  MuJoCoMessages(const MuJoCoMessages&) = delete;
  MuJoCoMessages& operator=(const MuJoCoMessages&) = delete;

  std::vector<std::string> warnings;  // MuJoCo's texts, in order
  // Runs inside the warning handler, before the text is kept: MuJoCo warns about a bad qpos, qvel or qacc
  // before it resets mjData, so this is where the values that blew up can still be read.
  std::function<void(const char* text)> on_warning;

  // Runs `call` so that an mju_error inside it returns false with `error` set instead of ending the
  // process (mujoco_support/error_trap.h says what `call` may hold and what becomes of `d`).
  template <typename Call>
  bool call(mjData* d, Call&& call, std::string& error) {
    return mujoco_support::call_trapped(d, std::forward<Call>(call), error);
  }

 private:
  const MuJoCoLibrary& mj_;
  MuJoCoMessages* outer_;  // the enclosing one on this thread
};

}  // namespace openplx::mjcf
