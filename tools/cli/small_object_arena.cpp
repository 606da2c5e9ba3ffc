#include "tools/cli/small_object_arena.h"

#include <sys/mman.h>

#include <atomic>
#include <cstdint>

namespace openplx::cli::arena {
namespace {

constexpr std::size_t kGranule = 16;
constexpr std::size_t kLargest = 2048;  // larger blocks go to malloc
constexpr std::size_t kClasses = kLargest / kGranule + 1;
constexpr std::size_t kPageShift = 16;  // 64 KiB pages, each of one size class
constexpr std::size_t kPage = std::size_t{1} << kPageShift;
// Address space only: untouched pages cost nothing. Without room for it (strict overcommit), malloc is used.
constexpr std::size_t kReserved = std::size_t{16} << 30;
constexpr std::size_t kPages = kReserved / kPage;

struct FreeBlock {
  FreeBlock* next;
};

struct Arena {
  std::atomic_flag busy = ATOMIC_FLAG_INIT;
  bool tried = false;
  char* base = nullptr;
  char* next_page = nullptr;  // pages below it have a class
  char* end = nullptr;
  char* cursor[kClasses] = {};  // the unused rest of each class's newest page
  char* limit[kClasses] = {};
  FreeBlock* free[kClasses] = {};
  unsigned char page_class[kPages] = {};
};

Arena arena;  // zero-initialised: no constructor runs before main's first allocation

class Lock {
 public:
  Lock() {
    while (arena.busy.test_and_set(std::memory_order_acquire)) {
    }
  }
  ~Lock() { arena.busy.clear(std::memory_order_release); }
};

bool reserve() {
  arena.tried = true;
  void* range =
      mmap(nullptr, kReserved, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
  if (range == MAP_FAILED) return false;
  arena.base = static_cast<char*>(range);
  arena.next_page = arena.base;
  arena.end = arena.base + kReserved;
  return true;
}

bool owns(const void* block) {
  const char* p = static_cast<const char*>(block);
  return arena.base && p >= arena.base && p < arena.next_page;
}

}  // namespace

void* allocate(std::size_t bytes) noexcept {
  if (bytes > kLargest) return nullptr;
  const std::size_t c = bytes == 0 ? 1 : (bytes + kGranule - 1) / kGranule;
  Lock lock;
  if (FreeBlock* block = arena.free[c]) {
    arena.free[c] = block->next;
    return block;
  }
  const std::size_t size = c * kGranule;
  if (!arena.cursor[c] || arena.cursor[c] + size > arena.limit[c]) {
    if (!arena.base && (arena.tried || !reserve())) return nullptr;
    if (arena.next_page == arena.end) return nullptr;
    char* page = arena.next_page;
    arena.next_page += kPage;
    arena.page_class[static_cast<std::size_t>(page - arena.base) >> kPageShift] =
        static_cast<unsigned char>(c);
    arena.cursor[c] = page;
    arena.limit[c] = page + kPage;
  }
  void* block = arena.cursor[c];
  arena.cursor[c] += size;
  return block;
}

bool deallocate(void* block) noexcept {
  if (!owns(block)) return false;
  Lock lock;
  const std::size_t c =
      arena.page_class[static_cast<std::size_t>(static_cast<char*>(block) - arena.base) >> kPageShift];
  auto* freed = static_cast<FreeBlock*>(block);
  freed->next = arena.free[c];
  arena.free[c] = freed;
  return true;
}

std::size_t block_size(const void* block) noexcept {
  if (!owns(block)) return 0;
  return arena.page_class[static_cast<std::size_t>(static_cast<const char*>(block) - arena.base) >>
                          kPageShift] *
         kGranule;
}

void use_huge_pages() noexcept {
  Lock lock;
  if (!arena.base && (arena.tried || !reserve())) return;
  // From the next page not yet given out, rounded up to a huge page: what is in use keeps its pages.
  constexpr std::uintptr_t kHugePage = std::uintptr_t{2} << 20;
  const auto from = (reinterpret_cast<std::uintptr_t>(arena.next_page) + kHugePage - 1) & ~(kHugePage - 1);
  const auto to = reinterpret_cast<std::uintptr_t>(arena.end) & ~(kHugePage - 1);
  if (to > from) madvise(reinterpret_cast<void*>(from), to - from, MADV_HUGEPAGE);
}

}  // namespace openplx::cli::arena
