// SPDX-License-Identifier: GPL-3.0-or-later
// Wall-clock timing for the benchmark programs.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <sstream>
#include <string>
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

/// The items of a comma-separated command-line value ("1,2,3": "1", "2", "3").
inline std::vector<std::string> comma_list(const std::string& text)
{
  std::vector<std::string> items;
  std::stringstream list(text);
  std::string item;
  while (std::getline(list, item, ','))
  {
    items.push_back(item);
  }
  return items;
}

/// The value after `--name` on the command line as an integer >= 1, or `fallback`.
inline int count_argument(int argc, char* argv[], const char* name, int fallback)
{
  for (int i = 1; i + 1 < argc; ++i)
  {
    if (!std::strcmp(argv[i], name))
    {
      return std::max(1, std::atoi(argv[i + 1]));
    }
  }
  return fallback;
}

/// Whether a baseline program runs here (`command` such as "mkdssp --version").
inline bool program_available(const std::string& command)
{
  return std::system((command + " > /dev/null 2>&1").c_str()) == 0;
}

} // namespace mesolens_test
