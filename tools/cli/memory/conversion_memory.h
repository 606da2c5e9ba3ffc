// The converter's memory, behind one call: everything in this folder (the small-object arena that
// operator new uses, the huge-page heap and its prefault thread) is for the openplx2mjcf process alone and
// changes nothing a conversion produces. The libraries, the runtime and the tests keep the standard
// allocator.
#pragma once

#include <cstdint>

namespace openplx::cli {

// Sets the heap up for converting an input of `input_bytes` bytes of text, before it is read. Small inputs
// leave it as it is; large ones get a huge-page heap sized from the text (see huge_page_heap.h).
void prepare_memory_for_input(std::uintmax_t input_bytes);

}  // namespace openplx::cli
