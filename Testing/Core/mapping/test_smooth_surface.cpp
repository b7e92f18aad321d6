// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/mapping/smooth_surface.h"

#include "mesolens/common/errors.h"
#include "mesolens_test_meshes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {
double norm(const std::array<double, 3>& a)
{
  return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

/// Radial unit normals: those of the sphere the icosphere's vertices lie on.
std::vector<double> radial_normals(const mesolens::TriangleMesh& mesh)
{
  std::vector<double> normals(mesh.points.size());
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
  {
    const auto p = mesh.point(std::int64_t(v));
    for (std::size_t d = 0; d < 3; ++d)
    {
      normals[3 * v + d] = p[d] / norm(p);
    }
  }
  return normals;
}
} // namespace

TEST(SmoothSurface, InterpolatesVerticesAndTheirNormals)
{
  const auto mesh = mesolens_test::icosphere(3.0, 0);
  const mesolens::SmoothSurface surface(mesh, radial_normals(mesh));
  for (std::int64_t t = 0; t < std::int64_t(mesh.triangle_count()); ++t)
  {
    for (std::size_t k = 0; k < 3; ++k)
    {
      std::array<double, 3> corner{ 0, 0, 0 };
      corner[k] = 1;
      const auto on = surface.evaluate(t, corner);
      const auto p = mesh.point(mesh.triangles[3 * std::size_t(t) + k]);
      for (std::size_t d = 0; d < 3; ++d)
      {
        EXPECT_NEAR(on.position[d], p[d], 1e-12);
        EXPECT_NEAR(on.normal[d], p[d] / 3.0, 1e-12);
      }
    }
  }
}

TEST(SmoothSurface, FlatWhereTheNormalsAreTheFacets)
{
  // A tilted plane: every vertex normal is the plane's, so the surface is the triangles.
  const auto plane = mesolens_test::plane_grid(5, 2.0, 0.2);
  mesolens::TriangleMesh tilted = plane;
  for (std::size_t v = 0; v < tilted.vertex_count(); ++v)
  {
    tilted.points[3 * v + 2] = 0.5 * tilted.points[3 * v] - 0.25 * tilted.points[3 * v + 1];
  }
  const mesolens::SmoothSurface surface(tilted);
  const std::array<double, 3> n{ -0.5, 0.25, 1.0 };
  for (std::int64_t t = 0; t < std::int64_t(tilted.triangle_count()); ++t)
  {
    const auto on = surface.evaluate(t, { 0.2, 0.3, 0.5 });
    const auto flat = mesolens_test::surface_point(tilted, t, { 0.2, 0.3, 0.5 }).position;
    for (std::size_t d = 0; d < 3; ++d)
    {
      EXPECT_NEAR(on.position[d], flat[d], 1e-12);
      EXPECT_NEAR(on.normal[d], n[d] / norm(n), 1e-12);
    }
  }
}

TEST(SmoothSurface, CurvesTowardsTheSphereAndMeetsAcrossEdges)
{
  // The icosahedron's flat faces lie 0.79 of the radius from the centre at their middles; the
  // smooth surface through the same vertices and (radial) normals comes much closer.
  const auto mesh = mesolens_test::icosphere(1.0, 0);
  const mesolens::SmoothSurface surface(mesh, radial_normals(mesh));
  for (std::int64_t t = 0; t < std::int64_t(mesh.triangle_count()); ++t)
  {
    const double flat =
      norm(mesolens_test::surface_point(mesh, t, { 1.0 / 3, 1.0 / 3, 1.0 / 3 }).position);
    const double smooth = norm(surface.evaluate(t, { 1.0 / 3, 1.0 / 3, 1.0 / 3 }).position);
    EXPECT_NEAR(flat, 0.795, 0.001);
    EXPECT_GT(smooth, 0.93); // 0.941: a third of the flat face's gap
    EXPECT_LT(smooth, 1.05);
  }
  // Triangles 0 (0, 11, 5) and 1 (0, 5, 1) share edge (0, 5): the same curve from both sides.
  for (const double f : { 0.1, 0.37, 0.5, 0.81 })
  {
    const auto from_first = surface.evaluate(0, { 1 - f, 0, f });
    const auto from_second = surface.evaluate(1, { 1 - f, f, 0 });
    for (std::size_t d = 0; d < 3; ++d)
    {
      EXPECT_NEAR(from_first.position[d], from_second.position[d], 1e-12);
      EXPECT_NEAR(from_first.normal[d], from_second.normal[d], 1e-12);
    }
  }
}

TEST(SmoothSurface, RefusesNormalsOfTheWrongSize)
{
  const auto mesh = mesolens_test::icosphere(1.0, 0);
  EXPECT_THROW(mesolens::SmoothSurface(mesh, std::vector<double>(3, 0.0)), mesolens::InvalidInput);
}
