// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/io/obj_file.h"

#include "mesolens/common/errors.h"
#include "mesolens_test_data.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

namespace {

using Polygon = std::vector<std::int64_t>;

mesolens::MeshFileContents read(const std::string& text)
{
  return mesolens::read_obj_bytes(text, "test.obj");
}

void expect_refused(const std::string& text, const std::string& phrase)
{
  try
  {
    read(text);
    ADD_FAILURE() << "accepted a file that should say: " << phrase;
  }
  catch (const mesolens::FileError& e)
  {
    EXPECT_NE(std::string(e.what()).find(phrase), std::string::npos) << e.what();
  }
}

} // namespace

TEST(ObjFile, QuadAndTriangleWithEveryCornerForm)
{
  const auto mesh = read("# a square\n"
                         "o square\nv 0 0 0\nv 1 0 0 1.0\nv 1 1 0 0.5 0.5 0.5\nv +0 1e0 0\n"
                         "vt 0 0\nvn 0 0 1\ns off\nusemtl red\n"
                         "f 1 2/1 3//1 4/1/1\n"
                         "f -4 -2 -1 # negative: counted back from the last vertex\n");
  ASSERT_EQ(mesh.soup.points.size(), 12u);
  EXPECT_EQ(mesh.soup.points[3], 1.0);
  EXPECT_EQ(mesh.soup.points[10], 1.0);
  ASSERT_EQ(mesh.soup.polygons.size(), 2u);
  EXPECT_EQ(mesh.soup.polygons[0], (Polygon{ 0, 1, 2, 3 }));
  EXPECT_EQ(mesh.soup.polygons[1], (Polygon{ 0, 2, 3 }));
  EXPECT_TRUE(mesh.normals.empty()); // vertices 1 and 2 have no normal
}

TEST(ObjFile, NormalsWhenEveryUsedVertexHasOne)
{
  const auto mesh = read("vn 0 0 1\nvn 0 0 -1\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\n"
                         "f 1//2 2//1 3//1\nf 1//1 3//2 2//2\n");
  ASSERT_EQ(mesh.normals.size(), 12u);
  EXPECT_EQ(mesh.normals[2], -1.0); // the first corner naming vertex 1 wins
  EXPECT_EQ(mesh.normals[5], 1.0);
  EXPECT_EQ(mesh.normals[8], 1.0);
  EXPECT_EQ(mesh.normals[11], 0.0); // unused vertex
}

TEST(ObjFile, ContinuedLinesAndForwardReferences)
{
  const auto mesh = read("f 1 2 \\\n  3\r\nv 0 0 0\r\nv 1 0 0\r\nv 0 \\\n1 0\r\n");
  ASSERT_EQ(mesh.soup.points.size(), 9u);
  EXPECT_EQ(mesh.soup.points[7], 1.0);
  EXPECT_EQ(mesh.soup.polygons.front(), (Polygon{ 0, 1, 2 }));
}

TEST(ObjFile, RealFileKeepsItsVertices)
{
  const auto mesh =
    mesolens::read_obj(mesolens_test::data_file("meshes/hipsc_cell_membrane_1.obj"));
  EXPECT_EQ(mesh.soup.points.size(), 3u * 1216);
  EXPECT_EQ(mesh.soup.polygons.size(), 2428u);
  EXPECT_EQ(mesh.normals.size(), 3u * 1216);
}

TEST(ObjFile, BadFilesNameTheLine)
{
  const struct
  {
    const char* text;
    const char* phrase;
  } cases[] = {
    { "", "the file is empty" },
    { "# nothing\n", "no vertices" },
    { "v 0 0 0\nv 1 0 0\nv 0 1 0\n", "no faces" },
    { "v 0 0\n", "line 1: 'v' needs 3 numbers" },
    { "v 0 0 0\nv 1 nan 0\n", "line 2: non-finite coordinate 'nan'" },
    { "v 0 0 0\nv 1 inf 0\n", "line 2: non-finite coordinate 'inf'" },
    { "v 0 0 1e999\n", "line 1: '1e999' is not a number" },
    { "v 0 0 0x\n", "line 1: '0x' is not a number" },
    { "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", "line 4: a face needs at least 3 corners" },
    { "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "line 4: vertex index 0" },
    { "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3.5\n", "line 4: '3.5' is not a vertex index" },
    { "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n", "counts back past the 3 read so far" },
    { "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n",
      "line 4: the face refers to vertex 4, but the file has 3 vertices" },
    { "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n", "is not a vertex index" },
    { "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//2 3//1\n", "line 5: normal index 2" },
    { "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/\x01 2 3\n", "'?' is not a texture coordinate index" },
    { "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/2 2 3\n", "line 5: texture coordinate index 2" },
  };
  for (const auto& c : cases)
  {
    SCOPED_TRACE(c.text);
    expect_refused(c.text, c.phrase);
  }
  EXPECT_THROW(mesolens::read_obj(mesolens_test::output_file("missing.obj")), mesolens::FileError);
}
