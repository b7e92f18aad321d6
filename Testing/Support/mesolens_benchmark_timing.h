// SPDX-License-Identifier: GPL-3.0-or-later
// Wall-clock timing, medians, process memory and command-line options for the benchmark programs.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
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

/// The median of `values` (not empty; the upper one of an even count).
inline double median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

/// Median wall time in seconds of `repeats` (>= 1) runs of `work`.
inline double median_seconds(int repeats, const std::function<void()>& work)
{
  std::vector<double> times;
  for (int r = 0; r < std::max(1, repeats); ++r)
  {
    times.push_back(seconds_of(work));
  }
  return median(times);
}

/// A memory figure of this process from /proc/self/status (`field`: "VmRSS", "VmHWM", ...), in
/// bytes; 0 where there is none (not Linux).
inline double process_status_bytes(const std::string& field)
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
  {
    if (line.rfind(field + ":", 0) == 0)
    {
      return 1024.0 * std::atof(line.c_str() + field.size() + 1);
    }
  }
  return 0.0;
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

/// The value after `--name` on the command line, or `fallback`.
inline const char* text_argument(int argc, char* argv[], const char* name, const char* fallback)
{
  for (int i = 1; i + 1 < argc; ++i)
  {
    if (!std::strcmp(argv[i], name))
    {
      return argv[i + 1];
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
