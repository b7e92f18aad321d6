// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/common/errors.h"
#include "mesolens/cutaway/structure_mesh.h"
#include "mesolens_test_meshes.h"
#include "mesolens_test_threads.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace {
constexpr double pi = 3.14159265358979323846;

std::vector<double> sphere_points(int count, double radius)
{
  return mesolens_test::fibonacci_sphere(count, radius);
}

/// Every angle within the structure mesh's bound, one component.
void expect_one_even_sheet(const mesolens::MeshQuality& quality)
{
  EXPECT_GE(quality.min_angle, mesolens::structure_mesh_min_angle);
  EXPECT_LE(quality.max_angle, mesolens::structure_mesh_max_angle);
  EXPECT_EQ(quality.components, 1u);
}

double radius_of(const std::array<double, 3>& p)
{
  return std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
}

/// The middle of the two leaflets below: a wave of 3 Å along x, periodic in the box.
double middle_height(double x)
{
  return 50.0 + 3.0 * std::sin(2 * pi * x / 100.0);
}

/// Two leaflets of a bilayer in a 100 x 90 Å patch (2.0 Å of noise, seeded), `gap` Å apart
/// about middle_height(): lipid centres (gap 20) or head groups (gap 40). 64 Å^2 per point.
std::vector<double> two_noisy_leaflets(double gap, unsigned seed)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> across(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, 2.0);
  std::vector<double> points;
  for (int leaflet = 0; leaflet < 2; ++leaflet)
  {
    for (int i = 0; i < 140; ++i)
    {
      const double x = 100.0 * across(random);
      const double y = 90.0 * across(random);
      const double side = leaflet == 0 ? -0.5 : 0.5;
      points.insert(points.end(), { x, y, middle_height(x) + side * gap + noise(random) });
    }
  }
  return points;
}

mesolens::PeriodicBox patch_box()
{
  mesolens::PeriodicBox box;
  box.vectors = { { { 100, 0, 0 }, { 0, 90, 0 }, { 0, 0, 120 } } };
  return box;
}
} // namespace

TEST(StructureMesh, QualityOfAnEquilateralTriangle)
{
  mesolens::TriangleMesh triangle;
  triangle.points = { 0, 0, 0, 2, 0, 0, 1, std::sqrt(3.0), 0 };
  triangle.triangles = { 0, 1, 2 };
  const auto quality = mesolens::mesh_quality(triangle);
  EXPECT_NEAR(quality.min_angle, 60, 1e-9);
  EXPECT_NEAR(quality.max_angle, 60, 1e-9);
  EXPECT_NEAR(quality.mean_edge, 2, 1e-12);
  EXPECT_NEAR(quality.edge_spread, 0, 1e-7);
  EXPECT_EQ(quality.boundary_edges, 3u);
  EXPECT_EQ(quality.boundary_loops, 1u);
  EXPECT_EQ(quality.components, 1u);
}

TEST(StructureMesh, ClosedEvenMeshOfTheRequestedSizeThroughASphereOfPoints)
{
  mesolens::MeshQuality quality;
  const auto mesh = mesolens::structure_mesh(sphere_points(3000, 10.0), { 300, 0 }, &quality);
  const std::size_t v = mesh.vertex_count();
  const std::size_t f = mesh.triangle_count();
  EXPECT_GT(v, 255u);
  EXPECT_LT(v, 345u);
  EXPECT_EQ(quality.boundary_edges, 0u);             // closed
  EXPECT_EQ(long(v) - long(3 * f / 2) + long(f), 2); // Euler characteristic of a sphere
  expect_one_even_sheet(quality);
  EXPECT_LT(quality.edge_spread, 0.35);
  for (std::size_t i = 0; i < v; ++i)
  {
    EXPECT_NEAR(radius_of(mesh.point(std::int64_t(i))), 10.0, 0.6);
  }
  // A target edge length instead of a vertex count.
  const auto coarse = mesolens::structure_mesh(sphere_points(3000, 10.0), { 0, 4.0 }, &quality);
  EXPECT_LT(coarse.vertex_count(), v);
  EXPECT_NEAR(quality.mean_edge, 4.0, 1.2);
  expect_one_even_sheet(quality);
}

TEST(StructureMesh, ABilayerVesicleGivesOneMeshThroughItsMiddle)
{
  // Lipid centres of both leaflets, 24 apart, 8 apart in each: one closed sheet at the
  // middle, not two.
  auto points = sphere_points(700, 60.0);
  const auto outer = sphere_points(1400, 84.0);
  points.insert(points.end(), outer.begin(), outer.end());
  mesolens::MeshQuality quality;
  const auto mesh = mesolens::structure_mesh(points, { 200, 0 }, &quality);
  const std::size_t v = mesh.vertex_count();
  const std::size_t f = mesh.triangle_count();
  EXPECT_GT(v, 170u);
  EXPECT_LT(v, 230u);
  EXPECT_EQ(quality.boundary_edges, 0u);
  EXPECT_EQ(long(v) - long(3 * f / 2) + long(f), 2);
  expect_one_even_sheet(quality);
  EXPECT_LT(quality.edge_spread, 0.25);
  for (std::size_t i = 0; i < v; ++i)
  {
    EXPECT_NEAR(radius_of(mesh.point(std::int64_t(i))), 72.0, 2.5);
  }
  // The same mesh every time, on one thread or two.
  const auto two_threads = mesolens_test::two_threads();
  for (int again = 0; again < 3; ++again)
  {
    const auto same = mesolens::structure_mesh(points, { 200, 0 }, nullptr, two_threads);
    EXPECT_EQ(same.points, mesh.points);
    EXPECT_EQ(same.triangles, mesh.triangles);
  }
}

TEST(StructureMesh, TwoConcentricSpheresOfHeadGroupsGiveOneSphereOfTheMeanRadius)
{
  // Head groups only: inner leaflet at 60 Å, outer at 100 Å, 64 Å^2 each, 1.5 Å of radial
  // noise. Their middle is the sphere of 80 Å (a mid-surface of each leaflet would be two).
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 1.5);
  std::vector<double> points;
  for (const auto& [count, radius] : { std::pair<int, double>{ 700, 60.0 }, { 1960, 100.0 } })
  {
    const auto leaflet = sphere_points(count, radius);
    for (std::size_t i = 0; i < leaflet.size(); i += 3)
    {
      const double scale = (radius + noise(random)) / radius;
      points.insert(points.end(),
                    { leaflet[i] * scale, leaflet[i + 1] * scale, leaflet[i + 2] * scale });
    }
  }
  for (const std::size_t vertices : { 20u, 400u })
  {
    mesolens::MeshQuality quality;
    const auto mesh = mesolens::structure_mesh(points, { vertices, 0 }, &quality);
    expect_one_even_sheet(quality);
    EXPECT_EQ(quality.boundary_loops, 0u);
    const std::size_t v = mesh.vertex_count();
    const std::size_t f = mesh.triangle_count();
    EXPECT_EQ(long(v) - long(3 * f / 2) + long(f), 2);
    EXPECT_NEAR(double(v), double(vertices), 0.15 * double(vertices));
    double sum = 0;
    for (std::size_t i = 0; i < v; ++i)
    {
      const double r = radius_of(mesh.point(std::int64_t(i)));
      EXPECT_NEAR(r, 80.0, 4.0) << vertices;
      sum += r;
    }
    EXPECT_NEAR(sum / double(v), 80.0, 2.0) << vertices;
  }
}

TEST(StructureMesh, TwoNoisyPlanesInAPeriodicBoxGiveOneOpenSheetAtTheMidPlane)
{
  for (const double gap : { 20.0, 40.0 }) // lipid centres, head groups
  {
    mesolens::StructureMeshParams params;
    params.vertices = 300;
    params.box = patch_box();
    mesolens::MeshQuality quality;
    const auto mesh = mesolens::structure_mesh(two_noisy_leaflets(gap, 11), params, &quality);
    expect_one_even_sheet(quality);
    EXPECT_EQ(quality.boundary_loops, 1u) << gap;
    EXPECT_NEAR(double(mesh.vertex_count()), 300.0, 45.0) << gap;
    double lowest[2] = { 1e9, 1e9 }, highest[2] = { -1e9, -1e9 };
    double off = 0;
    for (std::size_t i = 0; i < mesh.vertex_count(); ++i)
    {
      const auto p = mesh.point(std::int64_t(i));
      for (int d = 0; d < 2; ++d)
      {
        lowest[d] = std::min(lowest[d], p[d]);
        highest[d] = std::max(highest[d], p[d]);
      }
      off += std::abs(p[2] - middle_height(p[0])) / double(mesh.vertex_count());
      EXPECT_NEAR(p[2], middle_height(p[0]), 3.0) << gap;
    }
    EXPECT_LT(off, 1.2) << gap;
    // Spanning the patch (the sides along the second box vector zigzag by half an edge).
    EXPECT_GT(highest[0] - lowest[0], 100.0 - 1e-6) << gap;
    EXPECT_NEAR(highest[1] - lowest[1], 90.0, 1e-6) << gap;
  }
}

TEST(StructureMesh, TwoNoisyPlanesWithoutABoxGiveOneOpenSheetToo)
{
  mesolens::MeshQuality quality;
  const auto mesh = mesolens::structure_mesh(two_noisy_leaflets(40.0, 5), { 150, 0 }, &quality);
  expect_one_even_sheet(quality);
  EXPECT_GE(quality.boundary_loops, 1u);
  double off = 0;
  for (std::size_t i = 0; i < mesh.vertex_count(); ++i)
  {
    const auto p = mesh.point(std::int64_t(i));
    off += std::abs(p[2] - middle_height(p[0])) / double(mesh.vertex_count());
  }
  EXPECT_LT(off, 2.0);
}

TEST(StructureMesh, StraysFarFromTheMembraneAreLeftOut)
{
  auto points = two_noisy_leaflets(20.0, 3);
  for (int i = 0; i < 6; ++i)
  {
    points.insert(points.end(), { 15.0 * i, 40.0, 110.0 }); // in the water, far apart
  }
  mesolens::StructureMeshParams params;
  params.box = patch_box();
  params.vertices = 200;
  mesolens::MeshQuality quality;
  const auto mesh = mesolens::structure_mesh(points, params, &quality);
  expect_one_even_sheet(quality);
  for (std::size_t i = 0; i < mesh.vertex_count(); ++i)
  {
    EXPECT_NEAR(mesh.point(std::int64_t(i))[2], middle_height(mesh.point(std::int64_t(i))[0]), 3.0);
  }
}

TEST(StructureMesh, AnOpenPatchKeepsItsBorder)
{
  std::vector<double> plane;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j)
      plane.insert(plane.end(), { double(i), double(j), 0.05 * std::sin(i * 0.7 + j) });
  mesolens::MeshQuality quality;
  const auto mesh = mesolens::structure_mesh(plane, { 200, 0 }, &quality);
  EXPECT_GT(mesh.triangle_count(), 100u);
  EXPECT_GT(quality.boundary_edges, 20u);
  EXPECT_EQ(quality.boundary_loops, 1u);
  expect_one_even_sheet(quality);
}

TEST(StructureMesh, BadInputs)
{
  EXPECT_THROW(mesolens::structure_mesh({}, { 100, 0 }), mesolens::InvalidInput);
  EXPECT_THROW(
    mesolens::structure_mesh(std::vector<double>{ 0, 0, 0, 1, 0, 0, 0, 1, 0 }, { 100, 0 }),
    mesolens::InvalidInput);
  auto points = sphere_points(200, 1.0);
  EXPECT_THROW(mesolens::structure_mesh(points, { 3, 0 }), mesolens::InvalidInput);
  EXPECT_THROW(mesolens::structure_mesh(points, { 1000001, 0 }), mesolens::InvalidInput);
  EXPECT_THROW(mesolens::structure_mesh(points, { 100, -1.0 }), mesolens::InvalidInput);
  EXPECT_THROW(mesolens::structure_mesh(points, { 100, std::nan("") }), mesolens::InvalidInput);
  points[7] = std::nan("");
  EXPECT_THROW(mesolens::structure_mesh(points, { 100, 0 }), mesolens::InvalidInput);
  std::vector<double> line;
  for (int i = 0; i < 100; ++i)
    line.insert(line.end(), { double(i), 0, 0 });
  try
  {
    mesolens::structure_mesh(line, { 100, 0 });
    ADD_FAILURE() << "points on a line gave a mesh";
  }
  catch (const mesolens::TopologyError& error)
  {
    EXPECT_NE(std::string(error.what()).find("describe no surface"), std::string::npos)
      << error.what();
  }
  const std::vector<double> same(30, 1.5);
  EXPECT_THROW(mesolens::structure_mesh(same, { 100, 0 }), mesolens::InvalidInput);
}

namespace {

/// Fails unless structure_mesh() refuses `params` for `points` with an error naming the vertex
/// limit.
void expect_vertex_limit_error(const std::vector<double>& points,
                               const mesolens::StructureMeshParams& params)
{
  try
  {
    mesolens::structure_mesh(points, params);
    ADD_FAILURE() << "edges of " << params.edge_length << " gave a mesh";
  }
  catch (const mesolens::InvalidInput& error)
  {
    EXPECT_NE(std::string(error.what()).find("vertex limit"), std::string::npos) << error.what();
  }
}

} // namespace

TEST(StructureMesh, AnEdgeGivingMoreVerticesThanTheLimitIsRefusedBeforeRemeshing)
{
  // A subnormal edge once kept CGAL's remeshing splitting edges until the memory ran out.
  mesolens::StructureMeshParams params;
  params.edge_length = 2.122e-314;
  expect_vertex_limit_error(sphere_points(200, 1.0), params);
  params.box = patch_box(); // the periodic lattice path
  expect_vertex_limit_error(two_noisy_leaflets(20.0, 11), params);
  // 100 x 90 Å with edges of 1 Å is about 10 400 vertices: refused under a limit of 5 000, as
  // is a count of 6 000; edges of 4 Å under the default limit give a mesh.
  params.edge_length = 1.0;
  params.vertex_limit = 5000;
  expect_vertex_limit_error(two_noisy_leaflets(20.0, 11), params);
  params.edge_length = 0;
  params.vertices = 6000;
  expect_vertex_limit_error(two_noisy_leaflets(20.0, 11), params);
  params.vertex_limit = 1000000;
  params.edge_length = 4.0;
  EXPECT_NO_THROW(mesolens::structure_mesh(two_noisy_leaflets(20.0, 11), params));
}

TEST(StructureMesh, ASheetOfFourPointsRemeshedToDegenerateFacesGivesAClearError)
{
  // Remeshing these four points to 72 vertices leaves a vertex whose faces are all degenerate:
  // CGAL 5.5's remesher then read past its halfedge statuses (a crash under AddressSanitizer).
  // The sheet cannot meet the angle bound, which is what the caller must be told.
  const std::vector<double> points = {
    0, 0, -20, 0, 5.647, 20, 5.647, 5.647, -20, 5.647, 5.647, 20
  };
  mesolens::StructureMeshParams params;
  params.vertices = 72;
  try
  {
    mesolens::structure_mesh(points, params);
    FAIL() << "a mesh meeting the angle bound through four points";
  }
  catch (const mesolens::TopologyError& error)
  {
    EXPECT_NE(std::string(error.what()).find("angles within 30-120"), std::string::npos)
      << error.what();
  }
}

TEST(StructureMesh, WaterIonsAndProteinsAreNotPartOfTheSheet)
{
  for (const char* name :
       { "SOL", "WAT", "HOH", "TIP3", "tip3", "SPC", "W",  "PW", "NA",  "CL",  "K",    "NA+",
         "CL-", "Na+", "Cl-", "CA2+", "ION",  "CA",  "MG", "ZN", "SOD", "CLA", " POT " })
  {
    EXPECT_TRUE(mesolens::is_solvent_residue(name)) << name;
  }
  for (const char* name : { "DPPC", "POPC", "POPE", "CHOL", "POPG", "ALA", "" })
  {
    EXPECT_FALSE(mesolens::is_solvent_residue(name)) << name;
  }
  // Types: 0 lipid, 1 water, 2 ion, 3 an unnamed small molecule, 4 a protein chain.
  const std::vector<std::string> names{ "DPPC", "SOL", "NA+", "XYZ", "LEU" };
  const std::vector<int> types{ 0, 0, 0, 0, 1, 2, 3, 4 };
  const std::vector<std::size_t> atoms{ 50, 50, 50, 50, 3, 1, 2, 900 };
  EXPECT_EQ(mesolens::structure_molecules(types, names, atoms),
            (std::vector<std::uint8_t>{ 1, 1, 1, 1, 0, 0, 0, 0 }));
  // Fewer than 4 lipids: the protein is all the structure there is.
  const std::vector<int> few{ 0, 1, 4 };
  EXPECT_EQ(mesolens::structure_molecules(few, names, { 50, 3, 900 }),
            (std::vector<std::uint8_t>{ 1, 0, 1 }));
  // A head-group-only cloud: one bead per lipid, all kept.
  EXPECT_EQ(mesolens::structure_molecules({ 0, 0, 0, 0, 0 }, names, { 1, 1, 1, 1, 1 }),
            (std::vector<std::uint8_t>(5, 1)));
  EXPECT_EQ(mesolens::structure_molecules({}, {}, { 1, 1, 1 }), (std::vector<std::uint8_t>(3, 1)));
  EXPECT_THROW(mesolens::structure_molecules({ 0, 7 }, names, { 1, 1 }), mesolens::InvalidInput);
}
