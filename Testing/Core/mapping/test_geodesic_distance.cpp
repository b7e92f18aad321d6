// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/mapping/geodesic_distance.h"

#include "mesolens/common/errors.h"
#include "mesolens_test_meshes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

namespace {
constexpr double pi = 3.14159265358979323846;

double angle_between(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  const double dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const double na = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  const double nb = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
  return std::acos(std::clamp(dot / (na * nb), -1.0, 1.0));
}
} // namespace

TEST(GeodesicDistance, PlaneIsEuclidean)
{
  // A jittered grid: many triangles are obtuse, so the unfolding is exercised.
  const auto mesh = mesolens_test::plane_grid(81, 10.0, 0.3, 7);
  const mesolens::GeodesicSolver solver(mesh);
  const auto seed = mesolens_test::surface_point(mesh, 6480, { 0.6, 0.3, 0.1 });
  const auto field = solver.distances(seed, 8.0);
  ASSERT_GT(field.vertices.size(), 1000u);
  double worst = 0;
  for (std::size_t i = 0; i < field.vertices.size(); ++i)
  {
    const auto p = mesh.point(field.vertices[i]);
    const double exact = std::hypot(p[0] - seed.position[0], p[1] - seed.position[1]);
    if (exact > 0.5)
    {
      worst = std::max(worst, std::abs(field.distances[i] - exact) / exact);
    }
    EXPECT_LE(field.distances[i], 8.0);
  }
  EXPECT_LT(worst, 0.005);
  RecordProperty("worst_relative_error", std::to_string(worst));
  std::printf("plane: worst relative error %.2e\n", worst);
  // Distances come out sorted: the march is monotone.
  EXPECT_TRUE(std::is_sorted(field.distances.begin(), field.distances.end()));
}

TEST(GeodesicDistance, SphereIsRadiusTimesAngle)
{
  const double radius = 10.0;
  const auto mesh = mesolens_test::icosphere(radius, 6); // 81920 triangles
  const mesolens::GeodesicSolver solver(mesh);
  const auto seed = mesolens_test::surface_point(mesh, 123, { 0.25, 0.35, 0.4 });
  const auto field = solver.distances(seed, radius * pi / 2 * 1.05);
  double worst = 0;
  std::size_t checked = 0;
  for (std::size_t i = 0; i < field.vertices.size(); ++i)
  {
    const double angle = angle_between(seed.position, mesh.point(field.vertices[i]));
    if (angle > 0.05 && angle <= pi / 2)
    {
      worst = std::max(worst, std::abs(field.distances[i] - radius * angle) / (radius * angle));
      ++checked;
    }
  }
  EXPECT_GT(checked, 10000u);
  EXPECT_LT(worst, 0.01);
  std::printf("sphere: worst relative error %.2e over %zu vertices\n", worst, checked);
}

TEST(GeodesicDistance, StopsAtTheRadius)
{
  const auto mesh = mesolens_test::plane_grid(41, 10.0);
  const mesolens::GeodesicSolver solver(mesh);
  const auto seed = mesolens_test::surface_point(mesh, 1640);
  const auto small = solver.distances(seed, 2.0);
  const auto large = solver.distances(seed, 4.0);
  EXPECT_LT(small.vertices.size(), large.vertices.size());
  EXPECT_LE(small.distances.back(), 2.0);
  // The solver is reused: the same march twice gives the same answer.
  const auto again = solver.distances(seed, 2.0);
  EXPECT_EQ(again.vertices, small.vertices);
  EXPECT_EQ(again.distances, small.distances);
}

TEST(GeodesicDistance, ClosestPoint)
{
  const auto mesh = mesolens_test::icosphere(5.0, 3);
  const mesolens::GeodesicSolver solver(mesh);
  double distance = 0;
  const auto point = solver.closest_point({ 0, 0, 9.0 }, &distance);
  EXPECT_NEAR(distance, 4.0, 0.05);
  EXPECT_NEAR(point.position[2], 5.0, 0.05);
  EXPECT_NEAR(point.barycentric[0] + point.barycentric[1] + point.barycentric[2], 1.0, 1e-12);
  EXPECT_THROW(solver.closest_point({ std::nan(""), 0, 0 }), mesolens::InvalidInput);
}

TEST(GeodesicDistance, BadInputs)
{
  const auto mesh = mesolens_test::plane_grid(11, 1.0);
  const mesolens::GeodesicSolver solver(mesh);
  mesolens::SurfacePoint outside;
  outside.triangle = 100000;
  EXPECT_THROW(solver.distances(outside, 1.0), mesolens::InvalidInput);
  const auto seed = mesolens_test::surface_point(mesh, 3);
  EXPECT_THROW(solver.distances(seed, 0.0), mesolens::InvalidInput);
  EXPECT_THROW(solver.distances(seed, -1.0), mesolens::InvalidInput);
  EXPECT_THROW(solver.distances(seed, std::numeric_limits<double>::infinity()),
               mesolens::InvalidInput);
  // A non-manifold mesh: three triangles around one edge.
  mesolens::TriangleMesh fin;
  fin.points = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1 };
  fin.triangles = { 0, 1, 2, 1, 0, 3, 0, 1, 4 };
  EXPECT_THROW(mesolens::GeodesicSolver{ fin }, mesolens::TopologyError);
  EXPECT_THROW(mesolens::GeodesicSolver{ mesolens::TriangleMesh{} }, mesolens::InvalidInput);
  auto nan_mesh = mesh;
  nan_mesh.points[4] = std::nan("");
  EXPECT_THROW(mesolens::GeodesicSolver{ nan_mesh }, mesolens::InvalidInput);
}
