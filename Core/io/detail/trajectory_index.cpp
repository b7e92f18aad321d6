// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/detail/trajectory_index.h"

#include "mesolens/common/errors.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <string_view>

namespace mesolens {
namespace detail {

namespace {
constexpr std::int32_t xtc_magic = 1995;
constexpr std::int32_t trr_magic = 1993;

/// Big-endian (XDR) reads from a binary file with explicit end-of-file reporting.
class XdrScanner
{
public:
  explicit XdrScanner(const std::string& path)
    : Path(path)
    , Stream(path, std::ios::binary)
  {
    if (!this->Stream)
    {
      throw FileError(path + ": cannot be opened for reading");
    }
    this->Stream.seekg(0, std::ios::end);
    this->Size = std::int64_t(this->Stream.tellg());
    this->Stream.seekg(0);
  }

  std::int64_t size() const
  {
    return this->Size;
  }
  std::int64_t position()
  {
    return std::int64_t(this->Stream.tellg());
  }
  bool at_end()
  {
    return this->position() >= this->Size;
  }
  bool has(std::int64_t bytes)
  {
    return this->position() + bytes <= this->Size;
  }

  bool read_int(std::int32_t& value)
  {
    std::array<unsigned char, 4> b{};
    if (!this->Stream.read(reinterpret_cast<char*>(b.data()), 4))
    {
      return false;
    }
    value = std::int32_t((std::uint32_t(b[0]) << 24) | (std::uint32_t(b[1]) << 16) |
                         (std::uint32_t(b[2]) << 8) | std::uint32_t(b[3]));
    return true;
  }
  bool read_float(float& value)
  {
    std::int32_t bits = 0;
    if (!this->read_int(bits))
    {
      return false;
    }
    std::memcpy(&value, &bits, 4);
    return true;
  }
  bool read_double(double& value)
  {
    std::int32_t high = 0;
    std::int32_t low = 0;
    if (!this->read_int(high) || !this->read_int(low))
    {
      return false;
    }
    const std::uint64_t bits = (std::uint64_t(std::uint32_t(high)) << 32) | std::uint32_t(low);
    std::memcpy(&value, &bits, 8);
    return true;
  }
  void seek(std::int64_t offset)
  {
    this->Stream.seekg(offset);
  }
  void clear()
  {
    this->Stream.clear();
  }

private:
  std::string Path;
  std::ifstream Stream;
  std::int64_t Size = 0;
};

void check_atom_count(FrameIndex& index, std::int64_t atoms, std::size_t frame,
                      const std::string& path)
{
  if (atoms <= 0)
  {
    throw FileError(path + ": frame " + std::to_string(frame) + " claims " + std::to_string(atoms) +
                    " atoms; the file is corrupt");
  }
  if (index.atom_count < 0)
  {
    index.atom_count = atoms;
  }
  else if (index.atom_count != atoms)
  {
    throw FileError(path + ": frame " + std::to_string(frame) + " has " + std::to_string(atoms) +
                    " atoms but frame 0 has " + std::to_string(index.atom_count));
  }
}

std::string incomplete(std::size_t frame, std::int64_t offset, std::int64_t size)
{
  return "frame " + std::to_string(frame) + " starting at byte " + std::to_string(offset) +
    " is incomplete (the file ends at byte " + std::to_string(size) + ")";
}
/// Reads the magic number that starts a frame. False (and the index's incomplete tail set) when
/// the file ends inside it; throws FileError when it is not `expected` (`format`: "an XTC").
bool read_magic(XdrScanner& file, FrameIndex& index, std::int32_t expected, const char* format,
                const std::string& path)
{
  const std::size_t frame = index.offsets.size();
  const std::int64_t start = file.position();
  std::int32_t magic = 0;
  if (!file.read_int(magic))
  {
    index.incomplete_tail = incomplete(frame, start, file.size());
    return false;
  }
  if (magic != expected)
  {
    throw FileError(path + ": not " + format + " trajectory (frame " + std::to_string(frame) +
                    " at byte " + std::to_string(start) + " has magic number " +
                    std::to_string(magic) + ", expected " + std::to_string(expected) + ")");
  }
  return true;
}
} // namespace

FrameIndex index_xtc(const std::string& path)
{
  XdrScanner file(path);
  FrameIndex index;
  while (!file.at_end())
  {
    const std::size_t frame = index.offsets.size();
    const std::int64_t start = file.position();
    std::int32_t atoms = 0;
    std::int32_t step = 0;
    float time = 0;
    if (!read_magic(file, index, xtc_magic, "an XTC", path))
    {
      break;
    }
    // Header: natoms, step, time, 3x3 box, then natoms again before the coordinates.
    std::int32_t atoms_again = 0;
    bool complete = file.read_int(atoms) && file.read_int(step) && file.read_float(time);
    for (int k = 0; complete && k < 9; ++k)
    {
      float ignored = 0;
      complete = file.read_float(ignored);
    }
    complete = complete && file.read_int(atoms_again);
    if (!complete)
    {
      index.incomplete_tail = incomplete(frame, start, file.size());
      break;
    }
    check_atom_count(index, atoms, frame, path);
    if (atoms_again != atoms)
    {
      throw FileError(path + ": frame " + std::to_string(frame) + " is corrupt (atom counts " +
                      std::to_string(atoms) + " and " + std::to_string(atoms_again) +
                      " in its header)");
    }
    std::int64_t payload = 0;
    if (atoms <= 9)
    {
      payload = 12 * std::int64_t(atoms); // small frames are stored as raw floats
    }
    else
    {
      // precision, minint[3], maxint[3], smallidx, then the byte count of the compressed data.
      std::int32_t skipped = 0;
      for (int k = 0; complete && k < 8; ++k)
      {
        complete = file.read_int(skipped);
      }
      std::int32_t bytes = 0;
      complete = complete && file.read_int(bytes);
      if (!complete)
      {
        index.incomplete_tail = incomplete(frame, start, file.size());
        break;
      }
      if (bytes < 0)
      {
        throw FileError(path + ": frame " + std::to_string(frame) + " is corrupt (negative size)");
      }
      payload = (std::int64_t(bytes) + 3) / 4 * 4;
    }
    if (!file.has(payload))
    {
      index.incomplete_tail = incomplete(frame, start, file.size());
      break;
    }
    file.seek(file.position() + payload);
    index.offsets.push_back(start);
    index.times_ps.push_back(double(time));
  }
  return index;
}

FrameIndex index_trr(const std::string& path)
{
  XdrScanner file(path);
  FrameIndex index;
  while (!file.at_end())
  {
    const std::size_t frame = index.offsets.size();
    const std::int64_t start = file.position();
    if (!read_magic(file, index, trr_magic, "a TRR", path))
    {
      break;
    }
    // Version string: its size + 1, then an XDR string (length, bytes padded to 4).
    std::int32_t size_plus_one = 0;
    std::int32_t length = 0;
    bool complete = file.read_int(size_plus_one) && file.read_int(length);
    if (complete && (length < 0 || length > 128))
    {
      throw FileError(path + ": frame " + std::to_string(frame) + " has a corrupt header");
    }
    complete = complete && file.has((length + 3) / 4 * 4);
    if (complete)
    {
      file.seek(file.position() + (length + 3) / 4 * 4);
    }
    // ir, e, box, vir, pres, top, sym, x, v, f sizes; natoms; step; nre.
    std::array<std::int32_t, 13> fields{};
    for (std::size_t k = 0; complete && k < fields.size(); ++k)
    {
      complete = file.read_int(fields[k]);
    }
    if (!complete)
    {
      index.incomplete_tail = incomplete(frame, start, file.size());
      break;
    }
    const std::int32_t ir = fields[0], energy = fields[1], box = fields[2], vir = fields[3],
                       pres = fields[4], top = fields[5], sym = fields[6], x = fields[7],
                       v = fields[8], f = fields[9], atoms = fields[10];
    check_atom_count(index, atoms, frame, path);
    if (ir != 0 || energy != 0 || top != 0 || sym != 0)
    {
      throw FileError(
        path + ": frame " + std::to_string(frame) +
        " carries input records, energies or a topology, which TRR readers do not support");
    }
    if (x == 0)
    {
      throw FileError(path + ": frame " + std::to_string(frame) + " has no coordinates");
    }
    const std::int64_t real_size = box != 0 ? box / 9 : x / (3 * std::int64_t(atoms));
    if ((real_size != 4 && real_size != 8) || x != 3 * std::int64_t(atoms) * real_size || box < 0 ||
        vir < 0 || pres < 0 || v < 0 || f < 0)
    {
      throw FileError(path + ": frame " + std::to_string(frame) + " has inconsistent sizes");
    }
    double time = 0;
    bool time_ok = false;
    if (real_size == 4)
    {
      float t = 0;
      float lambda = 0;
      time_ok = file.read_float(t) && file.read_float(lambda);
      time = double(t);
    }
    else
    {
      double lambda = 0;
      time_ok = file.read_double(time) && file.read_double(lambda);
    }
    const std::int64_t payload = std::int64_t(box) + vir + pres + x + v + f;
    if (!time_ok || !file.has(payload))
    {
      index.incomplete_tail = incomplete(frame, start, file.size());
      break;
    }
    file.seek(file.position() + payload);
    index.offsets.push_back(start);
    index.times_ps.push_back(time);
  }
  return index;
}

/// The longest line GROMACS' GRO reader takes whole (its STRLEN, less a margin).
constexpr std::size_t longest_gro_line = 4000;

/// Throws FileError unless GROMACS' GRO reader (get_w_conf in groio.cpp) reads this atom line
/// without failing or overrunning its buffers: at least 39 characters; x, y and z each one
/// number in a field of `width` characters from column 21. `width` comes from the frame's first
/// atom line, as GROMACS takes it: the distance between its first two decimal points (anywhere
/// in the line), which must equal the distance between the second and third; at most 32 here
/// (GROMACS copies a field into a buffer of 256). Returns the width when `width` is 0. `where`
/// names the line in a message (called only to build one).
template<typename Where>
std::size_t check_gro_atom_line(std::string_view text, std::size_t width, const Where& where)
{
  if (!text.empty() && text.back() == '\r')
  {
    text.remove_suffix(1);
  }
  if (text.size() < 39 || text.size() > longest_gro_line)
  {
    throw FileError(where() + " has " + std::to_string(text.size()) +
                    " characters: an atom line of a GRO file has at least 39 (names, numbers and "
                    "x, y, z from column 21)");
  }
  constexpr std::size_t widest_field = 32;
  if (width == 0)
  {
    const std::size_t first = text.find('.');
    const std::size_t second = first == text.npos ? first : text.find('.', first + 1);
    const std::size_t third = second == text.npos ? second : text.find('.', second + 1);
    if (third == text.npos || second - first != third - second || second - first > widest_field)
    {
      throw FileError(where() +
                      ": the decimal points of x, y and z are not evenly spaced; GRO is "
                      "a fixed-column format");
    }
    width = second - first;
  }
  std::size_t column = 20;
  for (const char axis : { 'x', 'y', 'z' })
  {
    // strtod needs a terminated string: the field into a buffer of its own.
    char field[widest_field + 1] = {};
    text.substr(std::min(column, text.size()), width).copy(field, width);
    column += width;
    char* end = nullptr;
    std::strtod(field, &end);
    char* after = nullptr;
    std::strtod(end, &after);
    if (end == field || after != end)
    {
      throw FileError(where() + ": " + axis + " is not one number in its " + std::to_string(width) +
                      " columns; GRO is a fixed-column format");
    }
  }
  return width;
}

FrameIndex index_gro(const std::string& path, std::size_t frame_limit)
{
  std::ifstream stream(path, std::ios::binary);
  if (!stream)
  {
    throw FileError(path + ": cannot be opened for reading");
  }
  FrameIndex index;
  std::string line;
  std::int64_t offset = 0;
  while (frame_limit == 0 || index.offsets.size() < frame_limit)
  {
    const std::size_t frame = index.offsets.size();
    const std::int64_t start = offset;
    std::string title;
    if (!std::getline(stream, title))
    {
      break;
    }
    offset += std::int64_t(title.size()) + 1;
    if (title.find_first_not_of(" \t\r") == std::string::npos && stream.peek() == EOF)
    {
      break; // trailing blank line
    }
    std::string count_line;
    if (!std::getline(stream, count_line))
    {
      index.incomplete_tail = incomplete(frame, start, offset);
      break;
    }
    offset += std::int64_t(count_line.size()) + 1;
    char* end = nullptr;
    const long atoms = std::strtol(count_line.c_str(), &end, 10);
    if (end == count_line.c_str())
    {
      throw FileError(path + ": frame " + std::to_string(frame) +
                      " does not give an atom count on its second line; not a GRO file");
    }
    check_atom_count(index, atoms, frame, path);
    bool complete = true;
    std::size_t width = 0; // of the coordinate fields, from the frame's first atom line
    for (long i = 0; i <= atoms && complete; ++i) // atoms lines, then the box line
    {
      complete = bool(std::getline(stream, line));
      offset += std::int64_t(line.size()) + 1;
      if (complete && i < atoms)
      {
        width = check_gro_atom_line(line, width, [&] {
          return path + ": frame " + std::to_string(frame) + ", atom line " + std::to_string(i + 1);
        });
      }
      else if (complete)
      {
        double box[3];
        if (std::sscanf(line.c_str(), "%lf%lf%lf", &box[0], &box[1], &box[2]) != 3 ||
            line.size() > longest_gro_line)
        {
          throw FileError(path + ": frame " + std::to_string(frame) +
                          ": the box line after the atoms does not start with three numbers");
        }
      }
    }
    if (!complete)
    {
      index.incomplete_tail = "frame " + std::to_string(frame) + " starting at byte " +
        std::to_string(start) + " is incomplete (fewer than " + std::to_string(atoms) +
        " atom lines and a box line)";
      break;
    }
    double time = double(frame);
    const auto t = title.find("t=");
    if (t != std::string::npos)
    {
      time = std::strtod(title.c_str() + t + 2, nullptr);
    }
    index.offsets.push_back(start);
    index.times_ps.push_back(time);
  }
  return index;
}

} // namespace detail
} // namespace mesolens
