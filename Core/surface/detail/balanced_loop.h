// SPDX-License-Identifier: GPL-3.0-or-later
// Parallel loops whose items differ widely in cost (private to MesoLensCore).
#pragma once

#include "mesolens/common/parallel_for.h"

#include <atomic>
#include <cstddef>

namespace mesolens {

/// Runs `work(item, state)` for every item in [0, count), on the threads of `parallel_for`, each
/// thread taking the next item as soon as it is free. A ParallelFor hands out fixed ranges (a
/// quarter of a thread's share, say), which leaves threads idle when a few ranges hold most of
/// the work: the blocks of a grid that the surface crosses, the buried atoms of a protein. Each
/// range's kernel makes one `State` (default-constructible: buffers reused from item to item).
/// What `work` writes must depend on the item alone, so results do not depend on the threads.
template<typename State, typename Work>
void run_balanced(const ParallelFor& parallel_for, std::size_t count, const Work& work)
{
  std::atomic<std::size_t> next{ 0 };
  run_parallel(parallel_for, count, [&](std::size_t /*begin*/, std::size_t /*end*/) {
    State state;
    for (std::size_t item = next.fetch_add(1, std::memory_order_relaxed); item < count;
         item = next.fetch_add(1, std::memory_order_relaxed))
    {
      work(item, state);
    }
  });
}

} // namespace mesolens
