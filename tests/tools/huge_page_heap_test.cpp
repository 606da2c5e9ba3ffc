// The converter's heap set-up (tools/cli/memory/huge_page_heap.h): the arena's pages in use become a huge
// page, a thread faults in memory ahead of where the arena is in use and no further than asked, and what the
// program writes meanwhile is never changed. Each test is a process of its own (ctest runs them one
// by one), so the process-wide malloc settings it makes stay there.
#include <gtest/gtest.h>
#include <sys/mman.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "tools/cli/memory/huge_page_heap.h"
#include "tools/cli/memory/small_object_arena.h"

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

// The AnonHugePages of the mapping that holds `address`, in kB (/proc/self/smaps); -1 when not found.
long huge_kb_of_mapping_at(uintptr_t address) {
  std::ifstream smaps("/proc/self/smaps");
  bool inside = false;
  for (std::string line; std::getline(smaps, line);) {
    unsigned long from = 0, to = 0;
    if (std::sscanf(line.c_str(), "%lx-%lx ", &from, &to) == 2) inside = from <= address && address < to;
    if (inside && line.rfind("AnonHugePages:", 0) == 0) return std::strtol(line.c_str() + 14, nullptr, 10);
  }
  return -1;
}

TEST(HugePageHeap, TheArenasPagesInUseBecomeOneHugePage) {
  if (!huge_pages_available()) GTEST_SKIP() << "no transparent huge pages here";
  auto* before = static_cast<unsigned char*>(cli::arena::allocate(48));
  ASSERT_NE(before, nullptr);
  std::memset(before, 0x5a, 48);
  cli::reserve_huge_page_heap(size_t{64} << 20, 0);
  // Collapsed into a huge page (MADV_COLLAPSE), what was written there kept.
  EXPECT_GE(huge_kb_of_mapping_at(reinterpret_cast<uintptr_t>(before)), 2048);
  EXPECT_EQ(before[47], 0x5a);
}

// Takes 2 KiB blocks until the arena's new pages come from `address` (taking a block does not touch it).
void take_arena_up_to(uintptr_t address) {
  while (reinterpret_cast<uintptr_t>(cli::arena::frontier()) < address)
    ASSERT_NE(cli::arena::allocate(2048), nullptr);
}

TEST(HugePageHeap, PagesAheadOfTheArenaInUseAreFaultedInAndNoFurtherThanAsked) {
  if (!huge_pages_available()) GTEST_SKIP() << "no transparent huge pages here";
  constexpr size_t kPrefault = size_t{8} << 20;
  cli::reserve_huge_page_heap(size_t{64} << 20, kPrefault);
  const uintptr_t first = reinterpret_cast<uintptr_t>(cli::arena::frontier()) & ~(kHugePage - 1);
  take_arena_up_to(first + (size_t{1} << 20));
  // The huge page after the one in use is faulted in without anyone touching it, and no more: a quarter of
  // a second later the one after that is still untouched.
  EXPECT_TRUE(becomes_resident(first + kHugePage + 4096));
  std::this_thread::sleep_for(std::chrono::milliseconds(250));
  EXPECT_FALSE(resident(first + 2 * kHugePage + 4096));
  // In use far up: faulted in up to the limit asked for, not beyond.
  take_arena_up_to(first + (size_t{32} << 20));
  EXPECT_TRUE(becomes_resident(first + kPrefault - 4096));
  std::this_thread::sleep_for(std::chrono::milliseconds(250));
  EXPECT_FALSE(resident(first + kPrefault + 4096));
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
