// SPDX-License-Identifier: GPL-3.0-or-later
// What the fuzz targets share: reading option bytes and numbers off the front of an input, and
// a scratch file for the readers that take a path.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <unistd.h>

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

} // namespace mesolens_fuzz
