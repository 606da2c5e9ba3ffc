#include "runtime/mujoco_messages.h"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>

namespace openplx::runtime {

namespace {

void on_warning(const char* text) {
  if (MessageSink* sink = current_sink()) {
    sink->mujoco_warning(text);
  } else {
    std::fprintf(stderr, "MuJoCo warning: %s\n", text);
  }
}

[[noreturn]] void on_error(const char* text) {
  if (ErrorJump* jump = current_jump()) {
    std::snprintf(jump->message, sizeof(jump->message), "%s", text);
    siglongjmp(jump->target, 1);
  }
  // Not inside the runtime's own call: MuJoCo may not be returned to, and nothing above can be unwound.
  std::fprintf(stderr, "MuJoCo error: %s\n", text);
  std::fflush(stderr);
  std::exit(EXIT_FAILURE);
}

}  // namespace

MessageSink*& current_sink() {
  thread_local MessageSink* sink = nullptr;
  return sink;
}

ErrorJump*& current_jump() {
  thread_local ErrorJump* jump = nullptr;
  return jump;
}

void install_mujoco_handlers() {
  static std::mutex mutex;
  const std::lock_guard<std::mutex> lock(mutex);
  if (!mju_user_warning) mju_user_warning = on_warning;
  if (!mju_user_error) mju_user_error = on_error;
}

bool mujoco_handlers_installed() {
  return mju_user_warning == on_warning && mju_user_error == on_error;
}

}  // namespace openplx::runtime
