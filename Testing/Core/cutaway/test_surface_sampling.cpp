// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/common/errors.h"
#include "mesolens/cutaway/surface_sampling.h"
#include "mesolens_test_meshes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {
/// `count` points spread evenly over a sphere of `radius`, appended to `points`.
void add_sphere(std::vector<double>& points, int count, double radius)
{
  const auto sphere = mesolens_test::fibonacci_sphere(count, radius);
  points.insert(points.end(), sphere.begin(), sphere.end());
}

double distance(const double* a, const double* b)
{
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                   (a[2] - b[2]) * (a[2] - b[2]));
}
} // namespace

TEST(SurfaceSampling, MedianSpacingOfAGrid)
{
  std::vector<double> grid;
  for (int i = 0; i < 30; ++i)
    for (int j = 0; j < 20; ++j)
      grid.insert(grid.end(), { 2.5 * i, 2.5 * j, 7.0 });
  EXPECT_NEAR(mesolens::median_spacing(grid), 2.5, 1e-12);
  EXPECT_NEAR(mesolens::median_spacing(grid, 7), 2.5, 1e-12);
}

TEST(SurfaceSampling, PoissonDiskSubsetIsSparseAndCoversEveryPoint)
{
  std::vector<double> points;
  add_sphere(points, 5000, 10.0);
  const double spacing = 1.5;
  const auto kept = mesolens::poisson_disk_subset(points, spacing);
  const std::size_t n = kept.size() / 3;
  ASSERT_GT(n, 50u);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b)
      ASSERT_GE(distance(&kept[3 * a], &kept[3 * b]), spacing);
  for (std::size_t i = 0; i < points.size(); i += 3)
  {
    double nearest = 1e9;
    for (std::size_t k = 0; k < n; ++k)
      nearest = std::min(nearest, distance(&points[i], &kept[3 * k]));
    ASSERT_LT(nearest, spacing);
  }
  // The density the structure mesh relies on: 0.7 to 0.9 / spacing^2 points per unit area
  // (denser when the input order sweeps the surface, as here).
  const double density = double(n) * spacing * spacing / (4 * 3.14159265358979 * 100.0);
  EXPECT_GT(density, 0.55);
  EXPECT_LT(density, 1.0);
  EXPECT_EQ(kept, mesolens::poisson_disk_subset(points, spacing)); // deterministic
}

TEST(SurfaceSampling, TwoLeafletsMeetOnTheirMiddleSheet)
{
  // A vesicle's lipid centres: leaflets at radii 60 and 84, lipids 8 apart in each.
  std::vector<double> leaflets;
  add_sphere(leaflets, 700, 60.0);
  add_sphere(leaflets, 1400, 84.0);
  const double spacing = 16.0;
  const double radius = 32.0;
  const auto run_parallel_in_halves = [](std::size_t count, const mesolens::RangeKernel& kernel) {
    kernel(0, count / 2);
    kernel(count / 2, count);
  };
  const auto mid = mesolens::mid_surface_points(leaflets, spacing, radius, 4);
  ASSERT_GT(mid.size(), 3 * 60u);
  for (std::size_t i = 0; i < mid.size(); i += 3)
  {
    const double r = std::sqrt(mid[i] * mid[i] + mid[i + 1] * mid[i + 1] + mid[i + 2] * mid[i + 2]);
    // The middle is at 72; averaging over a curved sheet pulls it in by about radius^2 / 4 r.
    ASSERT_NEAR(r, 72.0 - 2.5, 2.5) << "point " << i / 3;
  }
  EXPECT_EQ(mid,
            mesolens::mid_surface_points(leaflets, spacing, radius, 4, run_parallel_in_halves));
  // Without the mean shift, the samples stay on their leaflets.
  const auto unmoved = mesolens::mid_surface_points(leaflets, spacing, radius, 0);
  const double r0 =
    std::sqrt(unmoved[0] * unmoved[0] + unmoved[1] * unmoved[1] + unmoved[2] * unmoved[2]);
  EXPECT_TRUE(std::abs(r0 - 60.0) < 1e-9 || std::abs(r0 - 84.0) < 1e-9);
}

TEST(SurfaceSampling, BadInputs)
{
  using Flat = std::vector<double>;
  EXPECT_THROW(mesolens::median_spacing(Flat{ 1, 2, 3 }), mesolens::InvalidInput);
  EXPECT_THROW(mesolens::median_spacing(Flat{ 1, 2, 3, 1, 2, 3, 1, 2, 3 }), mesolens::InvalidInput);
  EXPECT_THROW(mesolens::median_spacing(Flat{ 1, 2, 3, 1, 2 }), mesolens::InvalidInput);
  EXPECT_THROW(mesolens::median_spacing(Flat{ 0, 0, 0, std::nan(""), 1, 1 }),
               mesolens::InvalidInput);
  EXPECT_THROW(mesolens::poisson_disk_subset(Flat{ 0, 0, 0 }, 0.0), mesolens::InvalidInput);
  EXPECT_THROW(mesolens::poisson_disk_subset(Flat{ 0, 0, 0 }, std::nan("")),
               mesolens::InvalidInput);
  EXPECT_TRUE(mesolens::poisson_disk_subset(Flat{}, 1.0).empty());
  EXPECT_THROW(mesolens::mid_surface_points(Flat{}, 1.0, 1.0), mesolens::InvalidInput);
  EXPECT_THROW(mesolens::mid_surface_points(Flat{ 0, 0, 0 }, 1.0, -1.0), mesolens::InvalidInput);
  EXPECT_THROW(mesolens::mid_surface_points(Flat{ 0, 0, 0 }, 1.0, 1.0, -1), mesolens::InvalidInput);
}
