// SPDX-License-Identifier: GPL-3.0-or-later
// Where a grid edge crosses a surface (a private part of MesoLensCore, used for the molecular
// surfaces' vertices): the closed-form sphere crossing and regula falsi against exact roots.
#include "segment_roots.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <random>

namespace {
using Vec = Eigen::Vector3d;
}

TEST(SegmentRoots, SphereCrossingEntersAndLeaves)
{
  const Vec centre(1, 2, 3);
  // Entering: the nearer of the line's two crossings; leaving: the farther.
  EXPECT_NEAR(mesolens::sphere_crossing(centre + Vec(-3, 0, 0), centre, centre, 1.0), 2.0 / 3.0,
              1e-15);
  EXPECT_NEAR(mesolens::sphere_crossing(centre, centre + Vec(0, 3, 0), centre, 1.0), 1.0 / 3.0,
              1e-15);
  // Both ends on the far side of the centre: the crossing is still the one between them.
  EXPECT_NEAR(
    mesolens::sphere_crossing(centre + Vec(0, 0, 0.5), centre + Vec(0, 0, 2.5), centre, 1.0), 0.25,
    1e-15);
  // An end on the sphere is the crossing.
  EXPECT_NEAR(mesolens::sphere_crossing(centre + Vec(0, 1, 0), centre + Vec(0, 1, 1), centre, 1.0),
              0.0, 1e-15);
}

TEST(SegmentRoots, SphereCrossingIsOnTheSphereForAnySegment)
{
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const Vec centre(-4, 0.5, 9);
  const double radius = 1.7;
  int checked = 0;
  while (checked < 2000)
  {
    // Short edges near the sphere (as a grid's), and long ones far out (cancellation).
    const double scale = checked % 2 ? 0.6 : 40.0;
    const Vec a = centre +
      (radius + scale * uniform(random)) *
        Vec(uniform(random), uniform(random), uniform(random)).normalized();
    const Vec b = a + scale * Vec(uniform(random), uniform(random), uniform(random));
    const bool a_in = (a - centre).norm() < radius, b_in = (b - centre).norm() < radius;
    if (a_in == b_in)
    {
      continue;
    }
    const double t = mesolens::sphere_crossing(a, b, centre, radius);
    ASSERT_GE(t, 0.0);
    ASSERT_LE(t, 1.0);
    ASSERT_NEAR((a + t * (b - a) - centre).norm(), radius, 1e-12 * (1 + (b - a).norm()));
    ++checked;
  }
}

TEST(SegmentRoots, RegulaFalsiFindsTheRootAndKeepsOffTheEnds)
{
  const Vec a(0, 0, 0), b(2, 0, 0);
  // A curved field with its root at x = sqrt(2).
  const auto value = [](const Vec& x) { return x.squaredNorm() - 2.0; };
  const Vec root = mesolens::segment_root(a, value(a), b, value(b), value);
  EXPECT_NEAR(root[0], std::sqrt(2.0), 1e-9);
  // A root at an end is moved 1e-5 of the segment inside it.
  const auto at_start = [](const Vec& x) { return x[0]; };
  EXPECT_NEAR(mesolens::segment_root(a, 0.0, b, 2.0, at_start)[0], 2e-5, 1e-12);
  EXPECT_NEAR(mesolens::on_segment(a, b, 1.0)[0], 2.0 - 2e-5, 1e-12);
}
