// SPDX-License-Identifier: GPL-3.0-or-later
// Where a grid edge crosses a surface (a private part of MesoLensCore, used for the molecular
// surfaces' vertices): the closed-form sphere crossings, Newton's method and regula falsi
// against exact roots.
#include "surface/detail/segment_roots.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace {
using Vec = Eigen::Vector3d;
}

TEST(SegmentRoots, LineSphereCrossingsAreOnTheSphereForAnySegment)
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
    // One end inside: the line crosses, once between the ends (the entry when b is inside, the
    // exit when a is).
    double entry = 0, exit = 0;
    ASSERT_TRUE(mesolens::line_sphere(a, b, centre, radius, entry, exit));
    const double t = b_in ? entry : exit;
    ASSERT_GE(t, -1e-12);
    ASSERT_LE(t, 1.0 + 1e-12);
    ASSERT_NEAR((a + t * (b - a) - centre).norm(), radius, 1e-12 * (1 + (b - a).norm()));
    ASSERT_TRUE(b_in ? exit > 1.0 - 1e-12 : entry < 1e-12);
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

TEST(SegmentRoots, LineSphereGivesTheEntryAndTheExit)
{
  const Vec centre(1, -2, 0.5);
  double entry = 0, exit = 0;
  // Through the centre along x: in at t = 0.25, out at 0.75 (the segment is 4 long).
  ASSERT_TRUE(
    mesolens::line_sphere(centre - Vec(2, 0, 0), centre + Vec(2, 0, 0), centre, 1.0, entry, exit));
  EXPECT_NEAR(entry, 0.25, 1e-15);
  EXPECT_NEAR(exit, 0.75, 1e-15);
  // Crossings beyond the segment's ends are reported as they are (the caller picks).
  ASSERT_TRUE(mesolens::line_sphere(centre + Vec(0.5, 0, 0), centre + Vec(1.5, 0, 0), centre, 1.0,
                                    entry, exit));
  EXPECT_NEAR(entry, -1.5, 1e-15);
  EXPECT_NEAR(exit, 0.5, 1e-15);
  // A line passing by misses it.
  EXPECT_FALSE(mesolens::line_sphere(centre + Vec(-2, 1.5, 0), centre + Vec(2, 1.5, 0), centre, 1.0,
                                     entry, exit));
}

TEST(SegmentRoots, NewtonFindsTheRootOfACircleTubeInFewSteps)
{
  // The distance to the unit circle in the xy plane less 0.5: the root between a point inside
  // the tube and one outside is where the segment leaves it.
  const auto tube = [](const Vec& x, const Vec& direction, double& slope) {
    const Vec radial(x[0], x[1], 0);
    const Vec nearest = radial / radial.norm();
    const double gap = (x - nearest).norm();
    slope = (x - nearest).dot(direction) / gap;
    return gap - 0.5;
  };
  const Vec a(1.1, 0.1, 0.2), b(1.9, 0.6, 0.1);
  int calls = 0;
  double slope = 0;
  const Vec root = mesolens::segment_root_newton(a, tube(a, b - a, slope), b, tube(b, b - a, slope),
                                                 [&](const Vec& x, double& s) {
                                                   ++calls;
                                                   return tube(x, b - a, s);
                                                 });
  EXPECT_NEAR(tube(root, b - a, slope), 0.0, 1e-12);
  EXPECT_LE(calls, 8);
  // Regula falsi to the same root takes more.
  int falsi_calls = 0;
  const Vec falsi =
    mesolens::segment_root(a, tube(a, b - a, slope), b, tube(b, b - a, slope), [&](const Vec& x) {
      ++falsi_calls;
      double s = 0;
      return tube(x, b - a, s);
    });
  EXPECT_NEAR((falsi - root).norm(), 0.0, 1e-9);
  EXPECT_LT(calls, falsi_calls);
  // A slope that points the wrong way falls back to regula falsi and still brackets the root.
  const Vec wrong = mesolens::segment_root_newton(
    a, tube(a, b - a, slope), b, tube(b, b - a, slope), [&](const Vec& x, double& s) {
      const double f = tube(x, b - a, s);
      s = -s;
      return f;
    });
  EXPECT_NEAR((wrong - root).norm(), 0.0, 1e-9);
}

// Found by fuzz_surface: end values that break the precondition (both of one sign, equal, or
// infinite, as a distance search with nothing in reach gives) sent the first step off the
// segment to infinity, and the grid lookup there converted -inf to an integer.
TEST(SegmentRoots, EndValuesThatBreakThePreconditionKeepTheRootOnTheSegment)
{
  const Vec a(1, 2, 3), b(2, 2, 3);
  const double inf = std::numeric_limits<double>::infinity();
  const double cases[][2] = { { -1, -1 },  { 1, 1 },      { 0, 0 },       { -inf, 1 },
                              { -1, inf }, { -inf, inf }, { -inf, -inf }, { std::nan(""), 1 } };
  for (const auto& ends : cases)
  {
    std::vector<Vec> asked;
    const auto value = [&](const Vec& x) {
      asked.push_back(x);
      return ends[0];
    };
    const auto value_and_slope = [&](const Vec& x, double& slope) {
      asked.push_back(x);
      slope = 0;
      return ends[1];
    };
    for (const Vec& root :
         { mesolens::segment_root(a, ends[0], b, ends[1], value),
           mesolens::segment_root_newton(a, ends[0], b, ends[1], value_and_slope) })
    {
      EXPECT_GE(root[0], 1.0) << ends[0] << " " << ends[1];
      EXPECT_LE(root[0], 2.0) << ends[0] << " " << ends[1];
    }
    for (const Vec& x : asked)
    {
      EXPECT_TRUE(x[0] >= 1.0 && x[0] <= 2.0) << x[0] << " for " << ends[0] << " " << ends[1];
    }
  }
}
