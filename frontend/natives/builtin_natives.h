// Registration of the natively implemented bundle functions. Explicit calls, not static initialisers: a
// static library drops object files nothing refers to.
#pragma once

namespace openplx::frontend {
class NativeRegistry;
}

namespace openplx::natives {

void register_math_natives(frontend::NativeRegistry& registry);
void register_bundle_natives(frontend::NativeRegistry& registry);
// Registers every bundle's natives into NativeRegistry::global() once (thread-safe).
void register_builtin_natives();

}  // namespace openplx::natives
