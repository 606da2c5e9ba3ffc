// The converter's small-block arena (tools/cli/memory/small_object_arena.h), which its operator new uses:
// blocks are aligned, as large as asked, never overlap, come back through the free list of their size, and
// larger sizes are left to malloc. The whole converter runs on it in every test that starts the openplx2mjcf
// executable; these hold the arena itself to its contract.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <set>
#include <thread>
#include <vector>

#include "tools/cli/memory/small_object_arena.h"

namespace arena = openplx::cli::arena;

namespace {

TEST(SmallObjectArena, EverySmallSizeGetsAnAlignedBlockAtLeastThatLarge) {
  std::vector<std::pair<unsigned char*, size_t>> blocks;
  for (size_t size = 0; size <= 2048; ++size) {
    auto* block = static_cast<unsigned char*>(arena::allocate(size));
    ASSERT_NE(block, nullptr) << size;
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(block) % 16, 0u) << size;
    EXPECT_GE(arena::block_size(block), std::max<size_t>(size, 1)) << size;
    std::memset(block, static_cast<int>(size & 0xff), size);
    blocks.emplace_back(block, size);
  }
  // Filled one after another, none overwrote another.
  for (const auto& [block, size] : blocks) {
    for (size_t i = 0; i < size; ++i) ASSERT_EQ(block[i], static_cast<unsigned char>(size & 0xff)) << size;
  }
  for (const auto& [block, size] : blocks) EXPECT_TRUE(arena::deallocate(block));
}

TEST(SmallObjectArena, LargerSizesAndForeignPointersAreLeftToMalloc) {
  EXPECT_EQ(arena::allocate(2049), nullptr);
  EXPECT_EQ(arena::allocate(size_t{1} << 20), nullptr);
  void* foreign = std::malloc(64);
  EXPECT_FALSE(arena::deallocate(foreign));
  EXPECT_EQ(arena::block_size(foreign), 0u);
  std::free(foreign);
  EXPECT_FALSE(arena::deallocate(nullptr));
}

TEST(SmallObjectArena, AFreedBlockServesTheNextRequestOfItsSize) {
  void* first = arena::allocate(40);
  ASSERT_NE(first, nullptr);
  ASSERT_TRUE(arena::deallocate(first));
  EXPECT_EQ(arena::allocate(33), first);  // 33 and 40 bytes share the 48-byte class
  void* other = arena::allocate(200);
  EXPECT_NE(other, first);
  EXPECT_TRUE(arena::deallocate(first));
  EXPECT_TRUE(arena::deallocate(other));
}

TEST(SmallObjectArena, ThreadsTakingTurnsNeverGetTheSameBlock) {
  constexpr int kBlocks = 20000;
  std::vector<void*> mine[2];
  auto work = [&](int t) {
    for (int i = 0; i < kBlocks; ++i) {
      void* block = arena::allocate(static_cast<size_t>(16 + (i % 7) * 16));
      std::memcpy(block, &t, sizeof t);
      mine[t].push_back(block);
      if (i % 3 == 0) {  // give some back, so that the free lists are shared too
        ASSERT_TRUE(arena::deallocate(mine[t].back()));
        mine[t].pop_back();
      }
    }
  };
  std::thread a(work, 0), b(work, 1);
  a.join();
  b.join();
  std::set<void*> seen;
  for (int t = 0; t < 2; ++t) {
    for (void* block : mine[t]) {
      EXPECT_TRUE(seen.insert(block).second);
      int owner = -1;
      std::memcpy(&owner, block, sizeof owner);
      EXPECT_EQ(owner, t);
    }
  }
  for (int t = 0; t < 2; ++t) {
    for (void* block : mine[t]) EXPECT_TRUE(arena::deallocate(block));
  }
}

}  // namespace
