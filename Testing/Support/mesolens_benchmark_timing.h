// SPDX-License-Identifier: GPL-3.0-or-later
// Wall-clock timing for the benchmark programs.
#pragma once

#include <algorithm>
#include <chrono>
#include <functional>
#include <vector>

namespace mesolens_test {

/// Wall time in seconds of one run of `work`.
inline double seconds_of(const std::function<void()>& work)
{
  const auto start = std::chrono::steady_clock::now();
  work();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Median wall time in seconds of `repeats` (>= 1) runs of `work`.
inline double median_seconds(int repeats, const std::function<void()>& work)
{
  std::vector<double> times;
  for (int r = 0; r < std::max(1, repeats); ++r)
  {
    times.push_back(seconds_of(work));
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

} // namespace mesolens_test
