// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/mapping/cell_surface.h"

#include "mesolens/common/errors.h"
#include "mesolens/mapping/membrane_mapper.h"
#include "mesolens_test_meshes.h"
#include "mapping/detail/surface_levels.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {
double norm(const std::array<double, 3>& a)
{
  return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}
} // namespace

TEST(CellSurface, AdjacencyOfAClosedMesh)
{
  const auto mesh = mesolens_test::icosphere(1.0, 1);
  const mesolens::CellSurface surface(mesh);
  const auto& adjacency = surface.adjacency();
  ASSERT_EQ(adjacency.across.size(), 3 * mesh.triangle_count());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
  {
    for (std::size_t k = 0; k < 3; ++k)
    {
      const std::int64_t other = adjacency.across[3 * t + k];
      ASSERT_GE(other, 0);
      // The other triangle runs the same edge the other way.
      const std::int64_t a = mesh.triangles[3 * t + k], b = mesh.triangles[3 * t + (k + 1) % 3];
      bool found = false;
      for (std::size_t j = 0; j < 3; ++j)
      {
        found = found ||
          (mesh.triangles[3 * std::size_t(other) + j] == b &&
           mesh.triangles[3 * std::size_t(other) + (j + 1) % 3] == a);
      }
      EXPECT_TRUE(found);
    }
  }
  EXPECT_EQ(adjacency.vertex_start.back(), 3 * mesh.triangle_count());
  EXPECT_EQ(surface.level_count(), 1u);                                // small: no coarser copies
  EXPECT_NEAR(surface.bounding_diagonal(), 2 * std::sqrt(3.0), 1e-12); // vertices on the axes
}

TEST(CellSurface, VerticesNoTriangleUsesHaveNoAnchor)
{
  // Meshes may carry points no triangle uses (the mesh report counts them, the mapping accepts
  // them): one before and one after the mesh's own.
  auto mesh = mesolens_test::icosphere(1.0, 1);
  const std::size_t first_own = 1;
  for (std::int64_t& v : mesh.triangles)
  {
    v += std::int64_t(first_own);
  }
  mesh.points.insert(mesh.points.begin(), { 5.0, 5.0, 5.0 });
  mesh.points.insert(mesh.points.end(), { -5.0, 5.0, 5.0 });
  const mesolens::CellSurface surface(mesh);
  const auto& anchors = surface.level(0).anchor_triangle;
  ASSERT_EQ(anchors.size(), mesh.vertex_count());
  EXPECT_EQ(anchors.front(), -1);
  EXPECT_EQ(anchors.back(), -1);
  for (std::size_t v = first_own; v + 1 < anchors.size(); ++v)
  {
    EXPECT_GE(anchors[v], 0) << v;
  }
}

TEST(CellSurface, CoarserCopiesKeepTopologyBoundaryAndShape)
{
  // A fine torus (genus 1, 57 600 triangles): each copy has about a quarter of the vertices,
  // the same genus, and lies near the torus.
  const double major = 10, minor = 3;
  const auto ring = mesolens_test::torus(major, minor, 240, 120);
  const mesolens::CellSurface surface(ring);
  ASSERT_GE(surface.level_count(), 3u); // 28 800, 7 200 and 1 800 vertices
  EXPECT_EQ(&surface.level(0).mesh(), &surface.mesh());
  for (std::size_t k = 1; k < surface.level_count(); ++k)
  {
    const mesolens::TriangleMesh& copy = surface.level(k).mesh();
    const auto report = mesolens::mesh_report(copy.view());
    EXPECT_TRUE(report.is_closed_manifold()) << k << ": " << report.describe_defects();
    EXPECT_EQ(report.euler_characteristic, 0) << k;
    EXPECT_EQ(report.degenerate_triangles, 0u) << k;
    const double ratio =
      double(copy.vertex_count()) / double(surface.level(k - 1).mesh().vertex_count());
    EXPECT_GT(ratio, 0.2) << k;
    EXPECT_LT(ratio, 0.3) << k;
    double worst = 0;
    for (std::size_t v = 0; v < copy.vertex_count(); ++v)
    {
      const auto p = copy.point(std::int64_t(v));
      const double ring_distance = std::hypot(p[0], p[1]) - major;
      worst = std::max(worst, std::abs(std::hypot(ring_distance, p[2]) - minor));
      // Its anchor is an input triangle near it.
      const auto anchor = surface.level(k).anchor_triangle[v];
      const auto a = ring.point(ring.triangles[3 * std::size_t(anchor)]);
      EXPECT_LT(norm({ a[0] - p[0], a[1] - p[1], a[2] - p[2] }), 2.0 * std::pow(2.0, double(k)))
        << k;
    }
    EXPECT_LT(worst, 0.05 * minor) << k; // midpoints sag inward a little, level by level
  }
  // An open grid keeps its border: every boundary point of the input stays in every copy.
  const auto plane = mesolens_test::plane_grid(151, 10.0, 0.2);
  const mesolens::CellSurface open(plane);
  ASSERT_GE(open.level_count(), 2u);
  for (std::size_t k = 1; k < open.level_count(); ++k)
  {
    const auto report = mesolens::mesh_report(open.level(k).mesh().view());
    EXPECT_TRUE(report.is_manifold());
    EXPECT_EQ(report.boundary_loops, 1u);
    EXPECT_EQ(report.boundary_edges, 600u) << k; // 150 per side, as in the input
  }
}

TEST(CellSurface, WalkingFindsTheClosestPointFromNearby)
{
  const auto sphere = mesolens_test::icosphere(50.0, 4);
  const mesolens::CellSurface surface(sphere);
  const auto& level = surface.level(0);
  for (std::size_t t = 0; t < sphere.triangle_count(); t += 97)
  {
    const auto on = mesolens_test::surface_point(sphere, std::int64_t(t), { 0.1, 0.2, 0.7 });
    const std::array<double, 3> above{ 1.01 * on.position[0], 1.01 * on.position[1],
                                       1.01 * on.position[2] };
    // Start a few triangles away.
    const std::int64_t start = level.adjacency.across[3 * level.adjacency.across[3 * t]];
    const auto walked = mesolens::detail::walk_to_closest(sphere, level.adjacency, start, above);
    double exact_distance = 0, walked_distance = 0;
    const auto exact = surface.closest_point(above, &exact_distance);
    ASSERT_GE(walked.triangle, 0);
    walked_distance = norm({ walked.position[0] - above[0], walked.position[1] - above[1],
                             walked.position[2] - above[2] });
    EXPECT_NEAR(walked_distance, exact_distance, 1e-9);
    EXPECT_EQ(walked.triangle, exact.triangle);
  }
}

TEST(CellSurface, LargeDisksGrowOnACoarserCopyAndLandOnTheInput)
{
  // 81 920 triangles of a sphere of radius 100: a disk of radius 120 holds about 26 000 of them.
  const double radius = 100;
  const auto sphere = mesolens_test::icosphere(radius, 6);
  const mesolens::MembraneMapper mapper(sphere);
  const auto seed = mapper.seed_near({ 0, 0, radius });
  const auto chart = mapper.chart(seed, 120.0);
  EXPECT_GT(chart->disk.surface_level, 0u);
  EXPECT_LT(chart->disk.mesh.triangle_count(), 16000u);
  // Every chart point lies on the input's smooth surface, between its facets and the sphere,
  // and the disk's rim is 120 from the seed along the sphere.
  const double sag = radius * (1 - std::cos(3.14159265358979 / 80)); // generous for level 6
  mesolens::SurfaceFrame frame;
  for (int i = -10; i <= 10; ++i)
  {
    for (int j = -10; j <= 10; ++j)
    {
      const double u = chart->seed_uv[0] + 10.0 * i, v = chart->seed_uv[1] + 10.0 * j;
      if (!chart->chart.frame(u, v, frame))
      {
        continue;
      }
      double distance = 0;
      mapper.surface().closest_point(frame.position, &distance);
      EXPECT_LT(distance, sag);
      EXPECT_LT(std::abs(norm(frame.position) - radius), sag);
    }
  }
  for (std::size_t v = 0; v < chart->disk.mesh.vertex_count(); ++v)
  {
    if (chart->disk.distance[v] < 120.0)
    {
      continue;
    }
    const auto p = chart->disk.mesh.point(std::int64_t(v));
    const double angle = std::acos(std::clamp(p[2] / norm(p), -1.0, 1.0));
    EXPECT_NEAR(radius * angle, 120.0, 3.0);
  }
  // The same disk at the input's resolution agrees on where its rim is.
  mesolens::GeodesicDiskParams full;
  full.radius = 120;
  full.max_triangles = 0;
  const auto fine = mesolens::geodesic_disk(mapper.surface(), seed, full);
  EXPECT_EQ(fine.surface_level, 0u);
  EXPECT_GT(fine.mesh.triangle_count(), 16000u);
}
