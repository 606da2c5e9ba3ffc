// libFuzzer target for the lexer and parser: build with tools/fuzz.sh.
#include "tests/fuzz/fuzz_lex_parse.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  openplx::fuzz::lex_parse_one(data, size);
  return 0;
}
