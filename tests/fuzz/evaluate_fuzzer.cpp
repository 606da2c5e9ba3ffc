// libFuzzer target for name resolution and evaluation: build with tools/fuzz.sh evaluate_fuzzer.
#include "tests/fuzz/fuzz_evaluate.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  openplx::fuzz::evaluate_one(data, size);
  return 0;
}
