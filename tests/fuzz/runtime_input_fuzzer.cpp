// libFuzzer target for the runtime's inputs (sets, steps, reads) on the drivetrain sample: build and run with
// tools/fuzz.sh 300 runtime_input_fuzzer.
#include "tests/fuzz/fuzz_runtime.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  openplx::fuzz::runtime_input_one(data, size);
  return 0;
}
