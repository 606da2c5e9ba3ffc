// The converter's heap set-up (tools/cli/huge_page_heap.h): the arena's next pages start on a huge page, a
// thread faults in memory ahead of where the arena is in use and no further than asked, and what the
// program writes meanwhile is never changed. Each test is a process of its own (ctest runs them one
// by one), so the process-wide malloc settings it makes stay there.
#include <gtest/gtest.h>
#include <sys/mman.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "tools/cli/huge_page_heap.h"
#include "tools/cli/small_object_arena.h"

namespace cli = openplx::cli;

namespace {

constexpr uintptr_t kHugePage = 2u << 20;

// Transparent huge pages can be asked for (the kernel's setting is not "never"), outside the sanitizers,
// whose allocator keeps the heap to itself.
bool huge_pages_available() {
#if defined(__SANITIZE_ADDRESS__)
  return false;
#else
  std::ifstream setting("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string text((std::istreambuf_iterator<char>(setting)), std::istreambuf_iterator<char>());
  return !text.empty() && text.find("[never]") == std::string::npos;
#endif
}

bool resident(uintptr_t page) {
  unsigned char in_core = 0;
  return mincore(reinterpret_cast<void*>(page & ~uintptr_t{4095}), 4096, &in_core) == 0 && (in_core & 1);
}

// Waits up to two seconds for `page` to be faulted in.
bool becomes_resident(uintptr_t page) {
  for (int i = 0; i < 200; ++i) {
    if (resident(page)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

TEST(HugePageHeap, TheArenasNextPagesStartOnAHugePage) {
  if (!huge_pages_available()) GTEST_SKIP() << "no transparent huge pages here";
  void* before = cli::arena::allocate(48);
  ASSERT_NE(before, nullptr);
  std::memset(before, 0x5a, 48);
  cli::reserve_huge_page_heap(size_t{64} << 20, 0);
  const auto frontier = reinterpret_cast<uintptr_t>(cli::arena::frontier());
  EXPECT_EQ(frontier % kHugePage, 0u);
  // A size class that had no page yet gets its first one there.
  void* after = cli::arena::allocate(1984);
  ASSERT_NE(after, nullptr);
  EXPECT_GE(reinterpret_cast<uintptr_t>(after), frontier);
  EXPECT_EQ(static_cast<unsigned char*>(before)[47], 0x5a);
}

// Takes 2 KiB blocks until the arena's new pages come from `offset` bytes above `base` (taking a block
// does not touch it).
void take_arena_up_to(uintptr_t base, uintptr_t offset) {
  while (reinterpret_cast<uintptr_t>(cli::arena::frontier()) < base + offset)
    ASSERT_NE(cli::arena::allocate(2048), nullptr);
}

TEST(HugePageHeap, PagesAheadOfTheArenaInUseAreFaultedInAndNoFurtherThanAsked) {
  if (!huge_pages_available()) GTEST_SKIP() << "no transparent huge pages here";
  constexpr size_t kPrefault = size_t{8} << 20;
  cli::reserve_huge_page_heap(size_t{64} << 20, kPrefault);
  const auto base = reinterpret_cast<uintptr_t>(cli::arena::frontier());
  take_arena_up_to(base, size_t{1} << 20);
  // The huge page after the one in use is faulted in without anyone touching it, and no more: a quarter of
  // a second later the one after that is still untouched.
  EXPECT_TRUE(becomes_resident(base + kHugePage + 4096));
  std::this_thread::sleep_for(std::chrono::milliseconds(250));
  EXPECT_FALSE(resident(base + 2 * kHugePage + 4096));
  // In use far up: faulted in up to the limit asked for, not beyond.
  take_arena_up_to(base, size_t{32} << 20);
  EXPECT_TRUE(becomes_resident(base + kPrefault - 4096));
  std::this_thread::sleep_for(std::chrono::milliseconds(250));
  EXPECT_FALSE(resident(base + kPrefault + 4096));
}

TEST(HugePageHeap, WhatTheProgramWritesWhilePagesAreFaultedInStaysWritten) {
  if (!huge_pages_available()) GTEST_SKIP() << "no transparent huge pages here";
  constexpr size_t kPrefault = size_t{48} << 20;
  cli::reserve_huge_page_heap(size_t{128} << 20, kPrefault);
  // Heap and arena blocks written as fast as they are taken, racing the thread that faults pages in.
  std::vector<std::pair<unsigned char*, size_t>> heap_blocks;
  std::vector<unsigned char*> arena_blocks;
  for (int i = 0; i < 400; ++i) {
    const size_t size = 64 << 10;
    auto* heap = static_cast<unsigned char*>(std::malloc(size));
    ASSERT_NE(heap, nullptr);
    std::memset(heap, i & 0xff, size);
    heap_blocks.emplace_back(heap, size);
    for (int k = 0; k < 64; ++k) {
      auto* small = static_cast<unsigned char*>(cli::arena::allocate(1024));
      ASSERT_NE(small, nullptr);
      std::memset(small, (i + k) & 0xff, 1024);
      arena_blocks.push_back(small);
    }
  }
  for (size_t i = 0; i < heap_blocks.size(); ++i) {
    const auto& [heap, size] = heap_blocks[i];
    for (size_t b = 0; b < size; b += 4093) ASSERT_EQ(heap[b], i & 0xff) << i;
  }
  for (size_t j = 0; j < arena_blocks.size(); ++j) {
    const unsigned char expected = static_cast<unsigned char>((j / 64 + j % 64) & 0xff);
    for (size_t b = 0; b < 1024; b += 97) ASSERT_EQ(arena_blocks[j][b], expected) << j;
  }
  for (const auto& [heap, size] : heap_blocks) std::free(heap);
}

}  // namespace
