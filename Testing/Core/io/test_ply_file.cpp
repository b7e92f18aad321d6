// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/io/ply_file.h"

#include "mesolens/common/errors.h"
#include "mesolens_test_data.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

namespace {
using mesolens_test::write_bytes;

/// The bytes of `value` in little- or big-endian order.
template<typename T>
std::string bytes_of(T value, bool big_endian = false)
{
  std::string bytes(sizeof(T), '\0');
  std::memcpy(bytes.data(), &value, sizeof(T));
  if (big_endian)
  {
    std::reverse(bytes.begin(), bytes.end());
  }
  return bytes;
}

/// A square (4 vertices) as one quad and one triangle, ascii, with an extra vertex property and
/// an extra element read past.
const char* square_ascii = "ply\n"
                           "format ascii 1.0\n"
                           "comment made by hand\n"
                           "element vertex 4\n"
                           "property float x\n"
                           "property float y\n"
                           "property float z\n"
                           "property uchar red\n"
                           "element face 2\n"
                           "property list uchar int vertex_indices\n"
                           "element edge 1\n"
                           "property int vertex1\n"
                           "property int vertex2\n"
                           "end_header\n"
                           "0 0 0 255\n1 0 0 0\n1 1 0 0\n0 1 0 7\n"
                           "4 0 1 2 3\n3 0 2 3\n"
                           "0 1\n";

/// The same square in binary (`big_endian` or little), uchar counts and int indices.
std::string square_binary(bool big_endian, std::uint32_t claimed_vertices = 4,
                          std::uint8_t first_face_size = 4, std::int32_t last_index = 3)
{
  std::string text = std::string("ply\nformat ") +
    (big_endian ? "binary_big_endian" : "binary_little_endian") + " 1.0\nelement vertex " +
    std::to_string(claimed_vertices) +
    "\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 2\nproperty list uchar int vertex_indices\nend_header\n";
  const float points[4][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 } };
  for (const auto& p : points)
  {
    for (const float v : p)
    {
      text += bytes_of(v, big_endian);
    }
  }
  text += bytes_of(first_face_size, big_endian);
  for (std::int32_t i = 0; i < first_face_size; ++i)
  {
    text += bytes_of(i, big_endian);
  }
  text += bytes_of(std::uint8_t(3), big_endian);
  for (const std::int32_t i : { 0, 2, last_index })
  {
    text += bytes_of(i, big_endian);
  }
  return text;
}

void expect_square(const mesolens::MeshFileContents& mesh)
{
  ASSERT_EQ(mesh.soup.points.size(), 12u);
  EXPECT_EQ(mesh.soup.points[3], 1.0);
  EXPECT_EQ(mesh.soup.points[7], 1.0);
  ASSERT_EQ(mesh.soup.polygons.size(), 2u);
  EXPECT_EQ(mesh.soup.polygons[0], (std::vector<std::int64_t>{ 0, 1, 2, 3 }));
  EXPECT_EQ(mesh.soup.polygons[1], (std::vector<std::int64_t>{ 0, 2, 3 }));
  EXPECT_TRUE(mesh.normals.empty());
}

void expect_refused(const std::string& bytes, const std::string& phrase)
{
  const std::string path = write_bytes("refused.ply", bytes);
  try
  {
    mesolens::read_ply(path);
    ADD_FAILURE() << "accepted a file that should say: " << phrase;
  }
  catch (const mesolens::FileError& e)
  {
    EXPECT_NE(std::string(e.what()).find(phrase), std::string::npos) << e.what();
  }
}
} // namespace

TEST(PlyFile, ReadsTheEmbryoCellsWithTheirNormals)
{
  const auto mesh =
    mesolens::read_ply(mesolens_test::data_file("meshes/celegans_embryo_cell10_T10.ply"));
  EXPECT_EQ(mesh.soup.points.size(), 3u * 727);
  EXPECT_EQ(mesh.soup.polygons.size(), 1450u);
  ASSERT_EQ(mesh.normals.size(), 3u * 727);
  for (std::size_t v = 0; v < 727; ++v)
  {
    const double length =
      std::hypot(mesh.normals[3 * v], mesh.normals[3 * v + 1], mesh.normals[3 * v + 2]);
    EXPECT_NEAR(length, 1.0, 1e-3) << v; // unit normals: the big-endian floats read right
  }
}

TEST(PlyFile, ReadsAsciiAndBothBinaryOrders)
{
  expect_square(mesolens::read_ply(write_bytes("square_ascii.ply", square_ascii)));
  expect_square(mesolens::read_ply(write_bytes("square_little.ply", square_binary(false))));
  expect_square(mesolens::read_ply(write_bytes("square_big.ply", square_binary(true))));
  // Windows line ends in the header.
  std::string crlf;
  for (const char c : std::string(square_ascii))
  {
    crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  }
  expect_square(mesolens::read_ply(write_bytes("square_crlf.ply", crlf)));
}

TEST(PlyFile, FuzzFindingsAreRefused)
{
  // fuzz_ply: an ascii list count of 1.1e23 was converted to an integer for the message
  // (undefined behaviour, UBSan).
  std::string text = square_ascii;
  text.replace(text.find("3 0 2 3"), 1, "1.11111e+23");
  expect_refused(text, "a list of 1.11111e+23 vertex_indices, not a count");
  text = square_ascii;
  text.replace(text.find("3 0 2 3"), 1, "2.5");
  expect_refused(text, "a list of 2.5 vertex_indices, not a count");
  const std::string found =
    std::string(MESOLENS_SOURCE_DIR) + "/Testing/Data/meshes/fuzz_ply_list_count_1e23.ply";
  EXPECT_THROW(mesolens::read_ply(found), mesolens::FileError);
}

TEST(PlyFile, BytesInMemoryReadAsTheFile)
{
  expect_square(mesolens::read_ply_bytes(square_binary(true), "square in memory"));
  try
  {
    mesolens::read_ply_bytes("", "nothing");
    ADD_FAILURE() << "accepted no bytes";
  }
  catch (const mesolens::FileError& e)
  {
    EXPECT_NE(std::string(e.what()).find("nothing: the file is empty"), std::string::npos);
  }
}

TEST(PlyFile, ElementsWithoutPropertiesAreNotLoopedThrough)
{
  // A header claiming 10^18 items of an element with nothing to read must not hang.
  std::string text = square_ascii;
  text.insert(text.find("element face"), "element nothing 1000000000000000000\n");
  expect_square(mesolens::read_ply(write_bytes("square_nothing.ply", text)));
}

TEST(PlyFile, HostileAndBrokenFilesAreRefusedWithTheReason)
{
  EXPECT_THROW(mesolens::read_ply(mesolens_test::output_file("no_such.ply")), mesolens::FileError);
  expect_refused("", "empty");
  expect_refused("solid ascii\n", "not a PLY file");
  expect_refused("ply\nformat ascii 1.0\nelement vertex 3\n", "no end_header");
  expect_refused("ply\nformat utf9 1.0\nend_header\n", "unknown format");
  expect_refused("ply\nformat ascii 1.0\nelement vertex 1\nproperty quaternion x\nend_header\n",
                 "unknown property type");
  expect_refused("ply\nformat ascii 1.0\nproperty float x\nend_header\n",
                 "a property before any element");
  expect_refused("ply\nformat ascii 1.0\nelement vertex -5\nend_header\n",
                 "an element needs a name and a count");
  expect_refused("ply\nelement vertex 1\nproperty float x\nend_header\n0\n", "no format line");
  // Counts the file cannot hold: refused before anything is allocated.
  expect_refused(square_binary(false, 4000000000u), "more than the");
  expect_refused(square_binary(true, 4000000000u), "more than the");
  std::string long_list = square_binary(false);
  long_list[long_list.find("end_header\n") + 11 + 48] = char(250); // a list of 250 ints
  expect_refused(long_list, "a list of 250 vertex_indices, not a count the rest of the file");
  // A truncated body, a bad index, a face of two vertices, a missing element.
  const std::string whole = square_binary(false);
  expect_refused(whole.substr(0, whole.size() - 3), "not a count the rest of the file can hold");
  const std::string ascii = square_ascii;
  expect_refused(ascii.substr(0, ascii.find("3 0 2 3")), "the file ends before");
  expect_refused(square_binary(false, 4, 4, 9), "refers to vertex 9 of 4");
  expect_refused(square_binary(false, 4, 4, -1), "is not a vertex");
  expect_refused(square_binary(false, 4, 2), "a face needs 3 or more");
  std::string text = square_ascii;
  text.replace(text.find("1 1 0 0"), 7, "1 nan 0 0");
  expect_refused(text, "non-finite");
  text = square_ascii;
  text.replace(text.find("1 1 0 0"), 7, "1 one 0 0");
  expect_refused(text, "is not a number");
  expect_refused("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                 "property float z\nend_header\n0 0 0\n",
                 "no faces");
  expect_refused("ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int "
                 "vertex_indices\nend_header\n3 0 1 2\n",
                 "no vertices");
  expect_refused("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n0\n",
                 "needs x, y and z");
  expect_refused("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float "
                 "y\nproperty float z\nelement face 1\nproperty int vertex_indices\nend_header\n"
                 "0 0 0\n1 0 0\n0 1 0\n3\n",
                 "needs a vertex_indices list");
}
