// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/errors.h"
#include "mesolens/structure_mesh.h"
#include "mesolens_test_meshes.h"
#include "mesolens_test_threads.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {
std::vector<double> sphere_points(int count, double radius)
{
  return mesolens_test::fibonacci_sphere(count, radius);
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
}

TEST(StructureMesh, ClosedEvenMeshOfTheRequestedSizeThroughASphereOfPoints)
{
  mesolens::MeshQuality quality;
  const auto mesh = mesolens::structure_mesh(sphere_points(3000, 10.0), { 300, 0 }, &quality);
  const std::size_t v = mesh.vertex_count();
  const std::size_t f = mesh.triangle_count();
  EXPECT_GT(v, 180u);
  EXPECT_LT(v, 480u);
  EXPECT_EQ(quality.boundary_edges, 0u); // closed
  EXPECT_EQ(3 * f % 2, 0u);
  EXPECT_EQ(long(v) - long(3 * f / 2) + long(f), 2); // Euler characteristic of a sphere
  EXPECT_GT(quality.min_angle, 15.0);
  EXPECT_LT(quality.max_angle, 130.0);
  EXPECT_LT(quality.edge_spread, 0.35);
  for (std::size_t i = 0; i < v; ++i)
  {
    const auto p = mesh.point(std::int64_t(i));
    EXPECT_NEAR(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]), 10.0, 0.6);
  }
  // A target edge length instead of a vertex count.
  const auto coarse = mesolens::structure_mesh(sphere_points(3000, 10.0), { 0, 4.0 }, &quality);
  EXPECT_LT(coarse.vertex_count(), v);
  EXPECT_NEAR(quality.mean_edge, 4.0, 1.2);
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
  EXPECT_GT(v, 120u);
  EXPECT_LT(v, 320u);
  EXPECT_EQ(quality.boundary_edges, 0u);
  EXPECT_EQ(long(v) - long(3 * f / 2) + long(f), 2);
  EXPECT_GT(quality.min_angle, 25.0);
  EXPECT_LT(quality.max_angle, 115.0);
  EXPECT_LT(quality.edge_spread, 0.25);
  for (std::size_t i = 0; i < v; ++i)
  {
    const auto p = mesh.point(std::int64_t(i));
    EXPECT_NEAR(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]), 72.0 - 3.0, 2.5);
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
}

TEST(StructureMesh, BadInputs)
{
  EXPECT_THROW(mesolens::structure_mesh({}, { 100, 0 }), mesolens::InvalidInput);
  EXPECT_THROW(mesolens::structure_mesh({ 0, 0, 0, 1, 0, 0, 0, 1, 0 }, { 100, 0 }),
               mesolens::InvalidInput);
  auto points = sphere_points(200, 1.0);
  EXPECT_THROW(mesolens::structure_mesh(points, { 3, 0 }), mesolens::InvalidInput);
  EXPECT_THROW(mesolens::structure_mesh(points, { 100, -1.0 }), mesolens::InvalidInput);
  points[7] = std::nan("");
  EXPECT_THROW(mesolens::structure_mesh(points, { 100, 0 }), mesolens::InvalidInput);
  std::vector<double> line;
  for (int i = 0; i < 100; ++i)
    line.insert(line.end(), { double(i), 0, 0 });
  EXPECT_THROW(mesolens::structure_mesh(line, { 100, 0 }), mesolens::TopologyError);
}
