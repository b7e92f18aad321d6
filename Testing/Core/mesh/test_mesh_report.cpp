// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/mesh/mesh_report.h"

#include "mesolens/common/errors.h"
#include "mesolens/io/off_file.h"
#include "mesolens_test_data.h"
#include "mesolens_test_meshes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <utility>

namespace {
struct Mesh
{
  std::vector<double> points;
  std::vector<std::int64_t> triangles;
  mesolens::MeshReport report() const
  {
    mesolens::TriangleMeshView view;
    view.points = points;
    view.triangles = triangles.data();
    view.triangle_count = triangles.size() / 3;
    return mesolens::mesh_report(view);
  }
};

Mesh tetrahedron()
{
  return { { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1 }, { 0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2 } };
}

Mesh from_off(const std::string& path)
{
  mesolens::TriangleMesh mesh = mesolens_test::fan_triangulated(mesolens::read_off(path));
  return { std::move(mesh.points), std::move(mesh.triangles) };
}
} // namespace

TEST(MeshReport, ClosedTetrahedron)
{
  const auto r = tetrahedron().report();
  EXPECT_EQ(r.triangles, 4u);
  EXPECT_EQ(r.edges, 6u);
  EXPECT_EQ(r.boundary_edges, 0u);
  EXPECT_EQ(r.euler_characteristic, 2);
  EXPECT_EQ(r.components, 1u);
  EXPECT_TRUE(r.is_closed_manifold());
  EXPECT_EQ(r.describe_defects(), "");
}

TEST(MeshReport, OpenTetrahedronHasOneBoundaryLoop)
{
  Mesh mesh = tetrahedron();
  mesh.triangles.resize(9);
  const auto r = mesh.report();
  EXPECT_EQ(r.boundary_edges, 3u);
  EXPECT_EQ(r.boundary_loops, 1u);
  EXPECT_EQ(r.euler_characteristic, 1); // a topological disk
  EXPECT_TRUE(r.is_manifold());
  EXPECT_FALSE(r.is_closed_manifold());
}

TEST(MeshReport, FlippedTriangleIsInconsistent)
{
  Mesh mesh = tetrahedron();
  std::swap(mesh.triangles[0], mesh.triangles[1]);
  const auto r = mesh.report();
  EXPECT_EQ(r.inconsistently_oriented_edges, 3u);
  EXPECT_FALSE(r.is_closed_manifold());
}

TEST(MeshReport, NonManifoldEdgeAndVertex)
{
  // Three triangles around edge (0, 1): a non-manifold edge.
  Mesh fin{ { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1 }, { 0, 1, 2, 1, 0, 3, 0, 1, 4 } };
  auto r = fin.report();
  EXPECT_EQ(r.non_manifold_edges, 1u);
  EXPECT_GE(r.non_manifold_vertices, 2u);
  EXPECT_FALSE(r.is_manifold());
  // Two triangles touching at one vertex only (a bow tie).
  Mesh bowtie{ { 0, 0, 0, 1, 0, 0, 0, 1, 0, -1, 0, 0, 0, -1, 0 }, { 0, 1, 2, 0, 3, 4 } };
  r = bowtie.report();
  EXPECT_EQ(r.non_manifold_edges, 0u);
  EXPECT_EQ(r.non_manifold_vertices, 1u);
  EXPECT_EQ(r.vertex_is_non_manifold[0], 1u);
  EXPECT_EQ(r.components, 2u);
}

TEST(MeshReport, DegenerateAndInvalidTriangles)
{
  Mesh mesh{ { 0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0 }, { 0, 1, 2, 0, 0, 3, 0, 1, 7 } };
  const auto r = mesh.report();
  EXPECT_EQ(r.degenerate_triangles, 2u); // collinear, repeated vertex
  EXPECT_EQ(r.invalid_triangles, 1u);    // index 7 out of range
  EXPECT_EQ(r.triangle_is_degenerate, (std::vector<std::uint8_t>{ 1, 1, 1 }));
  Mesh nan = tetrahedron();
  nan.points[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(nan.report().invalid_triangles, 3u);
}

TEST(MeshReport, EmptyMesh)
{
  const auto r = Mesh{}.report();
  EXPECT_EQ(r.triangles, 0u);
  EXPECT_FALSE(r.is_manifold());
  EXPECT_NE(r.describe_defects().find("no triangles"), std::string::npos);
}

TEST(MeshReport, BadMeshesFromCgal)
{
  auto r = from_off(mesolens_test::data_file("meshes/bad/cgal_cube-ouvert.off")).report();
  EXPECT_EQ(r.boundary_edges, 4u);
  EXPECT_EQ(r.boundary_loops, 1u);
  EXPECT_EQ(r.unreferenced_vertices, 1u);
  r = from_off(mesolens_test::data_file("meshes/bad/cgal_tet-shuffled.off")).report();
  EXPECT_GT(r.inconsistently_oriented_edges, 0u);
  EXPECT_EQ(r.boundary_edges, 0u);
  r = from_off(mesolens_test::data_file("meshes/bad/cgal_tetra_intersected_by_triangle.off"))
        .report();
  EXPECT_EQ(r.components, 2u);
  r = from_off(mesolens_test::data_file("meshes/bad/cgal_degtri_sliding.off")).report();
  EXPECT_GT(r.degenerate_triangles, 0u);
  r = from_off(mesolens_test::data_file("meshes/bad/cgal_triangular_hole.off")).report();
  EXPECT_GE(r.boundary_loops, 2u); // outer border and the hole
  r = from_off(mesolens_test::data_file("meshes/cgal_mesh_with_border.off")).report();
  EXPECT_EQ(r.boundary_edges, 80u);
  EXPECT_TRUE(r.is_manifold());
}

TEST(OffFile, BadFiles)
{
  EXPECT_THROW(mesolens::read_off(mesolens_test::output_file("missing.off")), mesolens::FileError);
  const std::string square = "0 0 0\n1 0 0\n1 1 0\n";
  const struct
  {
    std::string text;
    const char* problem;
  } cases[] = {
    { "", "the file is empty" },
    { "PLY\n3 1 0\n", "'PLY' is not an OFF header" },
    { "4OFF\n3 1 0\n", "'4OFF' is not an OFF header" },
    { "OFF\n", "no vertex and face counts" },
    { "OFF\n3\n", "line 2: the counts line needs" },
    { "OFF\n4 1 0\n0 0 0\n1 0 0\n", "the file ends after 2 of 4 vertices" },
    { "OFF\n3 9 0\n" + square, "face count '9' is not a whole number" },
    { "OFF\n99999 1 0\n" + square, "vertex count '99999' is not a whole number in [0, " },
    { "OFF\n3 1 0\n0 0 nan\n1 0 0\n1 1 0\n3 0 1 2\n", "line 3: 'nan' is not a finite number" },
    { "OFF\n3 1 0\n0 0\n", "a vertex needs 3 coordinates" },
    { "OFF\n3 1 0\n" + square + "2 0 1\n", "a face needs at least 3 corners" },
    { "OFF\n3 1 0\n" + square + "4 0 1 2\n", "corner count '4' is not a whole number" },
    // Found by fuzz_mesh: CGAL's scanner converted -1 to an unsigned index (undefined).
    { "OFF\n3 1 0\n" + square + "3 0 -1 2\n",
      "line 6: vertex index '-1' is not a whole number in [0, 3)" },
    { "OFF\n3 1 0\n" + square + "3 0 1 3\n", "vertex index '3'" },
    { "OFF\n3 1 0\n" + square, "the file ends after 0 of 1 faces" },
    { "OFF\n3 0 0\n" + square, "no faces" },
  };
  for (const auto& c : cases)
  {
    SCOPED_TRACE(c.text);
    try
    {
      mesolens::read_off(mesolens_test::write_bytes("bad.off", c.text));
      ADD_FAILURE() << "accepted";
    }
    catch (const mesolens::FileError& e)
    {
      EXPECT_NE(std::string(e.what()).find(c.problem), std::string::npos) << e.what();
    }
  }
  // Counts on the header line, comments, colours after the coordinates and indices.
  const mesolens::PolygonSoup soup = mesolens::read_off(mesolens_test::write_bytes(
    "variants.off",
    "COFF 3 1 0 # one triangle\n0 0 0 255 0 0\n1 0 0 0 255 0\n1 1 0 0 0 255\n"
    "3 0 1 2 0.5 0.5 0.5\n"));
  ASSERT_EQ(soup.polygons.size(), 1u);
  EXPECT_EQ(soup.points[3], 1.0);
}
