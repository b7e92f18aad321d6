// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/common/errors.h"
#include "mesolens/surface/sphere_union_area.h"
#include "mesolens_test_data.h"
#include "mesolens_test_meshes.h"
#include "mesolens_test_threads.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>

namespace {
using Centres = std::vector<std::array<double, 3>>;
constexpr double pi = 3.14159265358979323846;

/// The exposed area of each sphere estimated by sampling its surface (`samples` points on a
/// Fibonacci lattice): an independent check, accurate to about 1 / samples.
std::vector<double> sampled_areas(const std::vector<std::array<double, 3>>& centres,
                                  const std::vector<double>& radii, int samples)
{
  const auto unit = mesolens_test::fibonacci_sphere(samples, 1.0);
  std::vector<double> areas(centres.size(), 0.0);
  for (std::size_t i = 0; i < centres.size(); ++i)
  {
    int exposed = 0;
    for (int s = 0; s < samples; ++s)
    {
      const std::array<double, 3> p{ centres[i][0] + radii[i] * unit[3 * s],
                                     centres[i][1] + radii[i] * unit[3 * s + 1],
                                     centres[i][2] + radii[i] * unit[3 * s + 2] };
      bool inside = false;
      for (std::size_t j = 0; j < centres.size() && !inside; ++j)
      {
        if (j == i)
          continue;
        const double dx = p[0] - centres[j][0], dy = p[1] - centres[j][1],
                     dz = p[2] - centres[j][2];
        inside = dx * dx + dy * dy + dz * dz < radii[j] * radii[j];
      }
      exposed += inside ? 0 : 1;
    }
    areas[i] = 4 * pi * radii[i] * radii[i] * exposed / samples;
  }
  return areas;
}
} // namespace

TEST(SphereUnionArea, OneSphereAndTwoOverlapping)
{
  const auto one = mesolens::sphere_union_area(Centres{ { 1, 2, 3 } }, { 1.7 });
  EXPECT_NEAR(one.total, 4 * pi * 1.7 * 1.7, 1e-12);
  // Two spheres: each loses a cap of height r - (r^2 + d^2 - r'^2) / 2d.
  const double r1 = 1.8, r2 = 1.3, d = 2.1;
  const auto two = mesolens::sphere_union_area(Centres{ { 0, 0, 0 }, { d, 0, 0 } }, { r1, r2 });
  const double h1 = (r1 * r1 + d * d - r2 * r2) / (2 * r1 * d);
  const double h2 = (r2 * r2 + d * d - r1 * r1) / (2 * r2 * d);
  EXPECT_NEAR(two.per_sphere[0], 2 * pi * r1 * r1 * (1 + h1), 1e-9);
  EXPECT_NEAR(two.per_sphere[1], 2 * pi * r2 * r2 * (1 + h2), 1e-9);
  // Apart, nested, coincident.
  EXPECT_NEAR(mesolens::sphere_union_area(Centres{ { 0, 0, 0 }, { 5, 0, 0 } }, { 1, 2 }).total,
              4 * pi * 5, 1e-9);
  const auto nested = mesolens::sphere_union_area(Centres{ { 0, 0, 0 }, { 0.5, 0, 0 } }, { 3, 1 });
  EXPECT_NEAR(nested.per_sphere[0], 4 * pi * 9, 1e-9);
  EXPECT_EQ(nested.per_sphere[1], 0.0);
  const auto same = mesolens::sphere_union_area(Centres{ { 1, 1, 1 }, { 1, 1, 1 } }, { 2, 2 });
  EXPECT_NEAR(same.total, 4 * pi * 4, 1e-9);
  // Volumes: a ball, and two less their lens, r1 + r2 - d deep.
  EXPECT_NEAR(one.volume, 4.0 / 3.0 * pi * std::pow(1.7, 3), 1e-9);
  const double lens = pi * std::pow(r1 + r2 - d, 2) *
    (d * d + 2 * d * (r1 + r2) - 3 * (r1 - r2) * (r1 - r2)) / (12 * d);
  EXPECT_NEAR(two.volume, 4.0 / 3.0 * pi * (std::pow(r1, 3) + std::pow(r2, 3)) - lens, 1e-9);
  EXPECT_NEAR(nested.volume, 4.0 / 3.0 * pi * 27, 1e-9);
  EXPECT_NEAR(same.volume, 4.0 / 3.0 * pi * 8, 1e-9);
}

TEST(SphereUnionArea, ANeighbourOfTwoCoincidentSpheresCountsTheirCapOnce)
{
  // Two coincident spheres cut the same cap from a third: the caps' circles coincide to
  // rounding, and the third sphere lost its whole area and the volume went negative (the
  // spheres fuzz_surface met, 1e-4 Å with the third 1.6e-6 Å away). The union is that of two
  // spheres, at any scale.
  for (const double scale : { 1.0, 100.0, 1e4 })
  {
    const Centres centres{ { -7.6862745098039218 * scale, -8 * scale, -6.3686274509803926 * scale },
                           { -7.6862745098039218 * scale, -8 * scale, -6.3686274509803926 * scale },
                           { -7.6862752588235299 * scale, -8.0000009999999993 * scale,
                             -6.3686284509803928 * scale } };
    const double r = 1e-4 * scale;
    const auto three = mesolens::sphere_union_area(centres, { r, r, r });
    double d = 0;
    for (int k = 0; k < 3; ++k)
    {
      d += (centres[2][k] - centres[0][k]) * (centres[2][k] - centres[0][k]);
    }
    d = std::sqrt(d);
    const double h = d / (2 * r); // each keeps 1 + h of its half
    EXPECT_NEAR(three.total, 4 * pi * r * r * (1 + h), 1e-9 * r * r) << scale;
    EXPECT_NEAR(three.per_sphere[2], 2 * pi * r * r * (1 + h), 1e-9 * r * r) << scale;
    const double lens = pi * std::pow(2 * r - d, 2) * (d * d + 4 * d * r) / (12 * d);
    EXPECT_NEAR(three.volume, 8.0 / 3.0 * pi * r * r * r - lens, 1e-6 * r * r * r) << scale;
  }
}

TEST(SphereUnionArea, EqualSpheresATinyDistanceApartCountOnce)
{
  // Centres 8e-128 Å apart: d + r rounds to r, so each sphere held the other and both were
  // dropped as buried (found by fuzz_surface). The first stays. 1e-20 Å apart (more than half
  // an ulp of r) they are two spheres that each keep half.
  for (const double offset : { 8.1207038992666975e-128, 1e-20, 0.0 })
  {
    const auto two = mesolens::sphere_union_area(Centres{ { -7.6, 7.8, offset }, { -7.6, 7.8, 0 } },
                                                 { 1e-4, 1e-4 });
    EXPECT_NEAR(two.total, 4 * pi * 1e-8, 1e-20) << offset;
    EXPECT_NEAR(two.volume, 4.0 / 3.0 * pi * 1e-12, 1e-24) << offset;
    if (offset != 1e-20)
    {
      EXPECT_EQ(two.per_sphere[1], 0.0) << offset;
    }
  }
}

TEST(SphereUnionArea, ThreeInARowAndAClusterAgreeWithSampling)
{
  // Three in a row: the middle one loses two disjoint caps (closed form).
  const double r = 1.5, d = 2.0;
  const auto row =
    mesolens::sphere_union_area(Centres{ { -d, 0, 0 }, { 0, 0, 0 }, { d, 0, 0 } }, { r, r, r });
  const double h = d / (2 * r);
  const double lens = pi * std::pow(2 * r - d, 2) * (d * d + 4 * d * r) / (12 * d);
  EXPECT_NEAR(row.volume, 3 * 4.0 / 3.0 * pi * r * r * r - 2 * lens, 1e-9);
  EXPECT_NEAR(row.per_sphere[1], 4 * pi * r * r - 2 * 2 * pi * r * r * (1 - h), 1e-9);
  EXPECT_NEAR(row.per_sphere[0], 2 * pi * r * r * (1 + h), 1e-9);
  // Three overlapping pairwise with a common triple region, and a random cluster of 40 spheres
  // (caps that cross, nest and cover whole spheres): the exact areas against 200 000 samples.
  std::vector<std::array<double, 3>> centres{ { 0, 0, 0 }, { 1.6, 0, 0 }, { 0.8, 1.3, 0 } };
  std::vector<double> radii{ 1.2, 1.0, 1.1 };
  std::mt19937 generator(3);
  std::uniform_real_distribution<double> position(-4.0, 4.0), size(0.8, 2.0);
  for (int i = 0; i < 40; ++i)
  {
    centres.push_back({ position(generator) + 20, position(generator), position(generator) });
    radii.push_back(size(generator));
  }
  const auto exact = mesolens::sphere_union_area(centres, radii);
  const auto sampled = sampled_areas(centres, radii, 200000);
  for (std::size_t i = 0; i < centres.size(); ++i)
    EXPECT_NEAR(exact.per_sphere[i], sampled[i], 0.002 * 4 * pi * radii[i] * radii[i] + 1e-9)
      << "sphere " << i;
  // The volume of the cluster against 2 000 000 random points in its box.
  double low[3] = { 1e9, 1e9, 1e9 }, high[3] = { -1e9, -1e9, -1e9 };
  for (std::size_t i = 3; i < centres.size(); ++i)
    for (int k = 0; k < 3; ++k)
    {
      low[k] = std::min(low[k], centres[i][k] - radii[i]);
      high[k] = std::max(high[k], centres[i][k] + radii[i]);
    }
  std::uniform_real_distribution<double> unit_interval(0.0, 1.0);
  const int points = 2000000;
  int inside_count = 0;
  for (int s = 0; s < points; ++s)
  {
    double p[3];
    for (int k = 0; k < 3; ++k)
      p[k] = low[k] + (high[k] - low[k]) * unit_interval(generator);
    for (std::size_t i = 3; i < centres.size(); ++i)
    {
      const double dx = p[0] - centres[i][0], dy = p[1] - centres[i][1], dz = p[2] - centres[i][2];
      if (dx * dx + dy * dy + dz * dz < radii[i] * radii[i])
      {
        ++inside_count;
        break;
      }
    }
  }
  const double box = (high[0] - low[0]) * (high[1] - low[1]) * (high[2] - low[2]);
  const std::vector<std::array<double, 3>> cluster(centres.begin() + 3, centres.end());
  const std::vector<double> cluster_radii(radii.begin() + 3, radii.end());
  const double sampled_volume = box * inside_count / points;
  EXPECT_NEAR(mesolens::sphere_union_area(cluster, cluster_radii).volume, sampled_volume,
              0.005 * sampled_volume);
  // The same on two threads.
  const auto two_threads = mesolens_test::two_threads();
  EXPECT_EQ(mesolens::sphere_union_area(centres, radii, two_threads).per_sphere, exact.per_sphere);
}

TEST(SphereUnionArea, SpheresWithManyNeighboursAgreeWithSampling)
{
  // Large spheres packed in a small box, as atoms inflated by a large probe: each overlaps
  // most of the others, and those with the most keep only their power cell's neighbours.
  std::mt19937 generator(11);
  std::uniform_real_distribution<double> position(0.0, 12.0), size(2.5, 4.0);
  std::vector<std::array<double, 3>> centres;
  std::vector<double> radii;
  for (int i = 0; i < 150; ++i)
  {
    centres.push_back({ position(generator), position(generator), position(generator) });
    radii.push_back(size(generator));
  }
  std::size_t most = 0;
  for (std::size_t i = 0; i < centres.size(); ++i)
  {
    std::size_t overlapping = 0;
    for (std::size_t j = 0; j < centres.size(); ++j)
    {
      const double dx = centres[i][0] - centres[j][0], dy = centres[i][1] - centres[j][1],
                   dz = centres[i][2] - centres[j][2];
      overlapping += j != i && std::sqrt(dx * dx + dy * dy + dz * dz) < radii[i] + radii[j];
    }
    most = std::max(most, overlapping);
  }
  ASSERT_GT(most, 100u);
  const auto exact = mesolens::sphere_union_area(centres, radii);
  const auto sampled = sampled_areas(centres, radii, 5000);
  double total = 0, sampled_total = 0;
  for (std::size_t i = 0; i < centres.size(); ++i)
  {
    EXPECT_NEAR(exact.per_sphere[i], sampled[i], 0.005 * 4 * pi * radii[i] * radii[i])
      << "sphere " << i;
    total += exact.per_sphere[i];
    sampled_total += sampled[i];
  }
  EXPECT_NEAR(total, sampled_total, 0.002 * total);
  EXPECT_GT(total, 100.0); // an outer layer is exposed
}

TEST(SphereUnionArea, SolventAccessibleAreaOfUbiquitinAsFreeSasa)
{
  // FreeSASA 2.1.2's per-atom output for 1ubq (ProtOr radii in the occupancy column, Lee &
  // Richards' 20 slices per atom in the B-factor column), probe 1.4 Å.
  const std::string path =
    mesolens_test::shared_file("reference/generated/1ubq_freesasa_LR20_per_atom.pdb");
  if (!mesolens_test::exists(path))
    GTEST_SKIP() << "needs ../shared/data";
  std::ifstream lines(path);
  std::string line;
  std::vector<std::array<double, 3>> centres;
  std::vector<double> radii, reference;
  while (std::getline(lines, line))
  {
    if (line.rfind("ATOM", 0) != 0)
      continue;
    centres.push_back({ std::stod(line.substr(30, 8)), std::stod(line.substr(38, 8)),
                        std::stod(line.substr(46, 8)) });
    radii.push_back(std::stod(line.substr(54, 6)) + 1.4);
    reference.push_back(std::stod(line.substr(60, 6)));
  }
  ASSERT_EQ(centres.size(), 602u);
  const auto exact = mesolens::sphere_union_area(centres, radii);
  double lee_richards = 0;
  for (double value : reference)
    lee_richards += value;
  std::printf("1ubq SAS: exact %.2f Å², FreeSASA Lee-Richards (20 slices) %.2f Å² "
              "(published 4804.06), relative difference %.5f\n",
              exact.total, lee_richards, (exact.total - lee_richards) / lee_richards);
  EXPECT_NEAR(exact.total, 4804.06, 0.001 * 4804.06);
  // Atom by atom too: the slices' error spreads over the atoms but stays small.
  double differences = 0;
  for (std::size_t i = 0; i < reference.size(); ++i)
    differences += std::abs(exact.per_sphere[i] - reference[i]);
  std::printf("1ubq SAS: per-atom absolute differences sum to %.2f Å² (%.3f of the total)\n",
              differences, differences / lee_richards);
  EXPECT_LT(differences / lee_richards, 0.02);
}

TEST(SphereUnionArea, BadInputs)
{
  EXPECT_EQ(mesolens::sphere_union_area(Centres{}, {}).total, 0.0);
  EXPECT_THROW(mesolens::sphere_union_area(Centres{ { 0, 0, 0 } }, {}), mesolens::InvalidInput);
  EXPECT_THROW(mesolens::sphere_union_area(Centres{ { 0, 0, 0 } }, { 0.0 }),
               mesolens::InvalidInput);
  EXPECT_THROW(mesolens::sphere_union_area(Centres{ { 0, 0, 0 } }, { -1.0 }),
               mesolens::InvalidInput);
  EXPECT_THROW(mesolens::sphere_union_area(Centres{ { std::nan(""), 0, 0 } }, { 1.0 }),
               mesolens::InvalidInput);
  EXPECT_THROW(mesolens::sphere_union_area(Centres{ { 0, 0, 0 } }, { INFINITY }),
               mesolens::InvalidInput);
}

// Found by fuzz_surface: finite centres far out (1e191) overflowed the neighbour grid's cell
// index (undefined behaviour) and left no digits for the geometry.
TEST(SphereUnionArea, SpheresBeyondTheCoordinateLimitAreRefused)
{
  for (const double far : { 2e8, -1e191, 1.7e308 })
  {
    try
    {
      mesolens::sphere_union_area(Centres{ { 0, 0, 0 }, { 0, far, 0 } }, { 1.0, 1.0 });
      ADD_FAILURE() << far << " accepted";
    }
    catch (const mesolens::InvalidInput& e)
    {
      EXPECT_NE(std::string(e.what()).find("sphere 1 lies or reaches beyond"), std::string::npos)
        << e.what();
    }
  }
  EXPECT_THROW(mesolens::sphere_union_area(Centres{ { 0, 0, 0 } }, { 1e300 }),
               mesolens::InvalidInput);
  // Just inside the limit, a sphere is still measured exactly.
  const double limit = mesolens::largest_sphere_coordinate;
  const auto area = mesolens::sphere_union_area(Centres{ { limit - 2, 0, 0 } }, { 1.0 });
  EXPECT_NEAR(area.total, 4 * M_PI, 1e-9);
}
