// SPDX-License-Identifier: GPL-3.0-or-later
// Paths of test inputs, and helpers to make damaged copies of them.
#pragma once

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <sys/stat.h>

namespace mesolens_test {

/// A file under Data/ (in the repository, or under $MESOLENS_DATA_DIR when it is set: a
/// benchmark carried to another machine, scripts/gpu-kit.sh).
inline std::string data_file(const std::string& relative)
{
  const char* moved = std::getenv("MESOLENS_DATA_DIR");
  return std::string(moved && *moved ? moved : MESOLENS_DATA_DIR) + "/" + relative;
}

/// A file under the shared data folder beside the checkout (may be absent).
inline std::string shared_file(const std::string& relative)
{
  return std::string(MESOLENS_SHARED_DATA_DIR) + "/" + relative;
}

inline bool exists(const std::string& path)
{
  struct stat info
  {
  };
  return ::stat(path.c_str(), &info) == 0;
}

/// A path for a file a test writes (under the build's Testing/Output).
inline std::string output_file(const std::string& name)
{
  return std::string(MESOLENS_TEST_OUTPUT_DIR) + "/" + name;
}

inline std::string read_bytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline std::string write_bytes(const std::string& name, const std::string& bytes)
{
  const std::string path = output_file(name);
  std::ofstream out(path, std::ios::binary);
  out << bytes;
  return path;
}

/// Writes the first `bytes` bytes of `source` to an output file and returns its path.
inline std::string truncated_copy(const std::string& source, std::size_t bytes,
                                  const std::string& name)
{
  return write_bytes(name, read_bytes(source).substr(0, bytes));
}

/// Writes `size` bytes of seeded pseudo-random garbage and returns the path.
inline std::string garbage_file(const std::string& name, std::size_t size = 4096)
{
  std::string bytes(size, '\0');
  unsigned state = 12345u;
  for (char& c : bytes)
  {
    state = state * 1103515245u + 12345u;
    c = static_cast<char>((state >> 16) & 0xff);
  }
  return write_bytes(name, bytes);
}

}
