// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/render/depth_pyramid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace {
/// Row-major orthographic projection of x, y in [-10, 10] and view depth [1, 11] looking down
/// -z from the origin: window depth = (-z - 1) / 10.
std::array<double, 16> orthographic()
{
  return { 0.1, 0, 0, 0, 0, 0.1, 0, 0, 0, 0, -0.2, -1.2, 0, 0, 0, 1 };
}

/// A camera whose eye space is the model space, with `projection`.
mesolens::ViewTransform view_of(const std::array<double, 16>& projection)
{
  mesolens::ViewTransform view{};
  const double identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  std::copy(identity, identity + 16, view.model_to_view);
  std::copy(projection.begin(), projection.end(), view.view_to_clip);
  view.Complete();
  return view;
}

/// Row-major perspective projection (as VTK's: w = -z), vertical field of view 30 degrees,
/// aspect 2, near 1, far 100, with a window centre shifted by 0.1 in x.
std::array<double, 16> perspective()
{
  const double f = 1.0 / std::tan(15.0 * 3.14159265358979 / 180.0);
  const double n = 1;
  const double far = 100;
  return { f / 2, 0, 0.1, 0, 0, f, 0, 0, 0, 0, -(far + n) / (far - n), -2 * far * n / (far - n),
           0,     0, -1,  0 };
}

/// The window rectangle and nearest depth of many points on the sphere, projected one by one.
mesolens::ScreenFootprint sampled_footprint(const double centre[3], double radius,
                                            const std::array<double, 16>& m, int width, int height)
{
  mesolens::ScreenFootprint f{ 1e300, 1e300, -1e300, -1e300, 1e300 };
  for (int i = 0; i <= 200; ++i)
  {
    const double polar = 3.14159265358979 * i / 200;
    for (int j = 0; j < 400; ++j)
    {
      const double azimuth = 2 * 3.14159265358979 * j / 400;
      const double p[3] = { centre[0] + radius * std::sin(polar) * std::cos(azimuth),
                            centre[1] + radius * std::sin(polar) * std::sin(azimuth),
                            centre[2] + radius * std::cos(polar) };
      double clip[4];
      for (int r = 0; r < 4; ++r)
      {
        clip[r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
      }
      const double x = (clip[0] / clip[3] + 1) * 0.5 * width;
      const double y = (clip[1] / clip[3] + 1) * 0.5 * height;
      f.x0 = std::min(f.x0, x);
      f.x1 = std::max(f.x1, x);
      f.y0 = std::min(f.y0, y);
      f.y1 = std::max(f.y1, y);
      f.depth = std::min(f.depth, (clip[2] / clip[3] + 1) * 0.5);
    }
  }
  return f;
}
} // namespace

TEST(DepthPyramid, SphereFootprintIsTheOutlineAndTheNearestDepth)
{
  for (const auto& projection : { orthographic(), perspective() })
  {
    const auto view = view_of(projection);
    for (const auto& sphere : std::vector<std::array<double, 4>>{
           { 0, 0, -5, 1 }, { 3, -2, -6, 0.7 }, { -4, 3, -9, 2 }, { 1.5, 1, -3, 0.4 } })
    {
      mesolens::ScreenFootprint exact;
      ASSERT_TRUE(mesolens::sphere_footprint(sphere.data(), sphere[3], view, 300, 150, exact));
      const auto sampled = sampled_footprint(sphere.data(), sphere[3], projection, 300, 150);
      // The outline contains every sampled point and is no larger than the samples' spacing.
      EXPECT_LE(exact.x0, sampled.x0 + 1e-9);
      EXPECT_GE(exact.x1, sampled.x1 - 1e-9);
      EXPECT_LE(exact.y0, sampled.y0 + 1e-9);
      EXPECT_GE(exact.y1, sampled.y1 - 1e-9);
      EXPECT_NEAR(exact.x0, sampled.x0, 0.05 * (sampled.x1 - sampled.x0));
      EXPECT_NEAR(exact.x1, sampled.x1, 0.05 * (sampled.x1 - sampled.x0));
      EXPECT_NEAR(exact.y1, sampled.y1, 0.05 * (sampled.y1 - sampled.y0));
      EXPECT_LE(exact.depth, sampled.depth + 1e-12);
      EXPECT_NEAR(exact.depth, sampled.depth, 1e-6);
    }
    // Reaching the near plane: no footprint.
    const double close[3] = { 0, 0, -1.2 };
    mesolens::ScreenFootprint unused;
    EXPECT_FALSE(mesolens::sphere_footprint(close, 0.5, view, 300, 150, unused));
  }
}

TEST(DepthPyramid, LevelsHoldTheFarthestDepth)
{
  // 5 x 3 image, all at 0.2 but one far pixel (4, 2) at 0.9.
  std::vector<float> depth(15, 0.2f);
  depth[2 * 5 + 4] = 0.9f;
  mesolens::DepthPyramid pyramid;
  pyramid.Build(depth.data(), 5, 3);
  EXPECT_EQ(pyramid.Width(), 5);
  // A footprint over pixel (0, 0) only, behind 0.2: hidden; in front: visible.
  EXPECT_TRUE(pyramid.Hidden({ 0.2, 0.2, 0.8, 0.8, 0.3 }));
  EXPECT_FALSE(pyramid.Hidden({ 0.2, 0.2, 0.8, 0.8, 0.1 }));
  // Over the whole image: the far pixel keeps it visible up to 0.9.
  EXPECT_FALSE(pyramid.Hidden({ 0.0, 0.0, 5.0, 3.0, 0.5 }));
  EXPECT_TRUE(pyramid.Hidden({ 0.0, 0.0, 5.0, 3.0, 0.95 }));
  // Near the far pixel but not over it (pixels 0..2 of every row): hidden at 0.5.
  EXPECT_TRUE(pyramid.Hidden({ 0.1, 0.1, 2.9, 2.9, 0.5 }));
  // Over the far pixel's centre (4.5, 2.5): visible; over its edge only: hidden (the pixel gets
  // no fragment).
  EXPECT_FALSE(pyramid.Hidden({ 3.5, 2.1, 4.6, 2.9, 0.5 }));
  EXPECT_TRUE(pyramid.Hidden({ 3.5, 2.1, 4.2, 2.9, 0.5 }));
  // No pixel centre at all: nothing drawn, hidden even in front of everything.
  EXPECT_TRUE(pyramid.Hidden({ 1.6, 1.6, 2.4, 2.4, 0.0 }));
  // Partly outside the image: its inside part decides; entirely outside: hidden.
  EXPECT_TRUE(pyramid.Hidden({ -0.5, 0.2, 0.8, 0.8, 0.3 }));
  EXPECT_FALSE(pyramid.Hidden({ 4.2, 2.2, 5.5, 3.5, 0.5 }));
  EXPECT_TRUE(pyramid.Hidden({ -2.5, 0.2, -0.8, 0.8, 0.01 }));
  EXPECT_TRUE(pyramid.Hidden({ 1.0, 3.5, 2.0, 4.0, 0.01 }));
  // No image: nothing is hidden.
  mesolens::DepthPyramid empty;
  empty.Build(nullptr, 0, 0);
  EXPECT_FALSE(empty.Hidden({ 0, 0, 1, 1, 1 }));
}

TEST(DepthPyramid, SphereHiddenLooksOnlyAtThePixelsItCovers)
{
  // A wall at depth 0.2 with one far pixel (12, 12); a sphere of radius 2.5 pixels centred on
  // pixel (10, 10) behind the wall. The far pixel is inside the outline's rectangle but its
  // centre (12.5, 12.5) is 2.83 pixels from the sphere's centre: outside its outline.
  std::vector<float> depth(400, 0.2f);
  depth[12 * 20 + 12] = 1.0f;
  mesolens::DepthPyramid pyramid;
  pyramid.Build(depth.data(), 20, 20);
  const auto projection = orthographic();
  const auto view = view_of(projection);
  const double centre[3] = { 0.5, 0.5, -8.0 }; // pixel (10.5, 10.5), nearest depth > 0.45
  mesolens::ScreenFootprint footprint;
  mesolens::EyeSphere eye;
  ASSERT_TRUE(mesolens::sphere_footprint(centre, 2.5, view, 20, 20, footprint, &eye));
  EXPECT_FALSE(pyramid.Hidden(footprint));
  EXPECT_TRUE(pyramid.SphereHidden(footprint, eye, view.view_to_clip));
  // Larger, the sphere covers the far pixel's centre and shows there.
  ASSERT_TRUE(mesolens::sphere_footprint(centre, 3.0, view, 20, 20, footprint, &eye));
  EXPECT_FALSE(pyramid.SphereHidden(footprint, eye, view.view_to_clip));
  // In front of the wall: visible; in perspective too.
  const double front[3] = { 0.5, 0.5, -2.0 };
  ASSERT_TRUE(mesolens::sphere_footprint(front, 0.5, view, 20, 20, footprint, &eye));
  EXPECT_FALSE(pyramid.SphereHidden(footprint, eye, view.view_to_clip));
  const auto seen = view_of(perspective());
  const double ahead[3] = { 0.0, 0.0, -1.15 }; // the wall is 1.25 from the eye
  ASSERT_TRUE(mesolens::sphere_footprint(ahead, 0.05, seen, 20, 20, footprint, &eye));
  EXPECT_FALSE(pyramid.SphereHidden(footprint, eye, seen.view_to_clip)); // depth < 0.2
  const double behind[3] = { 0.0, 0.0, -30.0 };
  ASSERT_TRUE(mesolens::sphere_footprint(behind, 1.0, seen, 20, 20, footprint, &eye));
  EXPECT_TRUE(pyramid.SphereHidden(footprint, eye, seen.view_to_clip));
}

TEST(DepthPyramid, BoxFootprintInAnOrthographicView)
{
  const auto m = orthographic();
  const double low[3] = { -5, -5, -4 };
  const double high[3] = { 0, 5, -2 };
  mesolens::ScreenFootprint footprint;
  ASSERT_TRUE(mesolens::box_footprint(low, high, m.data(), 200, 100, footprint));
  EXPECT_NEAR(footprint.x0, 50.0, 1e-9);
  EXPECT_NEAR(footprint.x1, 100.0, 1e-9);
  EXPECT_NEAR(footprint.y0, 25.0, 1e-9);
  EXPECT_NEAR(footprint.y1, 75.0, 1e-9);
  EXPECT_NEAR(footprint.depth, 0.1, 1e-9); // z = -2: 1 past the near plane of 10
  // Across the near plane (z > -1): no footprint.
  const double near_high[3] = { 0, 5, -0.5 };
  EXPECT_FALSE(mesolens::box_footprint(low, near_high, m.data(), 200, 100, footprint));
}

TEST(DepthPyramid, AtomsBehindAWallAreHiddenOthersStay)
{
  // A wall at depth 0.5 (z = -6) over the left half of a 20 x 20 image, far depth elsewhere.
  std::vector<float> depth(400, 1.0f);
  for (int j = 0; j < 20; ++j)
  {
    for (int i = 0; i < 10; ++i)
    {
      depth[std::size_t(20 * j + i)] = 0.5f;
    }
  }
  mesolens::DepthPyramid pyramid;
  pyramid.Build(depth.data(), 20, 20);
  const auto m = orthographic();
  const auto view = view_of(m);
  // Atoms (radius 1.2): behind the wall, in front of it, to the right, and one that was drawn
  // first and is still visible.
  const std::vector<float> xyz = { -5, 0, -8, -5, 0, -3, 5, 0, -8, 5, 5, -8 };
  const std::vector<std::uint8_t> elements = { 1, 1, 1, 1 };
  const float radii[2] = { 1.2f, 1.2f }; // 2.4 pixels across: over some pixel centres
  mesolens::AtomCells cells;
  cells.atom_of_slot = { 0, 1, 2, 3 };
  cells.cell_start = { 0, 2, 4 }; // two cells of two atoms
  std::vector<float> slot_xyz(12);
  std::vector<float> boxes;
  mesolens::gather_cell_positions(xyz, cells, slot_xyz, boxes);
  const auto in_view = mesolens::cells_in_view(boxes, 1.2, m.data());
  ASSERT_EQ(in_view.size(), 2u);
  std::vector<std::uint8_t> flags = { 0, 0, 0, mesolens::SEEN };
  const auto result = mesolens::test_atom_visibility(pyramid, view, slot_xyz, elements.data(), 1,
                                                     radii, cells, boxes, in_view, 1.2, flags);
  EXPECT_EQ(flags[0], 0);
  EXPECT_EQ(flags[1], mesolens::SEEN | mesolens::NEWLY_SEEN);
  EXPECT_EQ(flags[2], mesolens::SEEN | mesolens::NEWLY_SEEN);
  EXPECT_EQ(flags[3], mesolens::SEEN); // drawn first, so not again
  EXPECT_EQ(result.seen, (std::vector<std::uint8_t>{ 1, 1 }));
  EXPECT_EQ(result.newly_seen, (std::vector<std::uint8_t>{ 1, 1 }));
  EXPECT_EQ(result.drawn_first, 1u);
  EXPECT_EQ(result.drawn_after, 2u);

  // A whole cell behind the wall: hidden by its box, its atoms cleared.
  const std::vector<float> hidden_xyz = { -6, 0, -8, -4, 1, -9, 5, 0, -8, 5, 5, -8 };
  mesolens::gather_cell_positions(hidden_xyz, cells, slot_xyz, boxes);
  flags = { mesolens::SEEN, mesolens::SEEN, 0, 0 };
  const auto behind =
    mesolens::test_atom_visibility(pyramid, view, slot_xyz, elements.data(), 1, radii, cells, boxes,
                                   mesolens::cells_in_view(boxes, 1.2, m.data()), 1.2, flags);
  EXPECT_EQ(flags[0], 0);
  EXPECT_EQ(flags[1], 0);
  EXPECT_EQ(behind.seen[0], 0);
  // A cell out of view loses its flags.
  flags = { mesolens::SEEN, mesolens::SEEN, mesolens::SEEN, mesolens::SEEN };
  std::vector<mesolens::CellInView> only_first = { { 0, 0.5, false } };
  mesolens::test_atom_visibility(pyramid, view, slot_xyz, elements.data(), 1, radii, cells, boxes,
                                 only_first, 1.2, flags);
  EXPECT_EQ(flags[2], 0);
  EXPECT_EQ(flags[3], 0);
}
