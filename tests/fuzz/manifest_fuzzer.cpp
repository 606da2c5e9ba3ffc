// libFuzzer target for signal manifests read by a SignalBridge: build and run with tools/fuzz.sh 300
// manifest_fuzzer.
#include "tests/fuzz/fuzz_runtime.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  openplx::fuzz::manifest_one(data, size);
  return 0;
}
