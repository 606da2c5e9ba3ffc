#include "runtime/mujoco_messages.h"

#include <cstdio>
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

}  // namespace

MessageSink*& current_sink() {
  thread_local MessageSink* sink = nullptr;
  return sink;
}

void install_mujoco_handlers() {
  static std::mutex mutex;
  const std::lock_guard<std::mutex> lock(mutex);
  if (!mju_user_warning) mju_user_warning = on_warning;
  if (!mju_user_error) mju_user_error = mujoco_support::trap_error;
}

bool mujoco_handlers_installed() {
  return mju_user_warning == on_warning && mju_user_error == mujoco_support::trap_error;
}

}  // namespace openplx::runtime
