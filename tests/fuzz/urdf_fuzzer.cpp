// libFuzzer target for URDF import: build with tools/fuzz.sh 300 urdf_fuzzer.
#include "tests/fuzz/fuzz_urdf.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  openplx::fuzz::urdf_one(data, size);
  return 0;
}
