#include "frontend/natives/builtin_natives.h"

#include <mutex>

#include "frontend/evaluation/evaluator.h"

namespace openplx::natives {

void register_builtin_natives() {
  static std::once_flag once;
  std::call_once(once, [] {
    register_math_natives(frontend::NativeRegistry::global());
    register_bundle_natives(frontend::NativeRegistry::global());
  });
}

}  // namespace openplx::natives
