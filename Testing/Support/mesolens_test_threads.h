// SPDX-License-Identifier: GPL-3.0-or-later
// A ParallelFor on two threads, for tests that results do not depend on the threading.
#pragma once

#include "mesolens/common/parallel_for.h"

#include <thread>

namespace mesolens_test {

/// Runs the first half of the range on a thread of its own, the second on the calling one.
inline mesolens::ParallelFor two_threads()
{
  return [](std::size_t count, const mesolens::RangeKernel& kernel) {
    std::thread other([&] { kernel(0, count / 2); });
    kernel(count / 2, count);
    other.join();
  };
}

} // namespace mesolens_test
