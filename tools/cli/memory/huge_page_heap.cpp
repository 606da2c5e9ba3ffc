#include "tools/cli/memory/huge_page_heap.h"

#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <thread>

#include "tools/cli/memory/small_object_arena.h"

namespace openplx::cli {

namespace {

constexpr uintptr_t kHugePage = 2u << 20;

// The block that covers the heap below its first huge page: kept, never touched; volatile, or the compiler
// drops an allocation nobody reads.
void* volatile below_first_huge_page = nullptr;

uintptr_t huge_page_above(uintptr_t address) {
  return (address + kHugePage - 1) & ~(kHugePage - 1);
}

// Faults in the arena's next huge page before the conversion reaches it, up to `cap`, on a core the
// conversion does not use: on a virtual machine a fresh page costs far more (the host backs it) than the
// work the conversion does on it. MADV_POPULATE_WRITE faults a page in without writing to it, so it cannot
// race with what the conversion writes there. (The heap is left alone: its large blocks leave capacity they
// never touch, which faulting in would add to the resident memory.)
void prefault(uintptr_t populated, uintptr_t cap) {
  while (populated < cap) {
    const auto reached = reinterpret_cast<uintptr_t>(arena::frontier());
    if (populated >= huge_page_above(reached) + kHugePage) {
      std::this_thread::sleep_for(std::chrono::microseconds(200));
      continue;
    }
    // An older kernel (before 5.14) has no MADV_POPULATE_WRITE: then nothing is prefaulted.
    if (madvise(reinterpret_cast<void*>(populated), kHugePage, MADV_POPULATE_WRITE) != 0) return;
    populated += kHugePage;
  }
}

}  // namespace

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
  if (!block) {
    mallopt(M_MMAP_MAX, 65536);  // glibc's default: large blocks may come from mmap again
    return;
  }
  const auto begin = reinterpret_cast<uintptr_t>(block);
  free(block);
  const auto end = reinterpret_cast<uintptr_t>(sbrk(0));
  const uintptr_t first = huge_page_above(begin);
  const uintptr_t last = end & ~(kHugePage - 1);
  // Without THP (kernel setting "never") this fails harmlessly and the heap keeps small pages.
  if (last > first && madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE) == 0 &&
      first - begin >= 64) {
    // malloc hands out the top chunk from its bottom, in the small pages below `first`: a block kept and
    // never touched covers them, so the next one starts on the first huge page (its chunk is first - begin
    // bytes, 8 more than asked for).
    below_first_huge_page = malloc(first - begin - 8);
  }
  // Where operator new's small blocks come from.
  if (const auto arena_pages = reinterpret_cast<uintptr_t>(arena::use_huge_pages());
      arena_pages && prefault_bytes)
    std::thread(prefault, arena_pages, arena_pages + prefault_bytes).detach();
#endif
}

}  // namespace openplx::cli
