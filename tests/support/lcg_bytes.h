// Reproducible "random" bytes for tests: a fixed 64-bit LCG (Knuth's MMIX constants), the top byte of each
// state one byte of output. The same seed gives the same bytes on every machine.
#pragma once

#include <cstdint>
#include <string>

namespace openplx::testing {

inline std::string lcg_bytes(uint64_t seed, size_t size) {
  std::string out(size, '\0');
  for (char& c : out) {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    c = static_cast<char>(seed >> 56);
  }
  return out;
}

}  // namespace openplx::testing
