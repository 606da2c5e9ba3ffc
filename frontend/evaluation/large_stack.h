// Runs a function on a thread with a large stack and waits for it. Evaluation recurses through chains of
// dependent attributes (bounded by a depth limit); a big private stack keeps that limit safe under any
// caller's stack size and under AddressSanitizer's larger frames.
#pragma once

#include <cstddef>
#include <functional>

namespace openplx::frontend {

inline constexpr size_t kEvaluationStackBytes = size_t{256} << 20;

void run_with_large_stack(const std::function<void()>& fn, size_t stack_bytes = kEvaluationStackBytes);

}  // namespace openplx::frontend
