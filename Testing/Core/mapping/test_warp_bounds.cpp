// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/mapping/membrane_mapping.h"
#include "mesolens/mapping/polynomial_warp.h"
#include "mesolens/mapping/warp_bounds.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>
#include <vector>

namespace {
/// A slanted periodic cell, as a triclinic MD box gives.
mesolens::MembranePatch slanted_patch()
{
  mesolens::MembranePatch patch;
  patch.origin = { -3.0, 2.0 };
  patch.a = { 60.0, 4.0 };
  patch.b = { 10.0, 55.0 };
  patch.centre_height = 1.5;
  return patch;
}

/// A float-exact box: what atoms stored as floats span.
mesolens::Box float_box(std::mt19937& random, std::uniform_real_distribution<float>& coordinate)
{
  mesolens::Box box{};
  for (int d = 0; d < 3; ++d)
  {
    const float u = coordinate(random);
    const float v = coordinate(random);
    box[std::size_t(d)] = std::min(u, v);
    box[std::size_t(d) + 3] = std::max(u, v);
  }
  return box;
}

bool inside(const mesolens::Box& box, const std::array<double, 3>& x, double tolerance)
{
  for (std::size_t d = 0; d < 3; ++d)
  {
    if (x[d] < box[d] - tolerance || x[d] > box[d + 3] + tolerance)
    {
      return false;
    }
  }
  return true;
}
} // namespace

TEST(WarpBounds, HoldEveryWarpedPointOfTheBox)
{
  const auto patch = slanted_patch();
  const double thickness = 25;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coefficient(-2.0, 2.0);
  // Boxes inside the cell and beyond it (the tile's pieces are extrapolated there).
  std::uniform_real_distribution<float> coordinate(-40.0f, 100.0f);
  std::uniform_real_distribution<float> along(0.0f, 1.0f);
  for (const int splits : { 1, 2, 4 })
  {
    std::vector<double> coefficients(3 * mesolens::quadratic_terms * std::size_t(splits * splits));
    for (int trial = 0; trial < 200; ++trial)
    {
      for (double& c : coefficients)
      {
        c = coefficient(random);
      }
      const mesolens::Box box = float_box(random, coordinate);
      const mesolens::Box bounds =
        mesolens::warped_box(patch, thickness, splits, coefficients.data(), box);
      for (int sample = 0; sample < 200; ++sample)
      {
        const float point[3] = {
          float(box[0] + along(random) * (box[3] - box[0])),
          float(box[1] + along(random) * (box[4] - box[1])),
          float(box[2] + along(random) * (box[5] - box[2])),
        };
        // Corners too: the extremes of a warp of degree 1 lie there.
        const float corner[3] = { float(box[(sample & 1) ? 3 : 0]),
                                  float(box[(sample & 2) ? 4 : 1]),
                                  float(box[(sample & 4) ? 5 : 2]) };
        for (const float* p : { point, corner })
        {
          const auto x =
            mesolens::evaluate_tile_polynomial(patch, thickness, splits, coefficients.data(), p);
          ASSERT_TRUE(inside(bounds, x, 1e-9))
            << "splits " << splits << ", trial " << trial << ": (" << x[0] << ", " << x[1] << ", "
            << x[2] << ") outside [" << bounds[0] << ", " << bounds[3] << "] x [" << bounds[1]
            << ", " << bounds[4] << "] x [" << bounds[2] << ", " << bounds[5] << "]";
        }
      }
    }
  }
}

TEST(WarpBounds, ExactForAWarpOfDegreeOne)
{
  // x = 2 + 3 s - t, y = s + 4 h, z = -2 t + h: the box's corners give the true extent.
  const auto patch = slanted_patch();
  std::array<double, 30> warp{};
  warp[0] = 2, warp[1] = 3, warp[2] = -1;
  warp[10 + 1] = 1, warp[10 + 3] = 4;
  warp[20 + 2] = -2, warp[20 + 3] = 1;
  const mesolens::Box box{ 5, 10, -10, 30, 40, 12 };
  const mesolens::Box bounds = mesolens::warped_box(patch, 25, 1, warp.data(), box);
  mesolens::Box corners{ 1e300, 1e300, 1e300, -1e300, -1e300, -1e300 };
  for (int c = 0; c < 8; ++c)
  {
    const float p[3] = { float(box[(c & 1) ? 3 : 0]), float(box[(c & 2) ? 4 : 1]),
                         float(box[(c & 4) ? 5 : 2]) };
    const auto x = mesolens::evaluate_tile_polynomial(patch, 25, 1, warp.data(), p);
    for (std::size_t d = 0; d < 3; ++d)
    {
      corners[d] = std::min(corners[d], x[d]);
      corners[d + 3] = std::max(corners[d + 3], x[d]);
    }
  }
  for (std::size_t k = 0; k < 6; ++k)
  {
    EXPECT_NEAR(bounds[k], corners[k], 1e-9) << k;
  }
}

TEST(WarpBounds, ABulgeInsideTheBoxIsHeld)
{
  // x = 1 - s²: largest at s = 0, in the box's middle, not at its corners (which give 0).
  mesolens::MembranePatch patch;
  patch.a = { 2, 0 };
  patch.b = { 0, 2 };
  std::array<double, 30> warp{};
  warp[0] = 1;
  warp[4] = -1;
  const mesolens::Box box{ 0, 0, 0, 2, 2, 0 }; // s and t over [-1, 1]
  const mesolens::Box bounds = mesolens::warped_box(patch, 1, 1, warp.data(), box);
  EXPECT_GE(bounds[3], 1.0);
  EXPECT_LE(bounds[0], 0.0);
}
