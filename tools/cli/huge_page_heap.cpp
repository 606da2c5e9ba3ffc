#include "tools/cli/huge_page_heap.h"

#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>

#include "tools/cli/small_object_arena.h"

namespace openplx::cli {

void reserve_huge_page_heap(size_t bytes) {
#if defined(__SANITIZE_ADDRESS__)
  // AddressSanitizer's allocator owns the heap: the blocks would only sit in its quarantine.
  (void)bytes;
#else
  constexpr uintptr_t kHugePage = 2u << 20;
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
  const uintptr_t first = (begin + kHugePage - 1) & ~(kHugePage - 1);
  const uintptr_t last = end & ~(kHugePage - 1);
  // Without THP (kernel setting "never") this fails harmlessly and the heap keeps small pages.
  if (last > first && madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE) == 0 &&
      first - begin >= 64) {
    // malloc hands out the top chunk from its bottom, in the small pages below `first`: a block kept and
    // never touched covers them, so the next one starts on the first huge page (its chunk is first - begin
    // bytes, 8 more than asked for).
    static void* below_first_huge_page = malloc(first - begin - 8);
    (void)below_first_huge_page;
  }
  arena::use_huge_pages();  // and where small blocks come from, when operator new uses the arena
#endif
}

}  // namespace openplx::cli
