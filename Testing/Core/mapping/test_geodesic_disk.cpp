// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/mapping/geodesic_disk.h"

#include "mesolens/common/errors.h"
#include "mesolens/io/obj_file.h"
#include "mesolens_test_meshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace {
constexpr double pi = 3.14159265358979323846;

mesolens::MeshReport report_of(const mesolens::GeodesicDisk& disk)
{
  return mesolens::mesh_report(disk.mesh.view());
}

double area(const mesolens::TriangleMesh& mesh)
{
  double total = 0;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
  {
    const auto a = mesh.point(mesh.triangles[3 * t]);
    const auto b = mesh.point(mesh.triangles[3 * t + 1]);
    const auto c = mesh.point(mesh.triangles[3 * t + 2]);
    const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
    const double vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
    total += 0.5 *
      std::sqrt(std::pow(uy * vz - uz * vy, 2) + std::pow(uz * vx - ux * vz, 2) +
                std::pow(ux * vy - uy * vx, 2));
  }
  return total;
}
} // namespace

TEST(GeodesicDisk, PlaneDiskIsARoundDisk)
{
  const auto mesh = mesolens_test::plane_grid(101, 10.0, 0.25, 3);
  const mesolens::CellSurface solver(mesh);
  const auto seed = mesolens_test::surface_point(mesh, 10100, { 0.3, 0.3, 0.4 });
  mesolens::GeodesicDiskParams params;
  params.radius = 5.0;
  params.min_triangles = 0; // the input's triangles as they are
  const auto disk = mesolens::geodesic_disk(solver, seed, params);
  const auto report = report_of(disk);
  EXPECT_EQ(report.boundary_loops, 1u);
  EXPECT_EQ(report.euler_characteristic, 1);
  EXPECT_TRUE(report.is_manifold());
  EXPECT_EQ(disk.refinement_levels, 0);
  EXPECT_EQ(disk.holes_closed, 0u);
  // The cut follows the circle of radius 5: its area is pi r^2 up to the chords of the cut.
  EXPECT_NEAR(area(disk.mesh), pi * 25.0, 0.01 * pi * 25.0);
  double worst = 0;
  for (std::size_t v = 0; v < disk.distance.size(); ++v)
  {
    const auto p = disk.mesh.point(std::int64_t(v));
    const double exact = std::hypot(p[0] - seed.position[0], p[1] - seed.position[1]);
    EXPECT_LE(disk.distance[v], 5.0 + 1e-12);
    if (disk.original_vertex[v] >= 0 && exact > 0.5)
    {
      worst = std::max(worst, std::abs(disk.distance[v] - exact) / exact);
    }
  }
  EXPECT_LT(worst, 0.005);
  ASSERT_GE(disk.seed.triangle, 0);
  EXPECT_NEAR(disk.seed.position[0], seed.position[0], 1e-12);
  EXPECT_GE(
    std::min({ disk.seed.barycentric[0], disk.seed.barycentric[1], disk.seed.barycentric[2] }),
    -1e-9);
}

TEST(GeodesicDisk, SphereCapAndRefinementOfCoarseMeshes)
{
  const auto coarse = mesolens_test::icosphere(10.0, 1); // 80 triangles
  const mesolens::CellSurface solver(coarse);
  const auto seed = mesolens_test::surface_point(coarse, 5);
  mesolens::GeodesicDiskParams params;
  params.radius = 6.0;
  params.min_triangles = 1500;
  const auto disk = mesolens::geodesic_disk(solver, seed, params);
  EXPECT_GE(disk.refinement_levels, 1);
  EXPECT_GE(disk.mesh.triangle_count(), 1500u);
  const auto report = report_of(disk);
  EXPECT_EQ(report.boundary_loops, 1u);
  EXPECT_EQ(report.euler_characteristic, 1);
  // Vertices created by refinement have no original id; the old ones keep theirs.
  const auto created = std::count(disk.original_vertex.begin(), disk.original_vertex.end(), -1);
  EXPECT_GT(created, 0);
  EXPECT_LT(std::size_t(created), disk.original_vertex.size());
  params.min_triangles = 0;
  const auto unrefined = mesolens::geodesic_disk(solver, seed, params);
  EXPECT_EQ(unrefined.refinement_levels, 0);
  EXPECT_LT(unrefined.mesh.triangle_count(), 100u);
}

// Found by fuzz_geodesic: on a torus of 3 x 12 quads (edges of about 2000 units) a disk of
// radius 200 bisected its way to 2 million triangles (2.5 s, then an error): the patches' bulge
// bound kept far triangles within reach. Now it stops after 2e5 new triangles, saying why.
TEST(GeodesicDisk, TooCoarseAndCurvedAMeshFailsFast)
{
  const mesolens::CellSurface surface(mesolens_test::torus(3 * 568.628, 568.628, 3, 12));
  mesolens::GeodesicDiskParams params;
  params.radius = 200.817;
  params.min_triangles = 492;
  try
  {
    mesolens::geodesic_disk(surface, surface.closest_point({ -568.628, -5, 0 }), params);
    ADD_FAILURE() << "a disk was grown";
  }
  catch (const mesolens::SolverFailure& e)
  {
    EXPECT_NE(std::string(e.what()).find("more than 200000 new triangles: the mesh is too coarse "
                                         "and curved there for a disk this small"),
              std::string::npos)
      << e.what();
  }
}

// Found by fuzz_geodesic: on a damaged coarse sphere, one longest-edge bisection path (a single
// bisection's propagation) kept splitting, the smooth surface's midpoints lengthening edges as
// fast as it split them, until the memory ran out; the limit on new triangles was checked only
// between paths.
TEST(GeodesicDisk, ARunawayBisectionPathStopsAtTheTriangleLimit)
{
  const mesolens::TriangleMesh mesh = mesolens_test::fan_triangulated(
    mesolens::read_obj(std::string(MESOLENS_SOURCE_DIR) +
                       "/Testing/Data/meshes/fuzz_geodesic_runaway_bisection_path.obj")
      .soup);
  ASSERT_EQ(mesh.triangle_count(), 263u);
  const mesolens::CellSurface surface(mesh);
  mesolens::GeodesicDiskParams params;
  params.radius = 13.603366047245311;
  params.min_triangles = 338;
  params.max_triangles = 544;
  try
  {
    mesolens::geodesic_disk(surface, surface.closest_point({ -5, -5, -5 }), params);
    ADD_FAILURE() << "a disk was grown";
  }
  catch (const mesolens::SolverFailure& e)
  {
    EXPECT_NE(std::string(e.what()).find("more than 200000 new triangles"), std::string::npos)
      << e.what();
  }
}

// Found by fuzz_geodesic: a radius of 1e-73 on a mesh 3e-3 across bisected without end.
TEST(GeodesicDisk, RadiiTooSmallForTheMeshAreRefused)
{
  const mesolens::CellSurface surface(mesolens_test::icosphere(1e-3, 1));
  mesolens::GeodesicDiskParams params;
  params.radius = 3.36e-73;
  const mesolens::SurfacePoint seed = surface.closest_point({ 0, 0, 1 });
  try
  {
    mesolens::geodesic_disk(surface, seed, params);
    ADD_FAILURE() << "a disk was grown";
  }
  catch (const mesolens::InvalidInput& e)
  {
    EXPECT_NE(std::string(e.what()).find("is below 1e-09 times the mesh's size"), std::string::npos)
      << e.what();
  }
  params.radius = 1e-4; // a tenth of the sphere's radius: fine
  EXPECT_GT(mesolens::geodesic_disk(surface, seed, params).mesh.triangle_count(), 100u);
}

TEST(GeodesicDisk, TopologyErrors)
{
  // Radius beyond the plane's border.
  const auto plane = mesolens_test::plane_grid(41, 10.0);
  const mesolens::CellSurface plane_solver(plane);
  mesolens::GeodesicDiskParams params;
  params.radius = 12.0;
  try
  {
    mesolens::geodesic_disk(plane_solver, mesolens_test::surface_point(plane, 1640), params);
    FAIL() << "the disk reached the boundary without an error";
  }
  catch (const mesolens::TopologyError& e)
  {
    EXPECT_NE(std::string(e.what()).find("reaches the mesh boundary"), std::string::npos)
      << e.what();
  }
  // A disk wider than half the circumference of a tube wraps around it.
  const auto tube = mesolens_test::cylinder(2.0, 20.0, 48, 200);
  const mesolens::CellSurface tube_solver(tube);
  params.radius = 8.0;
  params.min_triangles = 0;
  try
  {
    mesolens::geodesic_disk(tube_solver, mesolens_test::surface_point(tube, 9600), params);
    FAIL() << "a disk wrapping the tube was accepted";
  }
  catch (const mesolens::TopologyError& e)
  {
    EXPECT_NE(std::string(e.what()).find("wraps a handle"), std::string::npos) << e.what();
  }
  params.radius = 2.5;
  const auto ok =
    mesolens::geodesic_disk(tube_solver, mesolens_test::surface_point(tube, 9600), params);
  EXPECT_EQ(report_of(ok).euler_characteristic, 1);
  // A radius larger than the whole sphere.
  const auto sphere = mesolens_test::icosphere(1.0, 3);
  const mesolens::CellSurface sphere_solver(sphere);
  params.radius = 10.0;
  try
  {
    mesolens::geodesic_disk(sphere_solver, mesolens_test::surface_point(sphere, 0), params);
    FAIL() << "a disk covering the sphere was accepted";
  }
  catch (const mesolens::TopologyError& e)
  {
    EXPECT_NE(std::string(e.what()).find("covers the whole"), std::string::npos) << e.what();
  }
  params.radius = 0.0;
  EXPECT_THROW(
    mesolens::geodesic_disk(sphere_solver, mesolens_test::surface_point(sphere, 0), params),
    mesolens::InvalidInput);
  params.radius = std::nan("");
  EXPECT_THROW(
    mesolens::geodesic_disk(sphere_solver, mesolens_test::surface_point(sphere, 0), params),
    mesolens::InvalidInput);
}

TEST(GeodesicDisk, TheTopOfABumpTheFrontWentRoundIsTakenWithItsOwnTriangles)
{
  // A tall, narrow bump 2 from the seed: its top is farther than 4 along the surface, the
  // ground behind it is not. The disk of radius 4 takes the top with the surface's own
  // triangles (no patch over it) and stays a disk.
  const auto bumpy = mesolens_test::lifted_grid(161, 8.0, [](double u, double v) {
    const double r2 = (u - 2) * (u - 2) + v * v;
    return std::array<double, 3>{ u, v, 3.0 * std::exp(-r2 / 0.25) };
  });
  const mesolens::CellSurface surface(bumpy);
  const auto seed = surface.closest_point({ 0.0, 0.0, 0.0 });
  mesolens::GeodesicDiskParams params;
  params.radius = 4.0;
  params.min_triangles = 0;
  const auto disk = mesolens::geodesic_disk(surface, seed, params);
  EXPECT_EQ(disk.holes_closed, 1u);
  const auto report = report_of(disk);
  EXPECT_EQ(report.euler_characteristic, 1);
  EXPECT_EQ(report.boundary_loops, 1u);
  double top = 0, farthest = 0;
  for (std::size_t v = 0; v < disk.mesh.vertex_count(); ++v)
  {
    top = std::max(top, disk.mesh.point(std::int64_t(v))[2]);
    farthest = std::max(farthest, disk.distance[v]);
    EXPECT_GE(disk.original_vertex[v] >= 0 ? 1 : 0, disk.distance[v] > 4.0 ? 1 : 0)
      << "only input vertices lie beyond the radius";
  }
  EXPECT_GT(top, 2.9);      // the bump's summit is in
  EXPECT_GT(farthest, 4.0); // and it lies beyond the radius
  for (const std::int64_t source : disk.source_triangle)
  {
    EXPECT_GE(source, 0); // every triangle is the surface's
  }
}
