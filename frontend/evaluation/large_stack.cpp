#include "frontend/evaluation/large_stack.h"

#include <pthread.h>

#include <exception>

namespace openplx::frontend {
namespace {

struct Task {
  const std::function<void()>* fn;
  std::exception_ptr error;
};

void* run_task(void* arg) {
  auto* task = static_cast<Task*>(arg);
  try {
    (*task->fn)();
  } catch (...) {
    task->error = std::current_exception();
  }
  return nullptr;
}

}  // namespace

void run_with_large_stack(const std::function<void()>& fn, size_t stack_bytes) {
  Task task{&fn, nullptr};
  pthread_attr_t attr;
  pthread_t thread;
  // The stack is reserved address space; only the pages touched are ever backed by memory.
  if (pthread_attr_init(&attr) != 0 || pthread_attr_setstacksize(&attr, stack_bytes) != 0 ||
      pthread_create(&thread, &attr, &run_task, &task) != 0) {
    pthread_attr_destroy(&attr);
    fn();  // no thread to be had: run here, with the caller's stack
    return;
  }
  pthread_attr_destroy(&attr);
  pthread_join(thread, nullptr);
  if (task.error) std::rethrow_exception(task.error);
}

}  // namespace openplx::frontend
