// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/mapping/temporal_subdivision.h"

#include "mesolens/common/errors.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <vector>

namespace {
/// Reference: the 4-point scheme run `levels` times over the whole sequence, with the reflected
/// linear extrapolation at both ends of every level.
std::vector<double> brute_force(std::vector<double> x, unsigned levels)
{
  for (unsigned level = 0; level < levels && x.size() > 1; ++level)
  {
    const long n = long(x.size());
    auto at = [&](long i) {
      if (i < 0)
      {
        return 2 * x[0] - x[1];
      }
      if (i >= n)
      {
        return 2 * x[std::size_t(n - 1)] - x[std::size_t(n - 2)];
      }
      return x[std::size_t(i)];
    };
    std::vector<double> refined;
    for (long i = 0; i < n; ++i)
    {
      refined.push_back(x[std::size_t(i)]);
      if (i + 1 < n)
      {
        refined.push_back((-at(i - 1) + 9 * at(i) + 9 * at(i + 1) - at(i + 2)) / 16);
      }
    }
    x = refined;
  }
  return x;
}

double evaluate(const mesolens::SubdivisionStencil& stencil, const std::vector<double>& keys)
{
  double sum = 0;
  for (std::size_t i = 0; i < stencil.key_frames.size(); ++i)
  {
    sum += stencil.weights[i] * keys[stencil.key_frames[i]];
  }
  return sum;
}

std::vector<double> sample(std::size_t count, const std::function<double(double)>& f)
{
  std::vector<double> values(count);
  for (std::size_t k = 0; k < count; ++k)
  {
    values[k] = f(double(k));
  }
  return values;
}
} // namespace

TEST(TemporalSubdivision, FrameCountsAndTimes)
{
  EXPECT_EQ(mesolens::refined_frame_count(1, 5), 1u);
  EXPECT_EQ(mesolens::refined_frame_count(2, 0), 2u);
  EXPECT_EQ(mesolens::refined_frame_count(5, 2), 17u);
  EXPECT_EQ(mesolens::refined_frame_count(5, 10), 4097u);
  const std::vector<double> times = mesolens::refined_times({ 0, 10, 40 }, 2);
  const std::vector<double> expected = { 0, 2.5, 5, 7.5, 10, 17.5, 25, 32.5, 40 };
  ASSERT_EQ(times.size(), expected.size());
  for (std::size_t j = 0; j < times.size(); ++j)
  {
    EXPECT_DOUBLE_EQ(times[j], expected[j]) << j;
  }
  EXPECT_EQ(mesolens::refined_times({ 7.0 }, 3), std::vector<double>{ 7.0 });
  // Latest frame not after the time, clamped.
  EXPECT_EQ(mesolens::frame_at_time(times, -1), 0u);
  EXPECT_EQ(mesolens::frame_at_time(times, 17.5), 5u);
  EXPECT_EQ(mesolens::frame_at_time(times, 17.49999999), 5u);
  EXPECT_EQ(mesolens::frame_at_time(times, 24.9), 5u);
  EXPECT_EQ(mesolens::frame_at_time(times, 1e9), 8u);
  EXPECT_EQ(mesolens::frame_at_time(times, std::nan("")), 0u);
}

TEST(TemporalSubdivision, KeyFramesAreExact)
{
  for (unsigned levels = 0; levels <= 6; ++levels)
  {
    for (std::size_t k = 0; k < 7; ++k)
    {
      const auto stencil = mesolens::subdivision_stencil(7, levels, k << levels);
      ASSERT_EQ(stencil.key_frames, std::vector<std::size_t>{ k });
      EXPECT_EQ(stencil.weights, std::vector<double>{ 1.0 });
      EXPECT_EQ(stencil.nearest_key_frame, k);
    }
  }
  // One key frame: every refined frame is that frame.
  const auto single = mesolens::subdivision_stencil(1, 4, 0);
  EXPECT_EQ(single.key_frames, std::vector<std::size_t>{ 0 });
}

TEST(TemporalSubdivision, MatchesTheSchemeRunOnTheWholeSequence)
{
  for (std::size_t keys : { 2u, 3u, 4u, 5u, 9u })
  {
    const std::vector<double> x = sample(keys, [](double t) { return std::sin(1.7 * t) + t; });
    for (unsigned levels = 0; levels <= 5; ++levels)
    {
      const std::vector<double> reference = brute_force(x, levels);
      ASSERT_EQ(reference.size(), mesolens::refined_frame_count(keys, levels));
      for (std::size_t j = 0; j < reference.size(); ++j)
      {
        const auto stencil = mesolens::subdivision_stencil(keys, levels, j);
        EXPECT_NEAR(evaluate(stencil, x), reference[j], 1e-12) << keys << " " << levels << " " << j;
      }
    }
  }
}

TEST(TemporalSubdivision, StencilShape)
{
  for (std::size_t keys : { 1u, 2u, 3u, 6u, 12u })
  {
    for (unsigned levels = 0; levels <= 8; ++levels)
    {
      const std::size_t count = mesolens::refined_frame_count(keys, levels);
      for (std::size_t j = 0; j < count; ++j)
      {
        const auto s = mesolens::subdivision_stencil(keys, levels, j);
        ASSERT_FALSE(s.key_frames.empty());
        EXPECT_LE(s.key_frames.size(), 6u); // the basis function has support (-3, 3)
        EXPECT_TRUE(std::is_sorted(s.key_frames.begin(), s.key_frames.end()));
        EXPECT_NEAR(std::accumulate(s.weights.begin(), s.weights.end(), 0.0), 1.0, 1e-14);
        const auto nearest =
          std::find(s.key_frames.begin(), s.key_frames.end(), s.nearest_key_frame);
        ASSERT_NE(nearest, s.key_frames.end());
        EXPECT_GT(s.weights[std::size_t(nearest - s.key_frames.begin())], 0.0);
        // Only nearby key frames contribute.
        const double t = double(j) / double(1u << levels);
        EXPECT_LT(std::abs(double(s.key_frames.front()) - t), 3.0);
        EXPECT_LT(std::abs(double(s.key_frames.back()) - t), 3.0);
      }
    }
  }
  // Large levels stay cheap and exact.
  const auto deep = mesolens::subdivision_stencil(100, 10, 50 * 1024 + 333);
  EXPECT_LE(deep.key_frames.size(), 6u);
}

TEST(TemporalSubdivision, LinearMotionExactEverywhere)
{
  const std::vector<double> x = sample(6, [](double t) { return 3.0 - 2.5 * t; });
  for (unsigned levels = 1; levels <= 4; ++levels)
  {
    const std::size_t count = mesolens::refined_frame_count(6, levels);
    for (std::size_t j = 0; j < count; ++j)
    {
      const double t = double(j) / double(1u << levels);
      EXPECT_NEAR(evaluate(mesolens::subdivision_stencil(6, levels, j), x), 3.0 - 2.5 * t, 1e-12);
    }
  }
  // Two key frames: linear interpolation.
  const auto half = mesolens::subdivision_stencil(2, 1, 1);
  ASSERT_EQ(half.weights.size(), 2u);
  EXPECT_EQ(half.weights[0], 0.5);
  EXPECT_EQ(half.weights[1], 0.5);
}

TEST(TemporalSubdivision, CubicMotionExactInTheInterior)
{
  auto cubic = [](double t) { return 1.5 - 0.7 * t + 0.3 * t * t - 0.05 * t * t * t; };
  const std::size_t keys = 10;
  const std::vector<double> x = sample(keys, cubic);
  std::size_t interior = 0;
  for (unsigned levels = 1; levels <= 5; ++levels)
  {
    const std::size_t count = mesolens::refined_frame_count(keys, levels);
    for (std::size_t j = 0; j < count; ++j)
    {
      const auto stencil = mesolens::subdivision_stencil(keys, levels, j);
      const double t = double(j) / double(1u << levels);
      // Frames whose stencil does not touch the end key frames (where the extrapolated values
      // fold in).
      if (stencil.key_frames.front() >= 1 && stencil.key_frames.back() + 2 <= keys)
      {
        EXPECT_NEAR(evaluate(stencil, x), cubic(t), 1e-9) << levels << " " << j;
        ++interior;
      }
    }
  }
  EXPECT_GT(interior, 100u);
  // The middle of the interval at the very start is not exact (extrapolation), as documented.
  const auto start = mesolens::subdivision_stencil(keys, 1, 1);
  EXPECT_GT(std::abs(evaluate(start, x) - cubic(0.5)), 1e-6);
}

TEST(TemporalSubdivision, CombineFrames)
{
  const std::vector<float> a = { 1, 2, 3, 4, 5, 6 };
  const std::vector<float> b = { 3, 2, 1, 0, -1, -2 };
  std::vector<float> out(6);
  mesolens::combine_frames({ a.data(), b.data() }, { 0.25, 0.75 }, 6, out.data());
  for (std::size_t v = 0; v < 6; ++v)
  {
    EXPECT_FLOAT_EQ(out[v], 0.25f * a[v] + 0.75f * b[v]);
  }
  mesolens::combine_frames({ a.data() }, { 1.0 }, 6, out.data());
  EXPECT_EQ(out, a);
  // A split parallel loop gives the same result.
  const mesolens::ParallelFor split = [](std::size_t count, const mesolens::RangeKernel& kernel) {
    for (std::size_t begin = 0; begin < count; begin += 4)
    {
      kernel(begin, std::min(count, begin + 4));
    }
  };
  std::vector<float> parallel(6);
  mesolens::combine_frames({ a.data(), b.data() }, { -0.5, 1.5 }, 6, parallel.data(), split);
  mesolens::combine_frames({ a.data(), b.data() }, { -0.5, 1.5 }, 6, out.data());
  EXPECT_EQ(parallel, out);
}

TEST(TemporalSubdivision, UnwrapToReference)
{
  mesolens::PeriodicBox box;
  box.vectors = { { { 10, 0, 0 }, { 0, 10, 0 }, { 0, 0, 10 } } };
  const std::vector<float> reference = { 9.5f, 5, 5, 1, 1, 1 };
  std::vector<float> moved = { 1.5f, 5, 5, 1.25f, 1, 9.75f }; // crossed +x, then -z
  mesolens::unwrap_to_reference(moved, reference, box);
  EXPECT_FLOAT_EQ(moved[0], 11.5f);
  EXPECT_FLOAT_EQ(moved[3], 1.25f);
  EXPECT_FLOAT_EQ(moved[5], -0.25f);
  // Whole molecules move together: a two-atom molecule straddling x = 10 in the reference
  // and wrapped differently in the next frame stays whole.
  const std::vector<float> pair_reference = { 9.5f, 5, 5, 10.5f, 5, 5, 2, 2, 2 };
  std::vector<float> pair = { 0.0f, 5, 5, 1.0f, 5, 5, 2.5f, 2, 2 }; // molecule 0 moved +0.5
  const std::vector<float> pair_frame = pair;
  const std::vector<int> ids = { 0, 0, 1 };
  const auto molecules = mesolens::group_molecules(ids.data(), 3);
  mesolens::unwrap_to_reference(pair, pair_reference, box, &molecules);
  EXPECT_FLOAT_EQ(pair[0], 10.0f);
  EXPECT_FLOAT_EQ(pair[3], 11.0f);
  EXPECT_FLOAT_EQ(pair[6], 2.5f);
  // Any ids, negative or far apart, group the same.
  const std::vector<int> sparse = { -7, -7, 2000000000 };
  const auto sparse_molecules = mesolens::group_molecules(sparse.data(), 3);
  std::vector<float> again = pair_frame;
  mesolens::unwrap_to_reference(again, pair_reference, box, &sparse_molecules);
  EXPECT_EQ(again, pair);
  // Molecules of another number of atoms are refused.
  const auto two = mesolens::group_molecules(ids.data(), 2);
  EXPECT_THROW(mesolens::unwrap_to_reference(again, pair_reference, box, &two),
               mesolens::InvalidInput);
  // Reference positions of another number of atoms are refused.
  EXPECT_THROW(mesolens::unwrap_to_reference(again, reference, box), mesolens::InvalidInput);
  // Unset box: no-op.
  std::vector<float> same = { 1.5f, 5, 5, 1.25f, 1, 9.75f };
  mesolens::unwrap_to_reference(same, reference, mesolens::PeriodicBox{});
  EXPECT_FLOAT_EQ(same[0], 1.5f);
}

TEST(TemporalSubdivision, BadInputsThrow)
{
  EXPECT_THROW(mesolens::refined_frame_count(0, 2), mesolens::InvalidInput);
  EXPECT_THROW(mesolens::refined_frame_count(5, 11), mesolens::InvalidInput);
  EXPECT_THROW(mesolens::subdivision_stencil(0, 2, 0), mesolens::InvalidInput);
  EXPECT_THROW(mesolens::subdivision_stencil(5, 11, 0), mesolens::InvalidInput);
  EXPECT_THROW(mesolens::subdivision_stencil(5, 2, 17), mesolens::InvalidInput);
  EXPECT_THROW(mesolens::subdivision_stencil(1, 2, 1), mesolens::InvalidInput);
  EXPECT_THROW(mesolens::refined_times({}, 2), mesolens::InvalidInput);
  EXPECT_THROW(mesolens::refined_times({ 0, 0 }, 2), mesolens::InvalidInput);
  EXPECT_THROW(mesolens::refined_times({ 0, std::nan("") }, 2), mesolens::InvalidInput);
  EXPECT_THROW(mesolens::frame_at_time({}, 0), mesolens::InvalidInput);
  const std::vector<float> a = { 1, 2, 3 };
  std::vector<float> out(3);
  EXPECT_THROW(mesolens::combine_frames({}, {}, 3, out.data()), mesolens::InvalidInput);
  EXPECT_THROW(mesolens::combine_frames({ a.data() }, { 0.5, 0.5 }, 3, out.data()),
               mesolens::InvalidInput);
  EXPECT_THROW(mesolens::combine_frames({ a.data() }, { 1.0 }, 3, nullptr), mesolens::InvalidInput);
}
