// SPDX-License-Identifier: GPL-3.0-or-later
// The clearance certificates of the solvent-excluded patches (a private part of MesoLensCore):
// against brute-force distances from densely sampled patches and foreign probe positions. A
// certificate may only say "clear" where no position comes within the probe radius, and must
// say so where every position stays well outside it.
#include "surface/detail/patch_clearance.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <random>
#include <vector>

namespace {
using Vec = Eigen::Vector3d;
using mesolens::SasArc;
constexpr double pi = 3.14159265358979323846;
constexpr double probe = 1.4;

SasArc make_arc(const Vec& centre, const Vec& axis, double radius, double start, double span)
{
  SasArc arc;
  arc.centre = centre;
  arc.axis = axis.normalized();
  const Vec helper = std::abs(arc.axis[0]) < 0.9 ? Vec::UnitX() : Vec::UnitY();
  arc.e1 = arc.axis.cross(helper).normalized();
  arc.e2 = arc.axis.cross(arc.e1);
  arc.radius = radius;
  arc.start = start;
  arc.span = span;
  return arc;
}

/// An arc of random centre (in the box [low, high]), axis, radius (0.3 to 2.5 Å) and span.
SasArc random_arc(std::mt19937& random, const Vec& low, const Vec& high)
{
  std::uniform_real_distribution<double> fraction(0.0, 1.0), unit(-1.0, 1.0), radius(0.3, 2.5),
    angle(0.0, 2.0 * pi), span(0.2, 2.0 * pi);
  const Vec centre(low[0] + (high[0] - low[0]) * fraction(random),
                   low[1] + (high[1] - low[1]) * fraction(random),
                   low[2] + (high[2] - low[2]) * fraction(random));
  const Vec axis(unit(random), unit(random), unit(random) + 1e-3);
  return make_arc(centre, axis, radius(random), angle(random), span(random));
}

/// Points of a torus piece on a grid of n x n parameters.
std::vector<Vec> torus_samples(const mesolens::TorusPatchPiece& torus, int n)
{
  std::vector<Vec> points;
  const SasArc& arc = *torus.arc;
  for (int i = 0; i <= n; ++i)
  {
    const double phi = torus.phi0 + (torus.phi1 - torus.phi0) * i / n;
    const Vec d = std::cos(phi) * arc.e1 + std::sin(phi) * arc.e2;
    for (int j = 0; j <= n; ++j)
    {
      const double t = torus.t0 + (torus.t1 - torus.t0) * j / n;
      points.push_back(arc.centre + arc.radius * d +
                       torus.probe * (std::cos(t) * arc.axis + std::sin(t) * d));
    }
  }
  return points;
}

/// Points of an exposed arc, n + 1 along it, ends included.
std::vector<Vec> arc_samples(const SasArc& arc, int n)
{
  std::vector<Vec> points;
  for (int i = 0; i <= n; ++i)
  {
    points.push_back(arc.point(arc.start + arc.span * i / n));
  }
  return points;
}

double nearest(const std::vector<Vec>& a, const std::vector<Vec>& b)
{
  double best = 1e300;
  for (const Vec& x : a)
  {
    for (const Vec& y : b)
    {
      best = std::min(best, (x - y).squaredNorm());
    }
  }
  return std::sqrt(best);
}

/// Tallies of one kind of test over random foreign pieces.
struct Tally
{
  int cut = 0, clear = 0, near = 0;
};

/// Checks one verdict against the sampled distance (which can only overestimate the true one,
/// by at most `sampling` Å): "clear" where something comes nearer than p is wrong; "not clear"
/// where everything stays 0.1 Å beyond p is a certificate too weak to be of use.
void check(bool certified, double sampled, double sampling, Tally& tally)
{
  if (sampled < probe - sampling)
  {
    ++tally.cut;
    EXPECT_FALSE(certified) << "certified clear, though a position lies " << sampled
                            << " Å from the patch";
  }
  else if (sampled > probe + 0.1)
  {
    ++tally.clear;
    EXPECT_TRUE(certified) << "not certified, though every position lies " << sampled
                           << " Å or more from the patch";
  }
  else
  {
    ++tally.near;
  }
}

// A torus piece of a probe passing between two atoms 2.6 Å apart, over 60 degrees of azimuth.
struct TorusCase
{
  SasArc arc = make_arc(Vec(0.3, -0.2, 0.1), Vec(0.2, 0.1, 1.0), 1.6, 0.4, 1.2);
  mesolens::TorusPatchPiece piece{ &arc, probe, 0.5, 0.5 + pi / 3, -2.4, -0.7 };
  std::vector<Vec> samples = torus_samples(piece, 120);
  // Grid steps of about (rho + p) * 0.009 and p * 0.014 in the two directions.
  double sampling = 0.03;
};
} // namespace

TEST(PatchClearance, TorusAgainstSinglePositions)
{
  const TorusCase torus;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-4.0, 4.0);
  Tally tally;
  for (int k = 0; k < 1500; ++k)
  {
    const Vec w(coordinate(random), coordinate(random), coordinate(random));
    const double sampled = nearest(torus.samples, { w });
    check(mesolens::torus_clear_of_position(torus.piece, w), sampled, torus.sampling, tally);
  }
  // Both verdicts occur often enough to matter.
  EXPECT_GT(tally.cut, 50);
  EXPECT_GT(tally.clear, 500);
}

TEST(PatchClearance, TorusAgainstArcs)
{
  const TorusCase torus;
  std::mt19937 random(11);
  Tally tally;
  for (int k = 0; k < 300; ++k)
  {
    const SasArc other = random_arc(random, Vec::Constant(-4.0), Vec::Constant(4.0));
    const double sampled = nearest(torus.samples, arc_samples(other, 200));
    check(mesolens::torus_clear_of_arc(torus.piece, other), sampled, torus.sampling + 0.04, tally);
  }
  EXPECT_GT(tally.cut, 20);
  EXPECT_GT(tally.clear, 100);
}

TEST(PatchClearance, ConcaveTriangleAgainstArcs)
{
  // A probe at the origin touching three atoms; its patch is the spherical triangle of the
  // directions to them.
  const Vec u0 = Vec(1.0, 0.1, 0.2).normalized(), u1 = Vec(0.1, 1.0, 0.3).normalized(),
            u2 = Vec(0.2, 0.3, 1.0).normalized();
  const Vec centre(0.5, -0.3, 0.2);
  const mesolens::SphericalTriangle triangle(u0, u1, u2);
  ASSERT_GT(u0.dot(u1.cross(u2)), 0);
  std::vector<Vec> samples;
  const int n = 150;
  for (int i = 0; i <= n; ++i)
  {
    for (int j = 0; i + j <= n; ++j)
    {
      const Vec u = (double(i) * u0 + double(j) * u1 + double(n - i - j) * u2).normalized();
      samples.push_back(centre + probe * u);
    }
  }
  std::mt19937 random(5);
  Tally tally;
  for (int k = 0; k < 400; ++k)
  {
    const SasArc other = random_arc(random, Vec::Constant(-3.5), Vec::Constant(4.5));
    const double sampled = nearest(samples, arc_samples(other, 200));
    check(mesolens::concave_clear_of_arc(centre, probe, triangle, other), sampled, 0.05, tally);
  }
  EXPECT_GT(tally.cut, 20);
  EXPECT_GT(tally.clear, 100);
}

TEST(PatchClearance, ArcsEndingOnThePatchAreNotCertified)
{
  // A foreign arc whose end lies inside the probe ball of a patch point cuts the patch, however
  // far the rest of it runs.
  const TorusCase torus;
  const Vec inside = torus.samples[torus.samples.size() / 2];
  const SasArc far_arc = make_arc(Vec(30, 0, 0), Vec::UnitZ(), 2.0, 0.0, 1.0);
  EXPECT_TRUE(mesolens::torus_clear_of_arc(torus.piece, far_arc));
  SasArc ending = make_arc(Vec::Zero(), Vec::UnitZ(), 2.0, -0.5, 0.5);
  ending.centre = inside - ending.radius * ending.e1; // its end at azimuth 0 on the patch
  ASSERT_LT((ending.point(0.0) - inside).norm(), 1e-9);
  EXPECT_FALSE(mesolens::torus_clear_of_arc(torus.piece, ending));
  EXPECT_FALSE(mesolens::torus_clear_of_position(torus.piece, inside));
}

namespace {
/// Atoms of inflated radii `radii` (Å) touching the probe position at the origin from unit
/// directions `directions`, and the accessible positions among random points within two probe
/// radii of it.
struct Touching
{
  std::vector<Vec> centres;
  std::vector<double> radii;

  Touching(const std::vector<Vec>& directions, const std::vector<double>& inflated)
    : radii(inflated)
  {
    for (std::size_t a = 0; a < directions.size(); ++a)
    {
      this->centres.push_back(inflated[a] * directions[a].normalized());
    }
  }

  std::vector<Vec> accessible_points(unsigned seed, int count) const
  {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> coordinate(-2.0 * probe, 2.0 * probe);
    std::vector<Vec> points;
    while (int(points.size()) < count)
    {
      const Vec w(coordinate(random), coordinate(random), coordinate(random));
      bool kept = w.norm() < 2.0 * probe; // nearer can reach the probe's sphere
      for (std::size_t a = 0; a < this->centres.size() && kept; ++a)
      {
        kept = (w - this->centres[a]).norm() >= this->radii[a];
      }
      if (kept)
      {
        points.push_back(w);
      }
    }
    return points;
  }
};

/// Points v + p u of the probe's sphere at the origin for u in the cone of `directions` (two:
/// the arc between them; three: the spherical triangle), n steps a side.
std::vector<Vec> cone_samples(const std::vector<Vec>& directions, int n)
{
  std::vector<Vec> points;
  for (int i = 0; i <= n; ++i)
  {
    for (int j = 0; i + j <= n; ++j)
    {
      if (directions.size() == 2 && i + j != n)
      {
        continue;
      }
      Vec u = double(i) * directions[0] + double(j) * directions[1];
      if (directions.size() == 3)
      {
        u += double(n - i - j) * directions[2];
      }
      points.push_back(probe * u.normalized());
    }
  }
  return points;
}
} // namespace

TEST(PatchClearance, NarrowPatchesAreClearOfEveryAccessiblePosition)
{
  // A torus between atoms of inflated radii 3.1 and 3.0 Å, 3 Å apart: its generating arc
  // spans about 59 degrees, and no position outside both atoms reaches it (some come within
  // the sampling of the probe radius: the probe's own path).
  const Vec first = Vec(-1.6, -2.65, 0).normalized(), second = Vec(1.4, -2.65, 0).normalized();
  const double span = std::acos(first.dot(second));
  EXPECT_TRUE(mesolens::torus_clear_of_every_position(probe, 3.1, 3.0, span));
  const Touching pair({ first, second }, { 3.1, 3.0 });
  const double torus_gap =
    nearest(cone_samples({ first, second }, 400), pair.accessible_points(11, 3000));
  EXPECT_GT(torus_gap, probe - 0.01);
  // A concave patch on three atoms 30 to 40 degrees apart.
  const std::vector<Vec> close = { Vec(0.3, 0, -1).normalized(), Vec(-0.2, 0.3, -1).normalized(),
                                   Vec(-0.2, -0.35, -1).normalized() };
  const double radii[3] = { 3.0, 3.2, 2.9 };
  const Vec corners[3] = { close[0], close[1], close[2] };
  EXPECT_TRUE(mesolens::concave_clear_of_every_position(probe, corners, radii));
  const Touching triple(close, { 3.0, 3.2, 2.9 });
  EXPECT_GT(nearest(cone_samples(close, 60), triple.accessible_points(13, 3000)), probe - 0.01);
}

TEST(PatchClearance, WidePatchesAreLeftToTheirCertificates)
{
  // A probe passing between atoms of inflated radius 2.9 Å, 5.3 Å apart: its own positions
  // across the axis cut the torus, and the condition fails.
  const Vec first = Vec(-2.65, -1.18, 0).normalized(), second = Vec(2.65, -1.18, 0).normalized();
  const double span = std::acos(first.dot(second));
  EXPECT_FALSE(mesolens::torus_clear_of_every_position(probe, 2.9, 2.9, span));
  const Touching pair({ first, second }, { 2.9, 2.9 });
  EXPECT_LT(nearest(cone_samples({ first, second }, 400), pair.accessible_points(17, 3000)),
            probe - 0.1);
  // Three atoms 70 degrees from the middle: a position below the probe, between them, is
  // accessible and cuts the concave patch.
  std::vector<Vec> wide;
  for (int a = 0; a < 3; ++a)
  {
    const double turn = 2.0 * pi * a / 3.0, tilt = 70.0 * pi / 180.0;
    wide.emplace_back(std::sin(tilt) * std::cos(turn), std::sin(tilt) * std::sin(turn),
                      -std::cos(tilt));
  }
  const double radii[3] = { 3.0, 3.0, 3.0 };
  const Vec corners[3] = { wide[0], wide[1], wide[2] };
  EXPECT_FALSE(mesolens::concave_clear_of_every_position(probe, corners, radii));
  const Touching triple(wide, { 3.0, 3.0, 3.0 });
  const Vec below(0, 0, -1.8 * probe);
  for (const Vec& c : triple.centres)
  {
    ASSERT_GE((below - c).norm(), 3.0);
  }
  EXPECT_LT(nearest(cone_samples(wide, 60), { below }), probe - 0.1);
}
