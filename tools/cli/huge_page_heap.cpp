#include "tools/cli/huge_page_heap.h"

#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <vector>

#include "tools/cli/small_object_arena.h"

namespace openplx::cli {

void reserve_huge_page_heap(size_t bytes) {
#if defined(__SANITIZE_ADDRESS__)
  // AddressSanitizer's allocator owns the heap: the blocks would only sit in its quarantine.
  (void)bytes;
#else
  constexpr uintptr_t kHugePage = 2u << 20;
  constexpr size_t kBlock = 16 << 20;  // below glibc's largest mmap threshold (32 MiB)
  // Blocks up to that size come from the heap (an mmap'd block would get small pages); never trimmed.
  mallopt(M_MMAP_THRESHOLD, 2 * kBlock);
  mallopt(M_TRIM_THRESHOLD, INT32_MAX);
  // Blocks taken in a row and given back coalesce into the heap's top chunk; none of it is touched yet.
  std::vector<void*> blocks;
  blocks.reserve(bytes / kBlock + 1);
  for (size_t taken = 0; taken < bytes; taken += kBlock) blocks.push_back(malloc(kBlock));
  // From the first block, not the break: the top chunk already holds main's pad (M_TOP_PAD), untouched.
  const auto begin = reinterpret_cast<uintptr_t>(blocks.front());
  for (void* block : blocks) free(block);
  const auto end = reinterpret_cast<uintptr_t>(sbrk(0));
  const uintptr_t first = (begin + kHugePage - 1) & ~(kHugePage - 1);
  const uintptr_t last = end & ~(kHugePage - 1);
  // Without THP (kernel setting "never") this fails harmlessly and the heap keeps small pages.
  if (last > first) madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
  arena::use_huge_pages();  // and where small blocks come from, when operator new uses the arena
#endif
}

}  // namespace openplx::cli
