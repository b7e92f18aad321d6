// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/molecules/periodic_box.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace {
double length(const std::array<double, 3>& v)
{
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/// Shortest image by brute force over a wide range of lattice translations.
std::array<double, 3> brute_force_image(const mesolens::PeriodicBox& box, std::array<double, 3> d)
{
  std::array<double, 3> best = d;
  for (int i = -4; i <= 4; ++i)
    for (int j = -4; j <= 4; ++j)
      for (int k = -4; k <= 4; ++k)
      {
        std::array<double, 3> c = d;
        for (int a = 0; a < 3; ++a)
          c[a] += i * box.vectors[0][a] + j * box.vectors[1][a] + k * box.vectors[2][a];
        if (length(c) < length(best))
          best = c;
      }
  return best;
}
} // namespace

TEST(PeriodicBox, UnsetBoxIsIdentity)
{
  const mesolens::PeriodicBox box;
  EXPECT_FALSE(box.is_set());
  const auto d = box.minimum_image({ 100.0, -50.0, 3.0 });
  EXPECT_EQ(d[0], 100.0);
  EXPECT_EQ(d[1], -50.0);
}

TEST(PeriodicBox, OrthorhombicImage)
{
  mesolens::PeriodicBox box;
  box.vectors = { { { 10, 0, 0 }, { 0, 20, 0 }, { 0, 0, 30 } } };
  EXPECT_TRUE(box.is_orthorhombic());
  EXPECT_NEAR(box.volume(), 6000.0, 1e-9);
  const auto d = box.minimum_image({ 9.0, -19.0, 16.0 });
  EXPECT_NEAR(d[0], -1.0, 1e-12);
  EXPECT_NEAR(d[1], 1.0, 1e-12);
  EXPECT_NEAR(d[2], -14.0, 1e-12);
}

TEST(PeriodicBox, TriclinicImageIsShortest)
{
  // The vesicle's box: strongly skewed (alpha = beta ~ 59 degrees).
  const auto box = mesolens::PeriodicBox::from_cell(470.6, 473.1, 462.3, 59.2, 59.4, 90.0);
  EXPECT_FALSE(box.is_orthorhombic());
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-900.0, 900.0);
  for (int trial = 0; trial < 300; ++trial)
  {
    const std::array<double, 3> d{ coordinate(random), coordinate(random), coordinate(random) };
    EXPECT_NEAR(length(box.minimum_image(d)), length(brute_force_image(box, d)), 1e-6);
  }
}

TEST(PeriodicBox, SmallestHeightBoundsEveryBoxVectorCombination)
{
  mesolens::PeriodicBox slab;
  slab.vectors = { { { 10, 0, 0 }, { 0, 20, 0 }, { 0, 0, 30 } } };
  EXPECT_NEAR(slab.smallest_height(), 10.0, 1e-12);
  // Hexagonal: a and b at 120 degrees are 10 sin 60 apart across their faces.
  const auto hexagonal = mesolens::PeriodicBox::from_cell(10, 10, 20, 90, 90, 120);
  EXPECT_NEAR(hexagonal.smallest_height(), 10 * std::sqrt(3.0) / 2, 1e-9);
  EXPECT_EQ(mesolens::PeriodicBox{}.smallest_height(), 0.0);
  const auto skewed = mesolens::PeriodicBox::from_cell(40, 45, 50, 70, 80, 100);
  const double height = skewed.smallest_height();
  double shortest = 1e300;
  for (int i = -3; i <= 3; ++i)
    for (int j = -3; j <= 3; ++j)
      for (int k = -3; k <= 3; ++k)
      {
        if (i == 0 && j == 0 && k == 0)
        {
          continue;
        }
        double squared = 0;
        for (int c = 0; c < 3; ++c)
        {
          const double x =
            i * skewed.vectors[0][c] + j * skewed.vectors[1][c] + k * skewed.vectors[2][c];
          squared += x * x;
        }
        shortest = std::min(shortest, std::sqrt(squared));
      }
  EXPECT_GE(shortest, height);
  EXPECT_LT(height, 40.0);
}

TEST(PeriodicBox, FromCellHexagonal)
{
  const auto box = mesolens::PeriodicBox::from_cell(10, 10, 20, 90, 90, 120);
  EXPECT_NEAR(box.vectors[1][0], -5.0, 1e-12);
  EXPECT_NEAR(box.vectors[1][1], 10 * std::sqrt(3.0) / 2, 1e-12);
  EXPECT_NEAR(box.vectors[2][2], 20.0, 1e-12);
  EXPECT_NEAR(box.volume(), 10 * 10 * std::sqrt(3.0) / 2 * 20, 1e-9);
}
