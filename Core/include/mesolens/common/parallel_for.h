// SPDX-License-Identifier: GPL-3.0-or-later
// How Core runs data-parallel loops without depending on a threading library.
#pragma once

#include <cstddef>
#include <functional>

namespace mesolens {

/// A loop body over the index range [begin, end).
using RangeKernel = std::function<void(std::size_t begin, std::size_t end)>;

/// Runs `kernel` over [0, count), split into ranges that may run concurrently. Core algorithms
/// take one of these so the caller chooses the threads (the VTK layer passes vtkSMPTools::For);
/// an empty ParallelFor runs the whole range on the calling thread. Results never depend on how
/// the range is split.
using ParallelFor = std::function<void(std::size_t count, const RangeKernel& kernel)>;

/// Calls `parallel_for` if set, else kernel(0, count).
inline void run_parallel(const ParallelFor& parallel_for, std::size_t count,
                         const RangeKernel& kernel)
{
  if (count == 0)
  {
    return;
  }
  if (parallel_for)
  {
    parallel_for(count, kernel);
  }
  else
  {
    kernel(0, count);
  }
}

} // namespace mesolens
