// A large model's conversion touches tens of megabytes of small objects once each; with 4 KiB pages a third
// of its run is page faults. Reserving the heap up front and asking the kernel for transparent huge pages
// there turns some 15,000 faults into a few dozen.
#pragma once

#include <cstddef>

namespace openplx::cli {

// Grows the malloc heap by `bytes` (kept, not trimmed) and marks it and the small-object arena for
// transparent huge pages. A thread of its own then faults in up to `prefault_bytes` of the arena, a huge page
// ahead of the conversion, so that the kernel's (and a virtual machine host's) work of backing fresh pages
// is done on the other core. For the converter process only: it changes malloc's thresholds for the rest of
// the process.
void reserve_huge_page_heap(size_t bytes, size_t prefault_bytes);

}  // namespace openplx::cli
