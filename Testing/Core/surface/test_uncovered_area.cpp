// SPDX-License-Identifier: GPL-3.0-or-later
// The exact uncovered part of the unit sphere under caps (a private part of MesoLensCore, used
// for concave patches that neighbouring probes cut): closed forms, and degenerate arrangements
// refused.
#include "surface/detail/sas_boundary.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <random>
#include <vector>

namespace {
using Vec = Eigen::Vector3d;
using mesolens::UnitCap;
constexpr double pi = 3.14159265358979323846;

void expect_near(const Vec& a, const Vec& b, double tolerance)
{
  EXPECT_NEAR((a - b).norm(), 0.0, tolerance) << a.transpose() << " against " << b.transpose();
}
} // namespace

TEST(UncoveredArea, OneCapLeavesTheRestOfTheSphere)
{
  const Vec axis = Vec(0.3, -0.5, 0.8).normalized();
  const double height = 0.35;
  double area = 0;
  Vec direction = Vec::Zero();
  ASSERT_TRUE(mesolens::uncovered_unit_area({ { axis, height } }, area, direction));
  EXPECT_NEAR(area, 2 * pi * (1 + height), 1e-12);
  // The cap's own integral of u is pi (1 - h^2) along its axis; the whole sphere's is zero.
  expect_near(direction, -pi * (1 - height * height) * axis, 1e-12);
}

TEST(UncoveredArea, ThreeHemispheresLeaveAnOctantAndACapInsideItIsTakenOut)
{
  std::vector<UnitCap> caps = { { -Vec::UnitX(), 0.0 },
                                { -Vec::UnitY(), 0.0 },
                                { -Vec::UnitZ(), 0.0 } };
  double area = 0;
  Vec direction = Vec::Zero();
  ASSERT_TRUE(mesolens::uncovered_unit_area(caps, area, direction));
  EXPECT_NEAR(area, pi / 2, 1e-12);
  expect_near(direction, Vec::Constant(pi / 4), 1e-12);
  // A cap of 25.8 degrees about the octant's middle (35.3 degrees from its sides).
  const Vec middle = Vec::Ones().normalized();
  caps.push_back({ middle, 0.9 });
  ASSERT_TRUE(mesolens::uncovered_unit_area(caps, area, direction));
  EXPECT_NEAR(area, pi / 2 - 2 * pi * (1 - 0.9), 1e-12);
  expect_near(direction, Vec::Constant(pi / 4) - pi * (1 - 0.81) * middle, 1e-12);
  // One cutting across a side: the octant less a cap about the x axis's end, whose quarter
  // lies in the octant.
  caps.back() = { Vec::UnitX(), 0.6 };
  ASSERT_TRUE(mesolens::uncovered_unit_area(caps, area, direction));
  EXPECT_NEAR(area, pi / 2 - 0.25 * 2 * pi * (1 - 0.6), 1e-12);
}

TEST(UncoveredArea, ThreeCirclesThroughOnePointAreRefused)
{
  // The great circles x = 0, y = 0 and x = y all pass through the poles.
  const std::vector<UnitCap> caps = { { -Vec::UnitX(), 0.0 },
                                      { -Vec::UnitY(), 0.0 },
                                      { Vec(1, -1, 0).normalized(), 0.0 } };
  double area = -1;
  Vec direction = Vec::Zero();
  EXPECT_FALSE(mesolens::uncovered_unit_area(caps, area, direction));
  EXPECT_EQ(area, -1);
}

TEST(UncoveredArea, ThreeCirclesThroughPointsThatFourthCapsHoldAreMeasured)
{
  // The three great circles above, with caps of 60 degrees about both poles, where they cross:
  // the lune 45 <= azimuth <= 90 degrees within |z| < 0.5. Its area is an eighth of the band's
  // 2 pi, and its integral of u is, with dA = dz dazimuth, the band's integral of sqrt(1 - z^2)
  // times that of (cos, sin) over the lune's azimuths.
  const std::vector<UnitCap> caps = { { -Vec::UnitX(), 0.0 },
                                      { -Vec::UnitY(), 0.0 },
                                      { Vec(1, -1, 0).normalized(), 0.0 },
                                      { Vec::UnitZ(), 0.5 },
                                      { -Vec::UnitZ(), 0.5 } };
  double area = 0;
  Vec direction = Vec::Zero();
  ASSERT_TRUE(mesolens::uncovered_unit_area(caps, area, direction));
  EXPECT_NEAR(area, pi / 4, 1e-12);
  const double band = 0.5 * std::sqrt(0.75) + pi / 6; // integral of sqrt(1 - z^2), |z| < 0.5
  expect_near(direction, band * Vec(1 - std::sqrt(0.5), std::sqrt(0.5), 0), 1e-12);
  // With one pole left open, its crossing is degenerate again.
  const std::vector<UnitCap> one_pole(caps.begin(), caps.end() - 1);
  EXPECT_FALSE(mesolens::uncovered_unit_area(one_pole, area, direction));
}

TEST(UncoveredArea, ManyCapsInOverlappingGroupsAgreeWithSampling)
{
  // 150 small caps (more than two 64-cap words of the overlap sets), crossing one another in
  // groups of all sizes: the exact area and direction integral against 400 000 points spread
  // evenly over the sphere (a Fibonacci lattice, good to about 1e-4 of the whole).
  std::mt19937 generator(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> angle(4.0 * pi / 180.0, 10.0 * pi / 180.0);
  std::vector<UnitCap> caps;
  for (int k = 0; k < 150; ++k)
  {
    const Vec axis = Vec(normal(generator), normal(generator), normal(generator)).normalized();
    caps.push_back({ axis, std::cos(angle(generator)) });
  }
  double area = 0;
  Vec direction = Vec::Zero();
  ASSERT_TRUE(mesolens::uncovered_unit_area(caps, area, direction));
  constexpr int samples = 400000;
  const double golden = pi * (3.0 - std::sqrt(5.0));
  int uncovered = 0;
  Vec sampled_direction = Vec::Zero();
  for (int s = 0; s < samples; ++s)
  {
    const double z = 1.0 - (2.0 * s + 1.0) / samples;
    const double ring = std::sqrt(1.0 - z * z);
    const Vec u(ring * std::cos(golden * s), ring * std::sin(golden * s), z);
    bool covered = false;
    for (const UnitCap& cap : caps)
    {
      covered = covered || u.dot(cap.axis) > cap.height;
    }
    if (!covered)
    {
      ++uncovered;
      sampled_direction += u;
    }
  }
  const double cell = 4.0 * pi / samples;
  EXPECT_GT(area, 5.0); // partly covered: most caps overlap others, groups stay apart
  EXPECT_LT(area, 10.0);
  EXPECT_NEAR(area, cell * uncovered, 2e-3);
  expect_near(direction, cell * sampled_direction, 2e-3);
}
