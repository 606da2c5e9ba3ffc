#include "tools/cli/huge_page_heap.h"

#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <thread>

#include "tools/cli/small_object_arena.h"

namespace openplx::cli {

namespace {

constexpr uintptr_t kHugePage = 2u << 20;

std::atomic<uintptr_t> heap_frontier{0};  // the end of the highest heap block operator new has handed out
// The block that covers the heap below its first huge page: kept, never touched; volatile, or the compiler
// drops an allocation nobody reads.
void* volatile below_first_huge_page = nullptr;

// A range that fills from its bottom, faulted in up to `cap`, a huge page ahead of where it is used.
struct Region {
  uintptr_t populated;  // faulted in below this
  uintptr_t cap;
};

uintptr_t huge_page_above(uintptr_t address) {
  return (address + kHugePage - 1) & ~(kHugePage - 1);
}

// Faults in the heap's and the arena's next huge page before the conversion reaches it, on a core the
// conversion does not use: on a virtual machine a fresh page costs far more (the host backs it) than the
// few microseconds of work the conversion does on it. MADV_POPULATE_WRITE faults a page in without writing
// to it, so it cannot race with what the conversion writes there.
void prefault(Region heap, Region arena) {
  for (;;) {
    bool faulted = false;
    const uintptr_t reached[2] = {heap_frontier.load(std::memory_order_relaxed),
                                  reinterpret_cast<uintptr_t>(arena::frontier())};
    Region* regions[2] = {&heap, &arena};
    for (int i = 0; i < 2; ++i) {
      Region& r = *regions[i];
      const uintptr_t wanted = std::min(r.cap, huge_page_above(reached[i]) + kHugePage);
      if (r.populated >= wanted) continue;
      if (madvise(reinterpret_cast<void*>(r.populated), kHugePage, MADV_POPULATE_WRITE) != 0)
        r.cap = 0;  // an older kernel (before 5.14): no prefaulting
      r.populated += kHugePage;
      faulted = true;
    }
    if (heap.populated >= heap.cap && arena.populated >= arena.cap) return;
    if (!faulted) std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
}

}  // namespace

void note_heap_block(const void* block, size_t bytes) noexcept {
  const uintptr_t end = reinterpret_cast<uintptr_t>(block) + bytes;
  uintptr_t seen = heap_frontier.load(std::memory_order_relaxed);
  while (end > seen && !heap_frontier.compare_exchange_weak(seen, end, std::memory_order_relaxed)) {
  }
}

void reserve_huge_page_heap(size_t bytes, size_t prefault_bytes) {
#if defined(__SANITIZE_ADDRESS__)
  // AddressSanitizer's allocator owns the heap: the blocks would only sit in its quarantine.
  (void)bytes;
  (void)prefault_bytes;
#else
  // Every block comes from the heap, never from mmap (which would get small pages); never trimmed.
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, INT32_MAX);
  // One block taken and given back grows the heap and leaves it as the top chunk, untouched but for the
  // block's header and the new top's: a page touched before the madvise below keeps its whole 2 MiB range
  // in small pages (up to 511 more faults, about 10 us each on a virtual machine), so one block, not many.
  void* block = malloc(bytes);
  if (!block) return;
  const auto begin = reinterpret_cast<uintptr_t>(block);
  free(block);
  const auto end = reinterpret_cast<uintptr_t>(sbrk(0));
  const uintptr_t first = huge_page_above(begin);
  const uintptr_t last = end & ~(kHugePage - 1);
  // Without THP (kernel setting "never") this fails harmlessly and the heap keeps small pages.
  const bool huge = last > first && madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE) == 0;
  if (huge && first - begin >= 64) {
    // malloc hands out the top chunk from its bottom, in the small pages below `first`: a block kept and
    // never touched covers them, so the next one starts on the first huge page (its chunk is first - begin
    // bytes, 8 more than asked for).
    below_first_huge_page = malloc(first - begin - 8);
  }
  const auto arena_pages = reinterpret_cast<uintptr_t>(arena::use_huge_pages());  // where operator new's
                                                                                  // small blocks come from
  Region heap{first, huge ? first + std::min<uintptr_t>(prefault_bytes, last - first) : 0};
  Region arena{arena_pages, arena_pages ? arena_pages + prefault_bytes : 0};
  if (heap.cap > heap.populated || arena.cap > arena.populated) std::thread(prefault, heap, arena).detach();
#endif
}

}  // namespace openplx::cli
