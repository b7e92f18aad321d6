// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/io/off_file.h"

#include "io/detail/file_checks.h"
#include "io/detail/text_fields.h"
#include "mesolens/common/errors.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace mesolens {
namespace {

/// The words of an OFF file, line by line, without comments.
class OffWords
{
public:
  OffWords(const std::string& bytes, const std::string& name)
    : Bytes(bytes)
    , Name(name)
  {
  }

  /// The words of the next line that has any; false at the end of the file.
  bool next_line(std::vector<std::string_view>& words)
  {
    words.clear();
    while (words.empty() && Position < Bytes.size())
    {
      std::size_t end = Bytes.find('\n', Position);
      if (end == std::string::npos)
      {
        end = Bytes.size();
      }
      std::string_view line(Bytes.data() + Position, end - Position);
      Position = end + 1;
      ++Line;
      words = detail::split_words(line.substr(0, line.find('#')));
    }
    return !words.empty();
  }

  [[noreturn]] void fail(const std::string& what) const
  {
    throw FileError(Name + ": line " + std::to_string(Line) + ": " + what);
  }

  double number(std::string_view word) const
  {
    double value = 0;
    if (!detail::parse_number(word, value) || !std::isfinite(value))
    {
      fail("'" + detail::quoted_field(word) + "' is not a finite number");
    }
    return value;
  }

  /// A count or an index: a whole number in [0, limit).
  std::int64_t whole(std::string_view word, std::int64_t limit, const char* what) const
  {
    long long value = -1;
    if (!detail::parse_integer(word, value) || value < 0 || value >= limit)
    {
      fail(std::string(what) + " '" + detail::quoted_field(word) +
           "' is not a whole number in [0, " + std::to_string(limit) + ")");
    }
    return value;
  }

private:
  const std::string& Bytes;
  const std::string& Name;
  std::size_t Position = 0;
  std::size_t Line = 0;
};

} // namespace

PolygonSoup read_off(const std::string& path)
{
  const std::string bytes = detail::read_file_bytes(path);
  OffWords words(bytes, path);
  std::vector<std::string_view> line;
  if (!words.next_line(line))
  {
    throw FileError(path + ": no OFF header");
  }
  // [ST][C][N]OFF; the 4D and n-dimensional variants are not meshes of 3D points.
  std::string_view header = line.front();
  for (const char* prefix : { "ST", "C", "N" })
  {
    const std::string_view p(prefix);
    if (header.substr(0, p.size()) == p && header.size() > 3)
    {
      header.remove_prefix(p.size());
    }
  }
  if (header != "OFF")
  {
    throw FileError(path + ": '" + detail::quoted_field(line.front()) +
                    "' is not an OFF header (OFF, COFF, NOFF, CNOFF, STOFF ...)");
  }
  std::vector<std::string_view> counts(line.begin() + 1, line.end());
  if (counts.empty() && !words.next_line(counts))
  {
    throw FileError(path + ": no vertex and face counts after the header");
  }
  if (counts.size() < 2)
  {
    words.fail("the counts line needs the vertex and face counts");
  }
  // Each vertex takes at least 6 bytes ("0 0 0\n"), each face at least 8 ("3 0 1 2\n").
  const std::int64_t vertices =
    words.whole(counts[0], std::int64_t(bytes.size() / 6) + 2, "vertex count");
  const std::int64_t faces =
    words.whole(counts[1], std::int64_t(bytes.size() / 8) + 2, "face count");
  PolygonSoup soup;
  soup.points.reserve(3 * std::size_t(vertices));
  for (std::int64_t v = 0; v < vertices; ++v)
  {
    if (!words.next_line(line))
    {
      throw FileError(path + ": the file ends after " + std::to_string(v) + " of " +
                      std::to_string(vertices) + " vertices");
    }
    if (line.size() < 3)
    {
      words.fail("a vertex needs 3 coordinates");
    }
    for (int d = 0; d < 3; ++d)
    {
      soup.points.push_back(words.number(line[std::size_t(d)]));
    }
  }
  soup.polygons.reserve(std::size_t(faces));
  for (std::int64_t f = 0; f < faces; ++f)
  {
    if (!words.next_line(line))
    {
      throw FileError(path + ": the file ends after " + std::to_string(f) + " of " +
                      std::to_string(faces) + " faces");
    }
    const std::int64_t corners = words.whole(line[0], std::int64_t(line.size()), "corner count");
    if (corners < 3)
    {
      words.fail("a face needs at least 3 corners");
    }
    std::vector<std::int64_t> polygon(static_cast<std::size_t>(corners));
    for (std::int64_t k = 0; k < corners; ++k)
    {
      polygon[std::size_t(k)] = words.whole(line[std::size_t(k + 1)], vertices, "vertex index");
    }
    soup.polygons.push_back(std::move(polygon));
  }
  if (soup.polygons.empty())
  {
    throw FileError(path + ": the file holds no faces");
  }
  return soup;
}

} // namespace mesolens
