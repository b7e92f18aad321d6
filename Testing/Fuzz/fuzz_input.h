// SPDX-License-Identifier: GPL-3.0-or-later
// What the fuzz targets share: reading option bytes and numbers off the front of an input, and
// a scratch file for the readers that take a path.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <unistd.h>
#include <utility>
#include <vector>

namespace mesolens_fuzz {

/// The bytes of one input, consumed from the front. Reading past the end gives zeros.
class FuzzInput
{
public:
  FuzzInput(const std::uint8_t* data, std::size_t size)
    : Data(data)
    , Size(size)
  {
  }

  std::uint8_t byte()
  {
    return Offset < Size ? Data[Offset++] : 0;
  }

  /// A double from the next 8 bytes: any bit pattern, NaN and infinities included.
  double any_double()
  {
    unsigned char bytes[sizeof(double)] = {};
    for (unsigned char& b : bytes)
    {
      b = byte();
    }
    double value;
    std::memcpy(&value, bytes, sizeof value);
    return value;
  }

  /// A double in [low, high] from the next 2 bytes, or (one time in 64) any double.
  double ranged(double low, double high)
  {
    const std::uint8_t choice = byte();
    if (choice >= 252)
    {
      return any_double();
    }
    const double unit = byte() / 255.0;
    return low + (high - low) * unit;
  }

  bool empty() const
  {
    return Offset >= Size;
  }
  std::size_t remaining() const
  {
    return Size - Offset;
  }
  std::string rest()
  {
    std::string bytes(reinterpret_cast<const char*>(Data) + Offset, Size - Offset);
    Offset = Size;
    return bytes;
  }

private:
  const std::uint8_t* Data;
  std::size_t Size;
  std::size_t Offset = 0;
};

/// A file named `stem` + `extension` in /dev/shm (memory) when there is one, else /tmp; one per
/// process and extension, overwritten by every input and removed at exit.
class ScratchFile
{
public:
  explicit ScratchFile(const std::string& extension)
  {
    const char* directory = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
    Path = std::string(directory) + "/mesolens-fuzz-" + std::to_string(getpid()) + extension;
  }
  ~ScratchFile()
  {
    std::remove(Path.c_str());
  }
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;

  /// Writes the bytes and returns the path.
  const std::string& write(const std::string& bytes) const
  {
    if (std::FILE* file = std::fopen(Path.c_str(), "wb"))
    {
      std::fwrite(bytes.data(), 1, bytes.size(), file);
      std::fclose(file);
    }
    return Path;
  }

private:
  std::string Path;
};

/// Stops the run as a defect when a promise of the code under test is broken.
inline void require(bool promise)
{
  if (!promise)
  {
    __builtin_trap();
  }
}

/// Every undirected edge in exactly two triangles, once each way, and no index outside the
/// vertices: a closed, consistently oriented mesh.
inline void require_closed_mesh(std::size_t vertices, const std::vector<std::int64_t>& triangles)
{
  require(triangles.size() % 3 == 0);
  std::map<std::pair<std::int64_t, std::int64_t>, int> directed;
  for (std::size_t t = 0; t < triangles.size(); t += 3)
  {
    for (int k = 0; k < 3; ++k)
    {
      const std::int64_t a = triangles[t + k], b = triangles[t + (k + 1) % 3];
      require(a >= 0 && std::size_t(a) < vertices && a != b);
      require(++directed[{ a, b }] == 1);
    }
  }
  for (const auto& edge : directed)
  {
    require(directed.count({ edge.first.second, edge.first.first }) == 1);
  }
}

} // namespace mesolens_fuzz
