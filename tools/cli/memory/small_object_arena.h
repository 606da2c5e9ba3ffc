// Small blocks for the converter process: a conversion makes a quarter of a million small objects (slots,
// names, paths, bindings) and frees few of them before it exits. glibc's malloc spends 100-200 instructions
// on each; this arena spends about ten: one reserved address range cut into 16 KiB pages, each page holding
// blocks of one size class (16-byte steps up to 2 KiB), a free list per class for the blocks given back.
//
// Only the openplx2mjcf executable routes operator new and delete here (tools/cli/memory/replace_new.cpp);
// the libraries and tests keep the standard ones. Thread-safe without a lock on the way: each thread has its
// own pages and free lists (a block freed by another thread joins that thread's list), and the caches of
// threads that end are taken up by the next ones.
#pragma once

#include <cstddef>

namespace openplx::cli::arena {

// A block of at least `bytes` bytes, 16-byte aligned; nullptr when the size is not a small one or the
// arena cannot be had (the caller then uses malloc).
void* allocate(std::size_t bytes) noexcept;
// Takes a block back; false when `block` is not from the arena (the caller then frees it).
bool deallocate(void* block) noexcept;
// Asks for transparent huge pages from the huge page in use on (see huge_page_heap.h), that one collapsed
// into a huge page where the kernel can; returns its start (nullptr when there is no range or THP is off).
char* use_huge_pages() noexcept;
// Where the arena's next new page comes from (its pages below are given out).
char* frontier() noexcept;
// The usable size of one of the arena's blocks (its size class); 0 for other pointers.
std::size_t block_size(const void* block) noexcept;

}  // namespace openplx::cli::arena
