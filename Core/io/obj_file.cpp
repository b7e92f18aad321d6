// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/io/obj_file.h"

#include "io/detail/file_checks.h"
#include "io/detail/text_fields.h"
#include "mesolens/common/errors.h"

#include <cctype>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace mesolens {
namespace {

/// Parses one OBJ file, a record at a time.
class ObjParser
{
public:
  explicit ObjParser(const std::string& name)
    : Name(name)
  {
  }

  void record(std::string_view line, std::size_t line_number)
  {
    Line = line_number;
    const std::vector<std::string_view> words = detail::split_words(line);
    if (words.empty())
    {
      return;
    }
    if (words[0] == "v")
    {
      vertex(words, Mesh.soup.points, 3);
    }
    else if (words[0] == "vn")
    {
      vertex(words, Normals, 3);
    }
    else if (words[0] == "vt")
    {
      std::vector<double> coordinates;
      vertex(words, coordinates, 1);
      ++TextureCoordinates;
    }
    else if (words[0] == "f" || words[0] == "fo")
    {
      face(words);
    }
  }

  MeshFileContents finish()
  {
    const std::int64_t vertices = vertex_count();
    if (vertices == 0)
    {
      throw FileError(Name + ": no vertices ('v' records)");
    }
    if (Mesh.soup.polygons.empty())
    {
      throw FileError(Name + ": no faces ('f' records)");
    }
    for (std::size_t f = 0; f < Mesh.soup.polygons.size(); ++f)
    {
      for (const std::int64_t index : Mesh.soup.polygons[f])
      {
        if (index >= vertices)
        {
          throw FileError(Name + ": line " + std::to_string(FaceLines[f]) +
                          ": the face refers to vertex " + std::to_string(index + 1) +
                          ", but the file has " + std::to_string(vertices) + " vertices");
        }
      }
    }
    finish_normals(vertices);
    return std::move(Mesh);
  }

private:
  [[noreturn]] void fail(const std::string& what) const
  {
    throw FileError(Name + ": line " + std::to_string(Line) + ": " + what);
  }

  std::int64_t vertex_count() const
  {
    return std::int64_t(Mesh.soup.points.size() / 3);
  }

  /// Appends the first `components` numbers of a v or vn record; later numbers (w, colours)
  /// must parse but are not kept.
  void vertex(const std::vector<std::string_view>& words, std::vector<double>& into,
              std::size_t components)
  {
    if (words.size() < components + 1)
    {
      fail("'" + std::string(words[0]) + "' needs " + std::to_string(components) + " numbers");
    }
    for (std::size_t k = 1; k < words.size(); ++k)
    {
      const double value = number(words[k]);
      if (k <= components)
      {
        into.push_back(value);
      }
    }
  }

  double number(std::string_view word) const
  {
    double value = 0.0;
    if (!detail::parse_number(word, value))
    {
      fail("'" + detail::quoted_field(word) + "' is not a number");
    }
    if (!std::isfinite(value))
    {
      fail("non-finite coordinate '" + detail::quoted_field(word) + "'");
    }
    return value;
  }

  /// A 0-based index from a 1-based or negative (relative) one; `count` is how many exist now.
  std::int64_t index(std::string_view word, std::int64_t count, const char* what) const
  {
    long long value = 0;
    if (!detail::parse_integer(word, value))
    {
      fail("'" + detail::quoted_field(word) + "' is not a " + what + " index");
    }
    if (value == 0)
    {
      fail(std::string(what) + " index 0 (indices start at 1)");
    }
    if (value < 0)
    {
      if (-value > count)
      {
        fail(std::string(what) + " index " + std::to_string(value) + " counts back past the " +
             std::to_string(count) + " read so far");
      }
      return count + value;
    }
    return value - 1;
  }

  void face(const std::vector<std::string_view>& words)
  {
    if (words.size() < 4)
    {
      fail("a face needs at least 3 corners");
    }
    std::vector<std::int64_t> polygon;
    polygon.reserve(words.size() - 1);
    for (std::size_t k = 1; k < words.size(); ++k)
    {
      const std::string_view corner = words[k];
      const std::size_t slash = corner.find('/');
      const std::int64_t vertex = index(corner.substr(0, slash), vertex_count(), "vertex");
      polygon.push_back(vertex);
      const std::size_t second =
        slash == std::string_view::npos ? slash : corner.find('/', slash + 1);
      if (slash != std::string_view::npos)
      {
        const std::string_view texture = corner.substr(slash + 1, second - slash - 1);
        if (!texture.empty() &&
            index(texture, TextureCoordinates, "texture coordinate") >= TextureCoordinates)
        {
          fail("texture coordinate index " + detail::quoted_field(texture) + " past the " +
               std::to_string(TextureCoordinates) + " read so far");
        }
      }
      if (second != std::string_view::npos && second + 1 < corner.size())
      {
        const std::int64_t normal =
          index(corner.substr(second + 1), std::int64_t(Normals.size() / 3), "normal");
        if (normal >= std::int64_t(Normals.size() / 3))
        {
          fail("normal index " + std::to_string(normal + 1) + " past the " +
               std::to_string(Normals.size() / 3) + " normals read so far");
        }
        if (std::size_t(vertex) >= NormalOf.size())
        {
          NormalOf.resize(std::size_t(vertex) + 1, -1);
        }
        if (NormalOf[std::size_t(vertex)] < 0)
        {
          NormalOf[std::size_t(vertex)] = normal;
        }
      }
    }
    Mesh.soup.polygons.push_back(std::move(polygon));
    FaceLines.push_back(Line);
  }

  /// Normals per vertex when every vertex used by a face has one.
  void finish_normals(std::int64_t vertices)
  {
    if (Normals.empty())
    {
      return;
    }
    NormalOf.resize(std::size_t(vertices), -1);
    std::vector<bool> used(std::size_t(vertices), false);
    for (const auto& polygon : Mesh.soup.polygons)
    {
      for (const std::int64_t index : polygon)
      {
        used[std::size_t(index)] = true;
        if (NormalOf[std::size_t(index)] < 0)
        {
          return;
        }
      }
    }
    Mesh.normals.assign(3 * std::size_t(vertices), 0.0);
    for (std::size_t v = 0; v < std::size_t(vertices); ++v)
    {
      if (used[v])
      {
        for (std::size_t d = 0; d < 3; ++d)
        {
          Mesh.normals[3 * v + d] = Normals[3 * std::size_t(NormalOf[v]) + d];
        }
      }
    }
  }

  std::string Name;
  std::size_t Line = 0;
  MeshFileContents Mesh;
  std::vector<double> Normals;         ///< the vn records, 3 per normal
  std::int64_t TextureCoordinates = 0; ///< vt records read so far
  std::vector<std::int64_t> NormalOf;  ///< per vertex, the first vn index a corner gave, or -1
  std::vector<std::size_t> FaceLines;  ///< per face, its line (for messages)
};

} // namespace

MeshFileContents read_obj(const std::string& path)
{
  return read_obj_bytes(detail::read_file_bytes(path), path);
}

MeshFileContents read_obj_bytes(const std::string& bytes, const std::string& name)
{
  if (bytes.empty())
  {
    throw FileError(name + ": the file is empty");
  }
  ObjParser parser(name);
  std::string record; // a record continued over lines by trailing backslashes
  std::size_t record_line = 0;
  std::size_t line_number = 0;
  for (std::size_t start = 0; start < bytes.size();)
  {
    std::size_t end = bytes.find('\n', start);
    if (end == std::string::npos)
    {
      end = bytes.size();
    }
    ++line_number;
    std::string_view line(bytes.data() + start, end - start);
    start = end + 1;
    const std::size_t comment = line.find('#');
    line = line.substr(0, comment);
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back())))
    {
      line.remove_suffix(1);
    }
    if (record.empty())
    {
      record_line = line_number;
    }
    if (!line.empty() && line.back() == '\\' && comment == std::string_view::npos)
    {
      record.append(line.substr(0, line.size() - 1));
      record.push_back(' ');
      continue;
    }
    if (record.empty())
    {
      parser.record(line, record_line);
    }
    else
    {
      record.append(line);
      parser.record(record, record_line);
      record.clear();
    }
  }
  if (!record.empty())
  {
    parser.record(record, record_line);
  }
  return parser.finish();
}

} // namespace mesolens
