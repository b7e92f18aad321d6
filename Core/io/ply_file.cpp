// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/io/ply_file.h"

#include "io/detail/file_checks.h"
#include "io/detail/text_fields.h"
#include "mesolens/common/errors.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace mesolens {
namespace {

enum class Format
{
  Ascii,
  LittleEndian,
  BigEndian
};

/// A scalar type of the format, its size in bytes (0: unknown).
struct ScalarType
{
  int bytes = 0;
  bool is_float = false;
  bool is_signed = false;
};

ScalarType scalar_type(const std::string& name)
{
  // The format's type names, old and new.
  static const struct
  {
    const char* old_name;
    const char* new_name;
    ScalarType type;
  } types[] = {
    { "char", "int8", { 1, false, true } },    { "uchar", "uint8", { 1, false, false } },
    { "short", "int16", { 2, false, true } },  { "ushort", "uint16", { 2, false, false } },
    { "int", "int32", { 4, false, true } },    { "uint", "uint32", { 4, false, false } },
    { "float", "float32", { 4, true, true } }, { "double", "float64", { 8, true, true } },
  };
  for (const auto& known : types)
  {
    if (name == known.old_name || name == known.new_name)
    {
      return known.type;
    }
  }
  return {};
}

struct Property
{
  std::string name;
  ScalarType type;
  bool is_list = false;
  ScalarType count_type; ///< lists: the type of their length
};

struct Element
{
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;

  /// The index of the property `name`, or -1.
  int find(const std::string& wanted) const
  {
    for (std::size_t k = 0; k < this->properties.size(); ++k)
    {
      if (this->properties[k].name == wanted)
      {
        return static_cast<int>(k);
      }
    }
    return -1;
  }
};

/// Reads the numbers of the body one by one, ascii or binary, never past its end.
class BodyReader
{
public:
  BodyReader(std::string path, Format format, std::vector<char> body)
    : Path(std::move(path))
    , Kind(format)
    , Body(std::move(body))
  {
  }

  /// Bytes (characters) not read yet.
  std::size_t left() const
  {
    return this->Body.size() - this->At;
  }

  /// The least bytes one value of `type` takes: its size in binary, a digit and a separator
  /// in ascii.
  std::size_t least_bytes(const ScalarType& type) const
  {
    return this->Kind == Format::Ascii ? 2 : std::size_t(type.bytes);
  }

  double read(const ScalarType& type, const char* what)
  {
    return this->Kind == Format::Ascii ? this->read_text(what) : this->read_binary(type, what);
  }

  [[noreturn]] void fail(const std::string& message) const
  {
    throw FileError(this->Path + ": " + message);
  }

private:
  double read_text(const char* what)
  {
    while (this->At < this->Body.size() &&
           std::isspace(static_cast<unsigned char>(this->Body[this->At])))
    {
      ++this->At;
    }
    if (this->At == this->Body.size())
    {
      this->fail(std::string("the file ends before ") + what);
    }
    // A token: up to the next white space (strtod needs a terminated string).
    std::size_t end = this->At;
    while (end < this->Body.size() && !std::isspace(static_cast<unsigned char>(this->Body[end])))
    {
      ++end;
    }
    const std::string token(this->Body.data() + this->At, end - this->At);
    char* parsed_end = nullptr;
    const double value = std::strtod(token.c_str(), &parsed_end);
    if (token.empty() || parsed_end != token.c_str() + token.size())
    {
      this->fail("'" + detail::quoted_field(token) + "' is not a number (" + what + ")");
    }
    this->At = end;
    return value;
  }

  double read_binary(const ScalarType& type, const char* what)
  {
    if (this->left() < std::size_t(type.bytes))
    {
      this->fail(std::string("the file ends before ") + what);
    }
    unsigned char bytes[8];
    std::memcpy(bytes, this->Body.data() + this->At, std::size_t(type.bytes));
    this->At += std::size_t(type.bytes);
    if (this->Kind == Format::BigEndian)
    {
      std::reverse(bytes, bytes + type.bytes);
    }
    // The host is little-endian (x86-64, ARM64 as Linux runs it).
    switch (type.bytes)
    {
      case 1:
        return type.is_signed ? double(static_cast<std::int8_t>(bytes[0])) : double(bytes[0]);
      case 2: {
        std::uint16_t v = 0;
        std::memcpy(&v, bytes, 2);
        return type.is_signed ? double(static_cast<std::int16_t>(v)) : double(v);
      }
      case 4: {
        if (type.is_float)
        {
          float f = 0;
          std::memcpy(&f, bytes, 4);
          return double(f);
        }
        std::uint32_t v = 0;
        std::memcpy(&v, bytes, 4);
        return type.is_signed ? double(static_cast<std::int32_t>(v)) : double(v);
      }
      default: {
        double d = 0;
        std::memcpy(&d, bytes, 8);
        return d;
      }
    }
  }

  std::string Path;
  Format Kind;
  std::vector<char> Body;
  std::size_t At = 0;
};

/// Reads the header; `body_start` gets the offset of the first byte after `end_header`.
std::vector<Element> read_header(const std::string& path, const std::vector<char>& file,
                                 Format& format, std::size_t& body_start)
{
  auto fail = [&](const std::string& message) { throw FileError(path + ": " + message); };
  std::size_t at = 0;
  auto next_line = [&](std::string& line) {
    if (at >= file.size())
    {
      return false;
    }
    const auto end = std::find(file.begin() + std::ptrdiff_t(at), file.end(), '\n');
    line.assign(file.begin() + std::ptrdiff_t(at), end);
    if (!line.empty() && line.back() == '\r')
    {
      line.pop_back();
    }
    at = end == file.end() ? file.size() : std::size_t(end - file.begin()) + 1;
    return true;
  };
  std::string line;
  if (!next_line(line) || line != "ply")
  {
    fail("not a PLY file (it does not start with 'ply')");
  }
  bool have_format = false;
  std::vector<Element> elements;
  for (int number = 2;; ++number)
  {
    if (!next_line(line))
    {
      fail("the header has no end_header");
    }
    if (number > 100000)
    {
      fail("the header runs over 100000 lines");
    }
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    const std::string where = "header line " + std::to_string(number);
    if (keyword == "end_header")
    {
      break;
    }
    if (keyword.empty() || keyword == "comment" || keyword == "obj_info")
    {
      continue;
    }
    if (keyword == "format")
    {
      std::string kind, version;
      words >> kind >> version;
      if (kind == "ascii")
      {
        format = Format::Ascii;
      }
      else if (kind == "binary_little_endian")
      {
        format = Format::LittleEndian;
      }
      else if (kind == "binary_big_endian")
      {
        format = Format::BigEndian;
      }
      else
      {
        fail(where + ": unknown format '" + detail::quoted_field(kind) + "'");
      }
      have_format = true;
    }
    else if (keyword == "element")
    {
      Element element;
      std::string count;
      words >> element.name >> count;
      char* end = nullptr;
      const unsigned long long value = std::strtoull(count.c_str(), &end, 10);
      if (element.name.empty() || count.empty() || *end != '\0' || count[0] == '-')
      {
        fail(where + ": an element needs a name and a count");
      }
      element.count = value;
      elements.push_back(std::move(element));
    }
    else if (keyword == "property")
    {
      if (elements.empty())
      {
        fail(where + ": a property before any element");
      }
      Property property;
      std::string type;
      words >> type;
      if (type == "list")
      {
        std::string count_type, item_type;
        words >> count_type >> item_type >> property.name;
        property.is_list = true;
        property.count_type = scalar_type(count_type);
        property.type = scalar_type(item_type);
        if (property.count_type.bytes == 0 || property.count_type.is_float ||
            property.type.bytes == 0)
        {
          fail(where + ": a list needs an integer count type and a known item type");
        }
      }
      else
      {
        words >> property.name;
        property.type = scalar_type(type);
        if (property.type.bytes == 0)
        {
          fail(where + ": unknown property type '" + detail::quoted_field(type) + "'");
        }
      }
      if (property.name.empty())
      {
        fail(where + ": a property needs a name");
      }
      elements.back().properties.push_back(property);
    }
    else
    {
      fail(where + ": unknown keyword '" + detail::quoted_field(keyword) + "'");
    }
  }
  if (!have_format)
  {
    fail("the header has no format line");
  }
  body_start = at;
  return elements;
}

} // namespace

MeshFileContents read_ply(const std::string& path)
{
  return read_ply_bytes(detail::read_file_bytes(path), path);
}

MeshFileContents read_ply_bytes(const std::string& bytes, const std::string& path)
{
  if (bytes.empty())
  {
    throw FileError(path + ": the file is empty");
  }
  std::vector<char> file(bytes.begin(), bytes.end());
  Format format = Format::Ascii;
  std::size_t body_start = 0;
  const std::vector<Element> elements = read_header(path, file, format, body_start);
  BodyReader body(path, format,
                  std::vector<char>(file.begin() + std::ptrdiff_t(body_start), file.end()));
  file.clear();
  file.shrink_to_fit();

  MeshFileContents mesh;
  std::uint64_t vertex_count = 0;
  bool have_vertices = false;
  for (const Element& element : elements)
  {
    // Every item takes at least the fixed part of its properties (a list at least its count):
    // a count the rest of the file cannot hold is refused before anything is allocated.
    std::size_t least = 0;
    for (const Property& property : element.properties)
    {
      least +=
        property.is_list ? body.least_bytes(property.count_type) : body.least_bytes(property.type);
    }
    if (least > 0 && element.count > body.left() / least)
    {
      body.fail("the header claims " + std::to_string(element.count) + " " + element.name +
                " items, more than the " + std::to_string(body.left()) + " bytes left can hold");
    }
    const bool vertices = element.name == "vertex" || element.name == "vertices";
    const bool faces = element.name == "face" || element.name == "faces";
    const int x = vertices ? element.find("x") : -1;
    const int y = vertices ? element.find("y") : -1;
    const int z = vertices ? element.find("z") : -1;
    const int nx = vertices ? element.find("nx") : -1;
    const int ny = vertices ? element.find("ny") : -1;
    const int nz = vertices ? element.find("nz") : -1;
    const bool with_normals = nx >= 0 && ny >= 0 && nz >= 0;
    int indices = faces ? element.find("vertex_indices") : -1;
    if (faces && indices < 0)
    {
      indices = element.find("vertex_index");
    }
    if (vertices &&
        (x < 0 || y < 0 || z < 0 || element.properties[std::size_t(x)].is_list ||
         element.properties[std::size_t(y)].is_list || element.properties[std::size_t(z)].is_list))
    {
      body.fail("the vertex element needs x, y and z");
    }
    if (faces && (indices < 0 || !element.properties[std::size_t(indices)].is_list))
    {
      body.fail("the face element needs a vertex_indices list");
    }
    if (vertices)
    {
      have_vertices = true;
      vertex_count = element.count;
      mesh.soup.points.reserve(3 * std::size_t(element.count));
      if (with_normals)
      {
        mesh.normals.reserve(3 * std::size_t(element.count));
      }
    }
    if (element.properties.empty())
    {
      continue; // nothing to read, however many items it claims
    }
    std::vector<double> values(element.properties.size());
    std::vector<std::int64_t> polygon;
    const std::string what = element.name + " item";
    for (std::uint64_t item = 0; item < element.count; ++item)
    {
      for (std::size_t k = 0; k < element.properties.size(); ++k)
      {
        const Property& property = element.properties[k];
        if (!property.is_list)
        {
          values[k] = body.read(property.type, what.c_str());
          continue;
        }
        const double length = body.read(property.count_type, what.c_str());
        // (An ascii count is any number: shown as it is, never converted if out of range.)
        if (!(length >= 0) || length != std::floor(length) ||
            length > double(body.left() / body.least_bytes(property.type)))
        {
          std::ostringstream shown;
          shown << length;
          body.fail(element.name + " " + std::to_string(item) + ": a list of " + shown.str() + " " +
                    property.name + ", not a count the rest of the file can hold");
        }
        const bool keep = faces && int(k) == indices;
        if (keep)
        {
          polygon.clear();
        }
        for (std::size_t i = 0; i < std::size_t(length); ++i)
        {
          const double value = body.read(property.type, what.c_str());
          if (keep)
          {
            if (!(value >= 0) || value != std::floor(value) || value >= 9.2e18)
            {
              body.fail("face " + std::to_string(item) + ": vertex index " + std::to_string(value) +
                        " is not a vertex");
            }
            polygon.push_back(static_cast<std::int64_t>(value));
          }
        }
      }
      if (vertices)
      {
        for (const int k : { x, y, z })
        {
          if (!std::isfinite(values[std::size_t(k)]))
          {
            body.fail("vertex " + std::to_string(item) + " has a non-finite coordinate");
          }
          mesh.soup.points.push_back(values[std::size_t(k)]);
        }
        if (with_normals)
        {
          for (const int k : { nx, ny, nz })
          {
            mesh.normals.push_back(values[std::size_t(k)]);
          }
        }
      }
      if (faces)
      {
        if (polygon.size() < 3)
        {
          body.fail("face " + std::to_string(item) + " has " + std::to_string(polygon.size()) +
                    " vertices; a face needs 3 or more");
        }
        mesh.soup.polygons.push_back(polygon);
      }
    }
  }
  if (!have_vertices || vertex_count == 0)
  {
    body.fail("the file has no vertices");
  }
  if (mesh.soup.polygons.empty())
  {
    body.fail("the file has no faces");
  }
  for (std::size_t f = 0; f < mesh.soup.polygons.size(); ++f)
  {
    for (const std::int64_t index : mesh.soup.polygons[f])
    {
      if (std::uint64_t(index) >= vertex_count)
      {
        body.fail("face " + std::to_string(f) + " refers to vertex " + std::to_string(index) +
                  " of " + std::to_string(vertex_count));
      }
    }
  }
  return mesh;
}

} // namespace mesolens
