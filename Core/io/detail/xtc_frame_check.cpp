// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/detail/xtc_frame_check.h"

#include "mesolens/common/errors.h"

#include <array>
#include <fstream>
#include <vector>

namespace mesolens {
namespace detail {

namespace {
// Bounds of the table of "magic" small-coordinate sizes in the XTC algorithm: a small-atom
// group is coded with `small_index` bits, small_index in [first_small_index, small_index_end).
constexpr int first_small_index = 9;
constexpr int small_index_end = 73;
constexpr std::uint32_t large_size_limit = 0xffffff;

std::int32_t big_endian_int(const unsigned char* p)
{
  return std::int32_t((std::uint32_t(p[0]) << 24) | (std::uint32_t(p[1]) << 16) |
                      (std::uint32_t(p[2]) << 8) | std::uint32_t(p[3]));
}

/// Bits needed to store `size` values, as the XTC algorithm counts them (GROMACS' sizeofint):
/// its int arithmetic overflows for sizes of 2^30 or more, which then take 32 bits, not 31.
int bits_for(std::uint64_t size)
{
  if (size >= (std::uint64_t(1) << 30))
  {
    return 32;
  }
  int bits = 0;
  while (bits < 32 && (std::uint64_t(1) << bits) <= size)
  {
    ++bits;
  }
  return bits;
}

/// Bits needed to store the product of three sizes (a number up to 72 bits).
int bits_for_product(const std::array<std::uint64_t, 3>& sizes)
{
  unsigned __int128 product = 1;
  for (const std::uint64_t size : sizes)
  {
    product *= size;
  }
  int bits = 0;
  while (product != 0)
  {
    ++bits;
    product >>= 1;
  }
  return bits;
}

/// Most-significant-bit-first reader over the compressed bytes, with a hard end.
class BitReader
{
public:
  BitReader(const std::vector<unsigned char>& bytes)
    : Bytes(bytes)
  {
  }
  bool skip(std::uint64_t bits)
  {
    this->Position += bits;
    return this->Position <= 8 * std::uint64_t(this->Bytes.size());
  }
  bool read(int bits, std::uint32_t& value)
  {
    if (this->Position + std::uint64_t(bits) > 8 * std::uint64_t(this->Bytes.size()))
    {
      return false;
    }
    value = 0;
    for (int b = 0; b < bits; ++b, ++this->Position)
    {
      const unsigned char byte = this->Bytes[std::size_t(this->Position / 8)];
      value = (value << 1) | ((byte >> (7 - this->Position % 8)) & 1u);
    }
    return true;
  }

private:
  const std::vector<unsigned char>& Bytes;
  std::uint64_t Position = 0;
};
} // namespace

void check_xtc_frame(const std::string& path, std::int64_t offset)
{
  auto corrupt = [&](const std::string& why) {
    return FileError(path + ": the frame at byte " + std::to_string(offset) + " is corrupt (" +
                     why + "); it was not decoded");
  };
  std::ifstream file(path, std::ios::binary);
  file.seekg(offset);
  // magic, natoms, step, time, box[9], natoms, precision, minint[3], maxint[3], smallidx, bytes
  std::array<unsigned char, 92> header{};
  if (!file.read(reinterpret_cast<char*>(header.data()), 56))
  {
    throw corrupt("header cut short");
  }
  const std::int32_t atoms = big_endian_int(header.data() + 52);
  if (atoms <= 9)
  {
    return; // stored as plain floats: nothing to decode
  }
  if (!file.read(reinterpret_cast<char*>(header.data() + 56), 36))
  {
    throw corrupt("header cut short");
  }
  std::array<std::int32_t, 3> min_int{};
  std::array<std::int32_t, 3> max_int{};
  std::array<std::uint64_t, 3> sizes{};
  for (int k = 0; k < 3; ++k)
  {
    min_int[std::size_t(k)] = big_endian_int(header.data() + 60 + 4 * k);
    max_int[std::size_t(k)] = big_endian_int(header.data() + 72 + 4 * k);
    const std::int64_t size =
      std::int64_t(max_int[std::size_t(k)]) - std::int64_t(min_int[std::size_t(k)]) + 1;
    if (size < 1 || size > std::int64_t(0x7fffffff))
    {
      throw corrupt("coordinate range is empty or too large");
    }
    sizes[std::size_t(k)] = std::uint64_t(size);
  }
  int small_index = big_endian_int(header.data() + 84);
  const std::int32_t byte_count = big_endian_int(header.data() + 88);
  if (small_index < first_small_index || small_index >= small_index_end)
  {
    throw corrupt("small-coordinate index out of range");
  }
  // GROMACS reads the compressed bytes (padded to 4) into a buffer of 60 ints for up to 16
  // atoms, else of 1.2 ints per coordinate, whose first 3 ints it keeps for itself.
  const std::int64_t coordinates = 3 * std::int64_t(atoms);
  const std::int64_t buffer_ints =
    coordinates <= 48 ? 60 : std::int64_t(static_cast<double>(coordinates) * 1.2);
  if (byte_count < 0 || std::int64_t(byte_count) > 12 * std::int64_t(atoms) + 64 ||
      (std::int64_t(byte_count) + 3) / 4 * 4 > 4 * (buffer_ints - 3))
  {
    throw corrupt("compressed size out of range");
  }
  std::vector<unsigned char> bytes(static_cast<std::size_t>(byte_count));
  if (!file.read(reinterpret_cast<char*>(bytes.data()), byte_count))
  {
    throw corrupt("compressed data cut short");
  }
  const bool large_sizes = (sizes[0] | sizes[1] | sizes[2]) > large_size_limit;
  std::uint64_t large_atom_bits = 0;
  if (large_sizes)
  {
    for (const std::uint64_t size : sizes)
    {
      large_atom_bits += std::uint64_t(bits_for(size));
    }
  }
  else
  {
    large_atom_bits = std::uint64_t(bits_for_product(sizes));
  }
  BitReader bits(bytes);
  std::int64_t decoded = 0;
  std::uint32_t run = 0; // carried over between groups when the flag bit is 0, as in GROMACS
  while (decoded < atoms)
  {
    if (!bits.skip(large_atom_bits))
    {
      throw corrupt("bit stream ends early");
    }
    ++decoded;
    std::uint32_t flag = 0;
    if (!bits.read(1, flag))
    {
      throw corrupt("bit stream ends early");
    }
    int is_smaller = 0;
    if (flag == 1)
    {
      if (!bits.read(5, run))
      {
        throw corrupt("bit stream ends early");
      }
      is_smaller = int(run % 3);
      run -= std::uint32_t(is_smaller);
      --is_smaller;
    }
    const std::int64_t small_atoms = (std::int64_t(run) + 2) / 3;
    if (decoded + small_atoms > atoms)
    {
      throw corrupt("more coordinates than atoms");
    }
    if (!bits.skip(std::uint64_t(small_atoms) * std::uint64_t(small_index)))
    {
      throw corrupt("bit stream ends early");
    }
    decoded += small_atoms;
    small_index += is_smaller;
    if (small_index < first_small_index || small_index >= small_index_end)
    {
      throw corrupt("small-coordinate index out of range");
    }
  }
}

} // namespace detail
} // namespace mesolens
