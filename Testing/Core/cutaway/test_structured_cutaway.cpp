// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/common/errors.h"
#include "mesolens/cutaway/structured_cutaway.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>

namespace {
using mesolens::CutawayParams;
using mesolens::CutRegion;

/// The regular icosahedron (circumradius ~1.9), triangles oriented outwards.
mesolens::TriangleMesh icosahedron()
{
  const double phi = (1 + std::sqrt(5.0)) / 2;
  mesolens::TriangleMesh mesh;
  for (int i = 0; i < 4; ++i)
  {
    const double a = (i & 1) ? -1 : 1;
    const double b = (i & 2) ? -phi : phi;
    mesh.points.insert(mesh.points.end(), { 0, a, b, a, b, 0, b, 0, a });
  }
  const std::size_t n = mesh.vertex_count();
  auto distance = [&](std::size_t i, std::size_t j) {
    const auto p = mesh.point(std::int64_t(i));
    const auto q = mesh.point(std::int64_t(j));
    return std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]);
  };
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      for (std::size_t k = j + 1; k < n; ++k)
        if (std::abs(distance(i, j) - 2) < 1e-9 && std::abs(distance(j, k) - 2) < 1e-9 &&
            std::abs(distance(i, k) - 2) < 1e-9)
        {
          const auto p = mesh.point(std::int64_t(i));
          const auto q = mesh.point(std::int64_t(j));
          const auto r = mesh.point(std::int64_t(k));
          const double u[3] = { q[0] - p[0], q[1] - p[1], q[2] - p[2] };
          const double v[3] = { r[0] - p[0], r[1] - p[1], r[2] - p[2] };
          const double normal[3] = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                                     u[0] * v[1] - u[1] * v[0] };
          const bool outward = normal[0] * p[0] + normal[1] * p[1] + normal[2] * p[2] > 0;
          mesh.triangles.insert(
            mesh.triangles.end(),
            { std::int64_t(i), std::int64_t(outward ? j : k), std::int64_t(outward ? k : j) });
        }
  return mesh;
}

/// Molecules on a sphere of radius 2.2 around the icosahedron: first the 20 above triangle
/// centres, then the 30 above edge midpoints.
std::vector<double> molecules_over(const mesolens::TriangleMesh& mesh)
{
  std::vector<double> centres;
  auto push = [&](double x, double y, double z) {
    const double length = std::sqrt(x * x + y * y + z * z);
    centres.insert(centres.end(), { 2.2 * x / length, 2.2 * y / length, 2.2 * z / length });
  };
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
  {
    double c[3] = { 0, 0, 0 };
    for (int v = 0; v < 3; ++v)
    {
      const auto p = mesh.point(mesh.triangles[3 * t + v]);
      for (int d = 0; d < 3; ++d)
        c[d] += p[d] / 3;
    }
    push(c[0], c[1], c[2]);
  }
  std::vector<std::pair<std::int64_t, std::int64_t>> edges;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    for (int e = 0; e < 3; ++e)
    {
      const auto a = mesh.triangles[3 * t + e];
      const auto b = mesh.triangles[3 * t + (e + 1) % 3];
      if (a < b)
        edges.emplace_back(a, b);
    }
  for (const auto& [a, b] : edges)
  {
    const auto p = mesh.point(a);
    const auto q = mesh.point(b);
    push((p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2);
  }
  return centres;
}

CutRegion everything()
{
  CutRegion cut;
  cut.balls.push_back({ { 0, 0, 0 }, 10.0 });
  return cut;
}

std::size_t hidden_count(const std::vector<std::uint8_t>& visible)
{
  return std::count(visible.begin(), visible.end(), 0);
}
} // namespace

TEST(StructuredCutaway, TunableSigmoid)
{
  for (double k : { -0.9, -0.5, 0.0, 0.5, 0.9 })
  {
    EXPECT_DOUBLE_EQ(mesolens::tunable_sigmoid(-1, k), -1);
    EXPECT_DOUBLE_EQ(mesolens::tunable_sigmoid(0, k), 0);
    EXPECT_DOUBLE_EQ(mesolens::tunable_sigmoid(1, k), 1);
    double last = -1;
    for (double n = -1; n <= 1; n += 0.05)
    {
      const double f = mesolens::tunable_sigmoid(n, k);
      EXPECT_GE(f, last - 1e-12);                               // monotonic
      EXPECT_NEAR(f, -mesolens::tunable_sigmoid(-n, k), 1e-12); // odd
      last = f;
    }
  }
  EXPECT_DOUBLE_EQ(mesolens::tunable_sigmoid(0.3, 0.0), 0.3);
  EXPECT_GT(mesolens::tunable_sigmoid(0.3, -0.8), 0.3); // towards a step
  EXPECT_LT(mesolens::tunable_sigmoid(0.3, 0.8), 0.3);
  EXPECT_THROW(mesolens::tunable_sigmoid(0.3, 1.0), mesolens::InvalidInput);
  EXPECT_THROW(mesolens::tunable_sigmoid(0.3, -1.0), mesolens::InvalidInput);
}

TEST(StructuredCutaway, CentresGoFirstAndEdgesLast)
{
  const auto mesh = icosahedron();
  ASSERT_EQ(mesh.triangle_count(), 20u);
  const mesolens::StructuredCutaway cutaway(mesh, molecules_over(mesh));
  ASSERT_EQ(cutaway.molecule_count(), 50u);
  for (std::size_t m = 0; m < 20; ++m)
    EXPECT_NEAR(cutaway.minimal_barycentric()[m], 1.0 / 3, 1e-9);
  for (std::size_t m = 20; m < 50; ++m)
    EXPECT_NEAR(cutaway.minimal_barycentric()[m], 0.0, 1e-9);
  const auto priority = cutaway.priorities(0.0);
  EXPECT_NEAR(priority[0], 1.0, 1e-9);
  EXPECT_NEAR(priority[20], 0.0, 1e-9);

  CutawayParams settings;
  settings.fraction_hidden = 0.4; // 20 of 50: exactly the triangle centres
  auto visible = cutaway.visibility(everything(), settings);
  for (std::size_t m = 0; m < 50; ++m)
    EXPECT_EQ(visible[m], m < 20 ? 0 : 1) << m;
  settings.fraction_hidden = 0.5; // then 5 of the edge molecules
  visible = cutaway.visibility(everything(), settings);
  EXPECT_EQ(hidden_count(visible), 25u);
  for (std::size_t m = 0; m < 20; ++m)
    EXPECT_EQ(visible[m], 0);
  // Inverted: the edges first.
  settings.fraction_hidden = 0.6;
  settings.inverted = true;
  visible = cutaway.visibility(everything(), settings);
  for (std::size_t m = 0; m < 50; ++m)
    EXPECT_EQ(visible[m], m < 20 ? 1 : 0) << m;
}

TEST(StructuredCutaway, ExactFractionInsideNothingOutsideNested)
{
  const auto mesh = icosahedron();
  const auto centres = molecules_over(mesh);
  const mesolens::StructuredCutaway cutaway(mesh, centres);
  CutRegion upper;
  upper.planes.push_back({ { 0, 0, 0.1 }, { 0, 0, 1 } });
  std::size_t inside = 0;
  for (std::size_t m = 0; m < 50; ++m)
    inside += upper.contains({ centres[3 * m], centres[3 * m + 1], centres[3 * m + 2] });
  ASSERT_GT(inside, 10u);
  ASSERT_LT(inside, 40u);
  for (bool random : { false, true })
  {
    CutawayParams settings;
    settings.random = random;
    std::vector<std::uint8_t> previous(50, 1);
    for (double fraction : { 0.0, 0.2, 0.5, 0.8, 1.0 })
    {
      settings.fraction_hidden = fraction;
      const auto visible = cutaway.visibility(upper, settings);
      EXPECT_EQ(hidden_count(visible), std::size_t(std::llround(fraction * double(inside))));
      for (std::size_t m = 0; m < 50; ++m)
      {
        if (!upper.contains({ centres[3 * m], centres[3 * m + 1], centres[3 * m + 2] }))
          EXPECT_EQ(visible[m], 1) << "outside the cut";
        if (!previous[m])
          EXPECT_EQ(visible[m], 0) << "a larger fraction keeps what a smaller one hid";
      }
      previous = visible;
    }
  }
}

TEST(StructuredCutaway, AKeptOrderGivesTheSameMasksForEveryFraction)
{
  const auto mesh = icosahedron();
  const auto centres = molecules_over(mesh);
  std::vector<int> types(50, 0);
  std::fill(types.begin() + 30, types.end(), 4);
  const auto run_in_halves = [](std::size_t count, const mesolens::RangeKernel& kernel) {
    kernel(0, count / 2);
    kernel(count / 2, count);
  };
  const mesolens::StructuredCutaway cutaway(mesh, centres, types, run_in_halves);
  EXPECT_EQ(cutaway.minimal_barycentric(),
            mesolens::StructuredCutaway(mesh, centres, types).minimal_barycentric());
  CutRegion upper;
  upper.planes.push_back({ { 0, 0, -0.2 }, { 0, 0, 1 } });
  const auto inside = [&](const std::array<double, 3>& p) { return upper.contains(p); };
  for (bool inverted : { false, true })
  {
    CutawayParams settings;
    settings.inverted = inverted;
    settings.k = -0.4;
    const mesolens::RemovalOrder order = cutaway.removal_order(inside, settings);
    EXPECT_EQ(order.molecule_count, 50u);
    std::size_t in_cut = 0;
    for (std::size_t m = 0; m < 50; ++m)
      in_cut += upper.contains({ centres[3 * m], centres[3 * m + 1], centres[3 * m + 2] });
    EXPECT_EQ(order.in_cut(), in_cut);
    for (double fraction : { 0.0, 0.3, 0.7, 1.0 })
    {
      settings.fraction_hidden = fraction;
      settings.fraction_by_type[4] = 1.0 - fraction;
      EXPECT_EQ(cutaway.visibility(order, settings), cutaway.visibility(upper, settings));
    }
  }
  mesolens::RemovalOrder other;
  other.molecule_count = 49;
  EXPECT_THROW(cutaway.visibility(other, CutawayParams()), mesolens::InvalidInput);
}

TEST(StructuredCutaway, ProbabilisticOrderMakesKABlendOfStructuredAndRandom)
{
  // 40 molecules at random places on each triangle of the icosahedron.
  const auto mesh = icosahedron();
  std::mt19937 generator(5);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<double> centres;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    for (int i = 0; i < 40; ++i)
    {
      double a = uniform(generator);
      double b = uniform(generator);
      if (a + b > 1)
      {
        a = 1 - a;
        b = 1 - b;
      }
      const double w[3] = { 1 - a - b, a, b };
      for (int d = 0; d < 3; ++d)
      {
        double value = 0;
        for (int k = 0; k < 3; ++k)
          value += w[k] * mesh.point(mesh.triangles[3 * t + k])[d];
        centres.push_back(1.02 * value);
      }
    }
  const mesolens::StructuredCutaway cutaway(mesh, centres);
  const auto& x = cutaway.minimal_barycentric();
  // How far apart the hidden and the visible molecules' mean x are, at half hidden.
  auto separation = [&](const CutawayParams& settings) {
    const auto visible = cutaway.visibility(everything(), settings);
    EXPECT_EQ(hidden_count(visible), x.size() / 2);
    double hidden_sum = 0, visible_sum = 0;
    for (std::size_t m = 0; m < x.size(); ++m)
      (visible[m] ? visible_sum : hidden_sum) += x[m];
    return (hidden_sum - visible_sum) / double(x.size() / 2);
  };
  CutawayParams settings;
  settings.fraction_hidden = 0.5;
  const double strict = separation(settings);
  settings.k = 0.9;
  EXPECT_EQ(separation(settings), strict); // the strict order ignores k
  settings.probabilistic = true;
  const double nearly_random = separation(settings);
  settings.k = 0.0;
  const double linear = separation(settings);
  settings.k = -0.9;
  const double two_classes = separation(settings);
  settings.random = true;
  const double random = separation(settings);
  EXPECT_GT(strict, 0.12); // x lies in [0, 1/3]
  EXPECT_LT(std::abs(random), 0.02);
  EXPECT_LT(std::abs(nearly_random), 0.03);
  EXPECT_GT(linear, nearly_random + 0.02);
  EXPECT_GT(two_classes, linear);
  EXPECT_LT(two_classes, strict);
  // Inverted and probabilistic: edges first.
  settings.random = false;
  settings.inverted = true;
  EXPECT_LT(separation(settings), -0.03);
  // Molecules on an edge (probability 0) never go before those with a chance.
  const auto edges = molecules_over(mesh);
  const mesolens::StructuredCutaway over(mesh, edges);
  settings = CutawayParams();
  settings.probabilistic = true;
  settings.fraction_hidden = 0.4; // the 20 centre molecules of 50
  const auto visible = over.visibility(everything(), settings);
  for (std::size_t m = 0; m < 50; ++m)
    EXPECT_EQ(visible[m], m < 20 ? 0 : 1);
}

TEST(StructuredCutaway, SeedsTypesAndLaterFrames)
{
  const auto mesh = icosahedron();
  const auto centres = molecules_over(mesh);
  std::vector<int> types(50, 2);
  std::fill(types.begin(), types.begin() + 20, 1);
  const mesolens::StructuredCutaway cutaway(mesh, centres, types);
  CutawayParams settings;
  settings.random = true;
  settings.fraction_hidden = 0.5;
  const auto first = cutaway.visibility(everything(), settings);
  EXPECT_EQ(first, cutaway.visibility(everything(), settings)); // same seed, same mask
  settings.seed = 7;
  EXPECT_NE(first, cutaway.visibility(everything(), settings));
  // Per type: all of type 2 (the edge molecules), none of type 1.
  settings = CutawayParams();
  settings.fraction_hidden = 0.0;
  settings.fraction_by_type[2] = 1.0;
  const auto by_type = cutaway.visibility(everything(), settings);
  for (std::size_t m = 0; m < 50; ++m)
    EXPECT_EQ(by_type[m], m < 20 ? 1 : 0);
  // A later frame where every molecule has left the cut: nothing hidden.
  std::vector<double> moved = centres;
  for (std::size_t i = 0; i < moved.size(); i += 3)
    moved[i] += 100;
  settings.fraction_by_type.clear();
  settings.fraction_hidden = 1.0;
  EXPECT_EQ(hidden_count(cutaway.visibility(everything(), settings, moved)), 0u);
}

TEST(StructuredCutaway, BadInputs)
{
  const auto mesh = icosahedron();
  using Flat = std::vector<double>;
  EXPECT_THROW(mesolens::StructuredCutaway(mesh, Flat{}), mesolens::InvalidInput);
  EXPECT_THROW(mesolens::StructuredCutaway(mesh, Flat{ 1, 2 }), mesolens::InvalidInput);
  EXPECT_THROW(mesolens::StructuredCutaway(mesh, Flat{ 1, std::nan(""), 2 }),
               mesolens::InvalidInput);
  EXPECT_THROW(mesolens::StructuredCutaway(mesh, Flat{ 1, 2, 3 }, { 1, 2 }),
               mesolens::InvalidInput);
  EXPECT_THROW(mesolens::StructuredCutaway(mesolens::TriangleMesh(), Flat{ 1, 2, 3 }),
               mesolens::InvalidInput);
  const Flat centres = molecules_over(mesh);
  const mesolens::StructuredCutaway cutaway(mesh, centres);
  // Later centres of another number of molecules are refused.
  const Flat fewer(centres.begin(), centres.end() - 3);
  EXPECT_THROW(cutaway.visibility(everything(), mesolens::CutawayParams{}, fewer),
               mesolens::InvalidInput);
  CutawayParams settings;
  settings.k = 1.0;
  EXPECT_THROW(cutaway.visibility(everything(), settings), mesolens::InvalidInput);
  settings.k = 0;
  settings.fraction_hidden = 1.5;
  EXPECT_THROW(cutaway.visibility(everything(), settings), mesolens::InvalidInput);
  settings.fraction_hidden = std::nan("");
  EXPECT_THROW(cutaway.visibility(everything(), settings), mesolens::InvalidInput);
  settings.fraction_hidden = 0.5;
  settings.fraction_by_type[3] = -0.1;
  EXPECT_THROW(cutaway.visibility(everything(), settings), mesolens::InvalidInput);
  // An empty cut hides nothing.
  settings.fraction_by_type.clear();
  EXPECT_EQ(hidden_count(cutaway.visibility(CutRegion(), settings)), 0u);
}
