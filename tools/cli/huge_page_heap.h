// A large model's conversion touches tens of megabytes of small objects once each; with 4 KiB pages a third
// of its run is page faults. Reserving the heap up front and asking the kernel for transparent huge pages
// there turns some 15,000 faults into a few dozen.
#pragma once

#include <cstddef>

namespace openplx::cli {

// Grows the malloc heap by `bytes` (kept, not trimmed) and marks it for transparent huge pages. For the
// converter process only: it changes malloc's thresholds for the rest of the process.
void reserve_huge_page_heap(size_t bytes);

}  // namespace openplx::cli
