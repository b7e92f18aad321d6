// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/mapping/membrane_mapping.h"

#include "mesolens/common/errors.h"
#include "mesolens/mapping/geodesic_disk.h"
#include "mesolens/mapping/harmonic_parameterization.h"
#include "mesolens_test_meshes.h"
#include "mesolens_test_patch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace {
/// A chart of the geodesic disk of `radius` around a point of `surface`.
mesolens::SurfaceChart chart_of(const mesolens::TriangleMesh& surface, std::int64_t seed_triangle,
                                double radius, std::array<double, 2>* seed_uv)
{
  const mesolens::CellSurface solver(surface);
  mesolens::GeodesicDiskParams params;
  params.radius = radius;
  params.min_triangles = 0;
  const auto disk =
    mesolens::geodesic_disk(solver, mesolens_test::surface_point(surface, seed_triangle), params);
  const auto map = mesolens::harmonic_parameterization(disk.mesh, radius);
  mesolens::SurfaceChart chart(disk.mesh, map.uv);
  *seed_uv = chart.uv_of(disk.seed);
  return chart;
}

template<typename P, typename Q>
double distance(const P* p, const Q* q)
{
  return std::sqrt((double(p[0]) - q[0]) * (double(p[0]) - q[0]) +
                   (double(p[1]) - q[1]) * (double(p[1]) - q[1]) +
                   (double(p[2]) - q[2]) * (double(p[2]) - q[2]));
}
} // namespace

TEST(PolynomialWarp, FitReproducesQuadraticsExactly)
{
  // A sheared paraboloid shell: x(s, t, h) = (s + 0.1 h, t, 0.3 s^2 - 0.2 st + 0.5 t^2 + h).
  mesolens::QuadraticWarp expected{};
  expected[1] = 1;
  expected[3] = 0.1;
  expected[10 + 2] = 1;
  expected[20 + 4] = 0.3;
  expected[20 + 5] = -0.2;
  expected[20 + 7] = 0.5;
  expected[20 + 3] = 1;
  std::vector<std::array<double, 3>> parameters;
  std::vector<std::array<double, 3>> targets;
  for (int h = -1; h <= 1; ++h)
    for (int j = 0; j < 6; ++j)
      for (int i = 0; i < 6; ++i)
      {
        const double s = -1 + 0.4 * i, t = -1 + 0.4 * j;
        parameters.push_back({ s, t, double(h) });
        targets.push_back(mesolens::evaluate_quadratic(expected, s, t, h));
      }
  const auto fit = mesolens::fit_quadratic(parameters, targets);
  for (std::size_t k = 0; k < expected.size(); ++k)
  {
    EXPECT_NEAR(fit.warp[k], expected[k], 1e-12) << k;
  }
  EXPECT_LT(fit.max_residual, 1e-12);
  // Samples on one layer cannot determine the h terms.
  parameters.resize(36);
  targets.resize(36);
  EXPECT_THROW(mesolens::fit_quadratic(parameters, targets), mesolens::SolverFailure);
  EXPECT_THROW(mesolens::fit_quadratic({}, {}), mesolens::InvalidInput);
}

TEST(MembraneMapping, FlatSurfaceMethodsAgree)
{
  // A flat disk whose boundary is a regular polygon on its circle maps onto the uv disk of the
  // same radius by a rotation: the displacement map is then a rigid motion, the polynomial
  // reproduces it exactly and instancing moves every molecule the same way.
  const auto flat = mesolens_test::polar_disk(30, 120, 40.0);
  const auto map = mesolens::harmonic_parameterization(flat, 40.0);
  const mesolens::SurfaceChart chart(flat, map.uv);
  const std::array<double, 2> seed_uv{ 0, 0 };
  const auto patch = mesolens_test::synthetic_patch(30, 4.0f);
  mesolens::MappingParams params;
  params.tiles = 2;
  params.scale = 0.5;
  params.centre_uv = seed_uv;
  params.method = mesolens::MappingMethod::Displacement;
  const auto displaced = mesolens::map_membrane(chart, patch.view(), params);
  params.method = mesolens::MappingMethod::Polynomial;
  const auto polynomial = mesolens::map_membrane(chart, patch.view(), params);
  params.method = mesolens::MappingMethod::MoleculeInstancing;
  const auto instanced = mesolens::map_membrane(chart, patch.view(), params);
  ASSERT_EQ(displaced.positions.size(), 3u * 150u * 4u);
  double worst_polynomial = 0;
  double worst_instanced = 0;
  for (std::size_t i = 0; i < displaced.positions.size(); ++i)
  {
    worst_polynomial = std::max(worst_polynomial,
                                double(std::abs(displaced.positions[i] - polynomial.positions[i])));
    worst_instanced =
      std::max(worst_instanced, double(std::abs(displaced.positions[i] - instanced.positions[i])));
  }
  EXPECT_LT(worst_polynomial, 1e-6);
  EXPECT_LT(worst_instanced, 1e-6);
  ASSERT_EQ(polynomial.polynomial_rms_residual.size(), 4u);
  for (double residual : polynomial.polynomial_rms_residual)
  {
    EXPECT_LT(residual, 1e-6);
  }
  // Heights: the plane's normal is +-z, atoms sit scale * (z - centre) away from it.
  const double height = std::abs(displaced.positions[2]);
  EXPECT_NEAR(height, 0.5 * std::abs(patch.positions[2] - 4.0), 1e-9);
  EXPECT_EQ(instanced.instance_matrices.size(), 16u * 30u * 4u);
  EXPECT_EQ(instanced.instance_tiles.back(), 3);
}

TEST(MembraneMapping, InstancingKeepsMoleculesRigidOnCurvedSurfaces)
{
  const auto sphere = mesolens_test::icosphere(60.0, 6);
  std::array<double, 2> seed_uv{};
  const auto chart = chart_of(sphere, 200, 80.0, &seed_uv);
  const auto patch = mesolens_test::synthetic_patch(40, 4.0f);
  mesolens::MappingParams params;
  params.method = mesolens::MappingMethod::MoleculeInstancing;
  params.tiles = 3;
  params.scale = 0.7;
  params.centre_uv = seed_uv;
  const auto mapped = mesolens::map_membrane(chart, patch.view(), params);
  double worst = 0;
  const std::size_t n = patch.molecule_ids.size();
  for (std::size_t tile = 0; tile < 9; ++tile)
  {
    for (std::size_t a = 0; a < n; ++a)
    {
      for (std::size_t b = a + 1; b < n && patch.molecule_ids[b] == patch.molecule_ids[a]; ++b)
      {
        const double original = 0.7 * distance(&patch.positions[3 * a], &patch.positions[3 * b]);
        const double now =
          distance(&mapped.positions[3 * (tile * n + a)], &mapped.positions[3 * (tile * n + b)]);
        worst = std::max(worst, std::abs(now - original) / original);
      }
    }
  }
  EXPECT_LT(worst, 1e-5);
  // Displacement bends the same molecules: their bonds change length.
  params.method = mesolens::MappingMethod::Displacement;
  const auto bent = mesolens::map_membrane(chart, patch.view(), params);
  std::vector<std::array<std::uint32_t, 2>> bonds;
  for (std::uint32_t a = 0; a + 1 < n; ++a)
  {
    if (patch.molecule_ids[a] == patch.molecule_ids[a + 1])
    {
      bonds.push_back({ a, a + 1 });
    }
  }
  const auto rigid = mesolens::bond_length_changes(patch.view(), mapped, bonds, 0.7);
  const auto changed = mesolens::bond_length_changes(patch.view(), bent, bonds, 0.7);
  ASSERT_EQ(rigid.size(), 9 * bonds.size());
  double largest_rigid = 0;
  double largest_bent = 0;
  for (std::size_t i = 0; i < rigid.size(); ++i)
  {
    largest_rigid = std::max(largest_rigid, std::abs(rigid[i]));
    largest_bent = std::max(largest_bent, std::abs(changed[i]));
  }
  EXPECT_LT(largest_rigid, 1e-5);
  EXPECT_GT(largest_bent, 1e-3);
}

TEST(MembraneMapping, BadInputs)
{
  const auto plane = mesolens_test::plane_grid(41, 20.0);
  std::array<double, 2> seed_uv{};
  const auto chart = chart_of(plane, 1640, 15.0, &seed_uv);
  auto patch = mesolens_test::synthetic_patch(4, 4.0f);
  mesolens::MappingParams params;
  params.centre_uv = seed_uv;
  params.tiles = 0;
  EXPECT_THROW(mesolens::map_membrane(chart, patch.view(), params), mesolens::InvalidInput);
  params.tiles = 4; // 80 wide: outside a disk of radius 15
  try
  {
    mesolens::map_membrane(chart, patch.view(), params);
    FAIL() << "atoms outside the disk were accepted";
  }
  catch (const mesolens::InvalidInput& e)
  {
    EXPECT_NE(std::string(e.what()).find("outside the geodesic disk"), std::string::npos)
      << e.what();
  }
  params.tiles = 1;
  params.scale = -1;
  EXPECT_THROW(mesolens::map_membrane(chart, patch.view(), params), mesolens::InvalidInput);
  params.scale = 0.1;
  params.method = mesolens::MappingMethod::MoleculeInstancing;
  auto view = patch.view();
  view.molecule_ids = nullptr;
  EXPECT_THROW(mesolens::map_membrane(chart, view, params), mesolens::InvalidInput);
  view = patch.view();
  view.b = view.a; // a degenerate cell
  EXPECT_THROW(mesolens::map_membrane(chart, view, params), mesolens::InvalidInput);
  patch.positions[4] = std::nanf("");
  EXPECT_THROW(mesolens::map_membrane(chart, patch.view(), params), mesolens::InvalidInput);
}
