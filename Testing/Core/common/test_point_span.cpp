// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/common/point_span.h"

#include <gtest/gtest.h>

#include <array>
#include <type_traits>
#include <vector>

using mesolens::PointSpan;

TEST(PointSpan, ViewsFlatArraysPointArraysAndPointers)
{
  const std::vector<double> flat = { 1, 2, 3, 4, 5, 6 };
  const PointSpan<const double> from_flat = flat;
  ASSERT_EQ(from_flat.size(), 2u);
  EXPECT_EQ(from_flat.value_count(), 6u);
  EXPECT_EQ(from_flat.data(), flat.data());
  EXPECT_EQ(from_flat[1][2], 6.0);
  EXPECT_EQ(from_flat.point(1), (std::array<double, 3>{ 4, 5, 6 }));

  const std::vector<std::array<double, 3>> points = { { 1, 2, 3 }, { 4, 5, 6 }, { 7, 8, 9 } };
  const PointSpan<const double> from_points = points;
  ASSERT_EQ(from_points.size(), 3u);
  EXPECT_EQ(from_points[2][0], 7.0);
  EXPECT_EQ(from_points.subspan(1, 2).point(0), (std::array<double, 3>{ 4, 5, 6 }));

  const float xyz[6] = { 1, 2, 3, 4, 5, 6 };
  const PointSpan<const float> from_pointer(xyz, 2);
  EXPECT_EQ(from_pointer.point(1), (std::array<double, 3>{ 4, 5, 6 }));

  // No points: empty, and no pointer even when one was given.
  const PointSpan<const float> none(xyz, 0);
  EXPECT_TRUE(none.empty());
  EXPECT_EQ(none.data(), nullptr);
  EXPECT_TRUE(PointSpan<const double>(std::vector<std::array<double, 3>>{}).empty());
}

TEST(PointSpan, WritesThroughAWritableSpanAndReadsItConst)
{
  std::vector<float> flat = { 0, 0, 0, 0, 0, 0 };
  const PointSpan<float> writable = flat;
  writable[1][1] = 5.0f;
  EXPECT_EQ(flat[4], 5.0f);
  const PointSpan<const float> readable = writable;
  EXPECT_EQ(readable[1][1], 5.0f);
  // A read-only array gives no writable span, and a writable span is not made from doubles.
  static_assert(!std::is_convertible<const std::vector<float>&, PointSpan<float>>::value, "");
  static_assert(!std::is_convertible<std::vector<double>&, PointSpan<float>>::value, "");
  static_assert(!std::is_convertible<PointSpan<const float>, PointSpan<float>>::value, "");
}

TEST(PointSpan, RefusesAFlatArrayOfPartialPoints)
{
  const std::vector<double> five = { 1, 2, 3, 4, 5 };
  EXPECT_THROW(PointSpan<const double>{ five }, mesolens::InvalidInput);
}
