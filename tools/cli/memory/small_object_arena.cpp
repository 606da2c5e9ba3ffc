#include "tools/cli/memory/small_object_arena.h"

#include <sys/mman.h>

#include <atomic>
#include <cstdint>
#include <cstring>

#ifndef MADV_COLLAPSE
#define MADV_COLLAPSE 25  // Linux 6.1; older C library headers lack it
#endif

namespace openplx::cli::arena {
namespace {

constexpr std::size_t kGranule = 16;
constexpr std::size_t kLargest = 2048;  // larger blocks go to malloc
constexpr std::size_t kClasses = kLargest / kGranule + 1;
constexpr std::size_t kPageShift = 14;  // 16 KiB pages, each of one size class
constexpr std::size_t kPage = std::size_t{1} << kPageShift;
// Address space only: untouched pages cost nothing. Without room for it (strict overcommit), malloc is used.
constexpr std::size_t kReserved = std::size_t{16} << 30;
constexpr std::size_t kPages = kReserved / kPage;
constexpr int kOrphans = 8;
constexpr std::uintptr_t kHugePage = std::uintptr_t{2} << 20;

struct FreeBlock {
  FreeBlock* next;
};

// What one thread allocates from, without a lock: the unused rest of its newest page of each class, and the
// blocks it was given back. Plain data, so that reaching it costs no initialisation check.
struct Cache {
  char* cursor[kClasses];
  char* limit[kClasses];
  FreeBlock* free[kClasses];
  bool registered;  // its hand-back at thread exit is arranged
};

thread_local Cache cache;

// Shared by all threads: the reserved range, the page cursor, each page's class, and the caches of threads
// that ended (the converter runs its passes on threads of their own, one after another).
struct Shared {
  std::atomic_flag busy = ATOMIC_FLAG_INIT;  // reserving, and the orphans
  std::atomic<bool> tried{false};
  char* base = nullptr;
  char* end = nullptr;
  std::atomic<char*> next_page{nullptr};  // pages below it have a class
  Cache orphans[kOrphans] = {};
  int orphan_count = 0;
  unsigned char page_class[kPages] = {};
};

Shared shared;  // constant-initialised: no constructor runs before main's first allocation

class Lock {
 public:
  Lock() {
    while (shared.busy.test_and_set(std::memory_order_acquire)) {
    }
  }
  ~Lock() { shared.busy.clear(std::memory_order_release); }
};

bool reserved() {
  if (shared.tried.load(std::memory_order_acquire)) return shared.base != nullptr;
  Lock lock;
  if (!shared.tried.load(std::memory_order_relaxed)) {
    // A huge page more than used, so that the range can start on one (see use_huge_pages).
    void* range = mmap(nullptr, kReserved + kHugePage, PROT_READ | PROT_WRITE,
                       MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    if (range != MAP_FAILED) {
      shared.base = reinterpret_cast<char*>((reinterpret_cast<std::uintptr_t>(range) + kHugePage - 1) &
                                            ~(kHugePage - 1));
      shared.end = shared.base + kReserved;
      shared.next_page.store(shared.base, std::memory_order_relaxed);
    }
    shared.tried.store(true, std::memory_order_release);
  }
  return shared.base != nullptr;
}

// A thread's cache goes back to the shared pool when the thread ends, for the next thread to take up: the
// blocks it was given back stay in use.
struct HandBack {
  ~HandBack() {
    Lock lock;
    if (shared.orphan_count < kOrphans) shared.orphans[shared.orphan_count++] = cache;
    const bool registered = cache.registered;
    std::memset(&cache, 0, sizeof cache);  // whatever this thread still frees or takes starts afresh
    cache.registered = registered;
  }
};

void register_thread() {
  cache.registered = true;
  {
    Lock lock;
    if (shared.orphan_count > 0) {
      cache = shared.orphans[--shared.orphan_count];
      cache.registered = true;
    }
  }
  static thread_local HandBack hand_back;
  (void)hand_back;
}

bool owns(const void* block) {
  const char* p = static_cast<const char*>(block);
  return shared.base && p >= shared.base && p < shared.next_page.load(std::memory_order_relaxed);
}

std::size_t class_of(const void* block) {
  return shared
      .page_class[static_cast<std::size_t>(static_cast<const char*>(block) - shared.base) >> kPageShift];
}

// A new page for class `c`; false when the range is used up or cannot be had.
bool new_page(std::size_t c) {
  if (!reserved()) return false;
  if (!cache.registered) {
    register_thread();
    if (cache.free[c] || (cache.cursor[c] && cache.cursor[c] + c * kGranule <= cache.limit[c])) return true;
  }
  char* page = shared.next_page.fetch_add(kPage, std::memory_order_relaxed);
  if (page >= shared.end) return false;
  shared.page_class[static_cast<std::size_t>(page - shared.base) >> kPageShift] =
      static_cast<unsigned char>(c);
  cache.cursor[c] = page;
  cache.limit[c] = page + kPage;
  return true;
}

}  // namespace

void* allocate(std::size_t bytes) noexcept {
  if (bytes > kLargest) return nullptr;
  const std::size_t c = bytes == 0 ? 1 : (bytes + kGranule - 1) / kGranule;
  if (FreeBlock* block = cache.free[c]) {
    cache.free[c] = block->next;
    return block;
  }
  const std::size_t size = c * kGranule;
  if (!cache.cursor[c] || cache.cursor[c] + size > cache.limit[c]) {
    if (!new_page(c)) return nullptr;
    if (FreeBlock* block = cache.free[c]) {  // taken up from a thread that ended
      cache.free[c] = block->next;
      return block;
    }
  }
  void* block = cache.cursor[c];
  cache.cursor[c] += size;
  return block;
}

bool deallocate(void* block) noexcept {
  if (!owns(block)) return false;
  const std::size_t c = class_of(block);
  auto* freed = static_cast<FreeBlock*>(block);
  freed->next = cache.free[c];
  cache.free[c] = freed;
  return true;
}

char* frontier() noexcept {
  return shared.next_page.load(std::memory_order_relaxed);
}

std::size_t block_size(const void* block) noexcept {
  return owns(block) ? class_of(block) * kGranule : 0;
}

char* use_huge_pages() noexcept {
  if (!reserved()) return nullptr;
  // The whole range from the huge page in use: the pages already given out there keep it in small pages
  // (up to 512 faults, each about 10 us on a virtual machine), so it is collapsed into one huge page now
  // (MADV_COLLAPSE, Linux 6.1; without it, that first one stays as it is).
  const auto next = reinterpret_cast<std::uintptr_t>(shared.next_page.load(std::memory_order_relaxed));
  const auto from = next & ~(kHugePage - 1);  // the range starts on a huge page
  const auto to = reinterpret_cast<std::uintptr_t>(shared.end);
  if (madvise(reinterpret_cast<void*>(from), to - from, MADV_HUGEPAGE) != 0) return nullptr;
  if (next > from) madvise(reinterpret_cast<void*>(from), kHugePage, MADV_COLLAPSE);
  return reinterpret_cast<char*>(from);
}

}  // namespace openplx::cli::arena
