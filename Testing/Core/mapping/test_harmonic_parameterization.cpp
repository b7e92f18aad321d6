// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/mapping/harmonic_parameterization.h"

#include "mesolens/common/errors.h"
#include "mesolens/mapping/geodesic_disk.h"
#include "mesolens_test_meshes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {
constexpr double pi = 3.14159265358979323846;

void expect_bijective_in_disk(const mesolens::DiskParameterization& map, double radius)
{
  EXPECT_TRUE(map.bijective()) << map.flipped_triangles << " flipped triangles";
  for (std::size_t v = 0; v < map.uv.size() / 2; ++v)
  {
    EXPECT_LE(std::hypot(map.uv[2 * v], map.uv[2 * v + 1]), radius * (1 + 1e-12));
  }
}
} // namespace

TEST(HarmonicParameterization, FlatDiskIsASimilarity)
{
  const auto disk = mesolens_test::polar_disk(12, 64, 3.0);
  const auto map = mesolens::harmonic_parameterization(disk, 2.0);
  expect_bijective_in_disk(map, 2.0);
  // Mean-value coordinates reproduce linear maps, so uv = (2/3) R x + t exactly.
  const double scale = 2.0 / 3.0;
  double worst = 0;
  for (std::size_t a = 0; a < disk.vertex_count(); a += 7)
  {
    for (std::size_t b = a + 1; b < disk.vertex_count(); b += 13)
    {
      const auto pa = disk.point(std::int64_t(a));
      const auto pb = disk.point(std::int64_t(b));
      const double d3 = std::hypot(pa[0] - pb[0], pa[1] - pb[1]);
      const double duv =
        std::hypot(map.uv[2 * a] - map.uv[2 * b], map.uv[2 * a + 1] - map.uv[2 * b + 1]);
      worst = std::max(worst, std::abs(duv - scale * d3));
    }
  }
  EXPECT_LT(worst, 1e-9);
  for (std::size_t t = 0; t < disk.triangle_count(); ++t)
  {
    EXPECT_NEAR(map.angle_distortion[t], 1.0, 1e-9);
    EXPECT_NEAR(map.area_distortion[t], 1.0, 1e-9);
  }
}

TEST(HarmonicParameterization, CurvedDisksHaveNoFlippedTriangles)
{
  struct Case
  {
    const char* name;
    mesolens::TriangleMesh surface;
    std::int64_t seed_triangle;
    double radius;
  };
  std::vector<Case> cases;
  cases.push_back({ "sphere cap", mesolens_test::icosphere(5.0, 5), 100, 5.0 });
  cases.push_back({ "saddle",
                    mesolens_test::lifted_grid(
                      81, 3.0,
                      [](double u, double v) {
                        return std::array<double, 3>{ u, v, 0.5 * (u * u - v * v) };
                      },
                      0.2, 5),
                    6480, 2.0 });
  cases.push_back({ "cylinder", mesolens_test::cylinder(2.0, 10.0, 64, 160), 10240, 4.5 });
  for (const Case& c : cases)
  {
    SCOPED_TRACE(c.name);
    const mesolens::CellSurface solver(c.surface);
    mesolens::GeodesicDiskParams params;
    params.radius = c.radius;
    params.min_triangles = 0;
    const auto disk = mesolens::geodesic_disk(
      solver, mesolens_test::surface_point(c.surface, c.seed_triangle), params);
    const auto map = mesolens::harmonic_parameterization(disk.mesh, c.radius);
    expect_bijective_in_disk(map, c.radius);
    EXPECT_EQ(map.angle_distortion.size(), disk.mesh.triangle_count());
  }
}

TEST(HarmonicParameterization, RefusesWhatIsNotADisk)
{
  EXPECT_THROW(mesolens::harmonic_parameterization(mesolens_test::icosphere(1.0, 2), 1.0),
               mesolens::TopologyError);
  const auto tube = mesolens_test::cylinder(1.0, 2.0, 16, 8); // an annulus: two boundary loops
  EXPECT_THROW(mesolens::harmonic_parameterization(tube, 1.0), mesolens::TopologyError);
  const auto disk = mesolens_test::polar_disk(3, 12, 1.0);
  EXPECT_THROW(mesolens::harmonic_parameterization(disk, 0.0), mesolens::InvalidInput);
  EXPECT_THROW(mesolens::harmonic_parameterization(disk, std::nan("")), mesolens::InvalidInput);
  EXPECT_THROW(mesolens::harmonic_parameterization(mesolens::TriangleMesh{}, 1.0),
               mesolens::InvalidInput);
}
