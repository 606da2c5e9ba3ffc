#include "tools/cli/memory/conversion_memory.h"

#include <algorithm>

#include "tools/cli/memory/huge_page_heap.h"

namespace openplx::cli {

namespace {
// Below this a model does not pay for the reservation.
constexpr std::uintmax_t kHugePageInputBytes = 32 << 10;
}  // namespace

void prepare_memory_for_input(std::uintmax_t input_bytes) {
  // A model written out by hand or by a script (boxes, trees) needs a few hundred bytes of heap per byte of
  // text. Capped: only touched pages cost memory, but a reservation need not outgrow any machine.
  // Prefaulted: 48 bytes of small-block arena per byte of text, below the 70-80 a plain model uses
  // (boxes, trees), so that a model that needs less, or text that is mostly comments, gains little
  // resident memory it does not use.
  if (input_bytes < kHugePageInputBytes) return;
  reserve_huge_page_heap(std::min<std::uintmax_t>(input_bytes * 512, 2ull << 30), input_bytes * 48);
}

}  // namespace openplx::cli
