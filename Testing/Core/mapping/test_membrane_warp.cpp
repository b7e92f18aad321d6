// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/mapping/membrane_warp.h"

#include "mesolens/common/errors.h"
#include "mesolens/mapping/membrane_mapper.h"
#include "mesolens_test_patch.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

/// A drawable warp of k x k tiles by `method`: polynomial pieces per side `splits` (one per
/// tile), or `molecules` instances per tile.
mesolens::MembraneWarp warp_of(mesolens::MappingMethod method, int k,
                               const std::vector<int>& splits = {}, int molecules = 2)
{
  mesolens::MembraneWarp warp;
  warp.method = method;
  warp.tiles = k;
  warp.a = { 60, 0 };
  warp.b = { 10, 55 };
  warp.layer_half_thickness = 20;
  if (method == mesolens::MappingMethod::Polynomial)
  {
    warp.polynomial_splits = splits;
    std::size_t pieces = 0;
    for (const int m : splits)
    {
      pieces += std::size_t(m * m);
    }
    warp.polynomial_coefficients.assign(30 * (splits.empty() ? std::size_t(k * k) : pieces), 0.5);
  }
  else
  {
    for (int tile = 0; tile < k * k; ++tile)
    {
      for (int m = 0; m < molecules; ++m)
      {
        warp.instance_molecules.push_back(7 + m);
        warp.instance_tiles.push_back(tile);
        warp.instance_matrices.insert(warp.instance_matrices.end(), 16, 0.0);
      }
    }
  }
  return warp;
}

TEST(MembraneWarp, FirstPiecesFollowTheSplits)
{
  const auto warp = warp_of(mesolens::MappingMethod::Polynomial, 2, { 1, 2, 1, 4 });
  EXPECT_EQ(mesolens::polynomial_first_pieces(warp), (std::vector<std::size_t>{ 0, 1, 5, 6, 22 }));
  // Without splits, one piece per tile.
  const auto whole = warp_of(mesolens::MappingMethod::Polynomial, 3);
  EXPECT_EQ(mesolens::polynomial_first_pieces(whole).back(), 9u);
}

TEST(MembraneWarp, InconsistentPolynomialsAreRefused)
{
  auto short_of_one = warp_of(mesolens::MappingMethod::Polynomial, 2, { 1, 2, 1, 4 });
  short_of_one.polynomial_coefficients.resize(30 * 21);
  EXPECT_THROW(mesolens::polynomial_first_pieces(short_of_one), mesolens::InvalidInput);
  auto no_pieces = warp_of(mesolens::MappingMethod::Polynomial, 2, { 1, 0, 1, 1 });
  EXPECT_THROW(mesolens::polynomial_first_pieces(no_pieces), mesolens::InvalidInput);
  auto too_many = warp_of(mesolens::MappingMethod::Polynomial, 1, { 65 });
  EXPECT_THROW(mesolens::polynomial_first_pieces(too_many), mesolens::InvalidInput);
  auto wrong_tiles = warp_of(mesolens::MappingMethod::Polynomial, 2, { 1, 1, 1 });
  EXPECT_THROW(mesolens::polynomial_first_pieces(wrong_tiles), mesolens::InvalidInput);
  EXPECT_THROW(mesolens::check_drawable(short_of_one), mesolens::InvalidInput);
}

TEST(MembraneWarp, DrawableWarpsPassAndEveryDefectIsNamed)
{
  EXPECT_NO_THROW(mesolens::check_drawable(warp_of(mesolens::MappingMethod::Polynomial, 2)));
  EXPECT_NO_THROW(
    mesolens::check_drawable(warp_of(mesolens::MappingMethod::MoleculeInstancing, 3)));
  auto expect_refused = [](const mesolens::MembraneWarp& warp, const std::string& phrase) {
    try
    {
      mesolens::check_drawable(warp);
      ADD_FAILURE() << "accepted; expected: " << phrase;
    }
    catch (const mesolens::InvalidInput& e)
    {
      EXPECT_NE(std::string(e.what()).find(phrase), std::string::npos) << e.what();
    }
  };
  auto warp = warp_of(mesolens::MappingMethod::Polynomial, 2);
  warp.tiles = 0;
  expect_refused(warp, "no tiles");
  warp = warp_of(mesolens::MappingMethod::Polynomial, 2);
  warp.layer_half_thickness = 0;
  expect_refused(warp, "thickness");
  warp.layer_half_thickness = std::nan("");
  expect_refused(warp, "thickness");
  warp = warp_of(mesolens::MappingMethod::Polynomial, 1);
  warp.cut_to_disk = true;
  expect_refused(warp, "cut its one tile");
  warp = warp_of(mesolens::MappingMethod::Polynomial, 2);
  warp.b = { 120, 0 }; // parallel to a
  expect_refused(warp, "degenerate");
  warp = warp_of(mesolens::MappingMethod::Displacement, 2);
  expect_refused(warp, "DISPLACEMENT");
  warp = warp_of(mesolens::MappingMethod::MoleculeInstancing, 2);
  warp.instance_matrices.pop_back();
  expect_refused(warp, "molecule motions");
  warp = warp_of(mesolens::MappingMethod::MoleculeInstancing, 2);
  warp.instance_tiles.assign(warp.instance_tiles.size(), 1); // no tile 0
  expect_refused(warp, "molecule motions");
}

TEST(MembraneWarp, MoleculesPerTileAreTileZerosInstances)
{
  EXPECT_EQ(mesolens::molecules_per_tile(warp_of(mesolens::MappingMethod::MoleculeInstancing, 2,
                                                 {}, 5)),
            5u);
  EXPECT_EQ(mesolens::molecules_per_tile(mesolens::MembraneWarp{}), 0u);
}

TEST(MembraneWarp, IsWhatTheMapperMapped)
{
  mesolens::TriangleMesh square;
  square.points = { -1e3, -1e3, 0, 1e3, -1e3, 0, 1e3, 1e3, 0, -1e3, 1e3, 0 };
  square.triangles = { 0, 1, 2, 0, 2, 3 };
  const mesolens::MembraneMapper mapper(square);
  const auto patch = mesolens_test::synthetic_patch(8);
  const auto seed = mapper.seed_near({ 1.0, 2.0, 0.0 });
  for (const auto method :
       { mesolens::MappingMethod::MoleculeInstancing, mesolens::MappingMethod::Polynomial })
  {
    mesolens::MapRequest request;
    request.mapping.method = method;
    request.mapping.tiles = 2;
    request.mapping.scale = 0.5;
    request.mapping.layer_half_thickness = 15;
    const auto result = mapper.map(seed, patch.view(), request);
    const auto warp = mesolens::membrane_warp(result, patch.view(), request);
    EXPECT_EQ(warp.method, method);
    EXPECT_EQ(warp.tiles, 2);
    EXPECT_EQ(warp.tiles_requested, 2);
    EXPECT_EQ(warp.scale, 0.5);
    EXPECT_EQ(warp.layer_half_thickness, 15);
    EXPECT_EQ(warp.a, patch.view().a);
    EXPECT_EQ(warp.b, patch.view().b);
    EXPECT_EQ(warp.centre_height, patch.view().centre_height);
    EXPECT_EQ(warp.geodesic_radius, result.chart->radius);
    EXPECT_EQ(warp.seed_uv, result.chart->seed_uv);
    EXPECT_NEAR(std::abs(warp.seed_normal[2]), 1.0, 1e-9); // the flat square's normal
    EXPECT_EQ(warp.polynomial_coefficients, result.mapped.polynomial_coefficients);
    EXPECT_EQ(warp.instance_matrices, result.mapped.instance_matrices);
    EXPECT_NO_THROW(mesolens::check_drawable(warp));
    if (method == mesolens::MappingMethod::MoleculeInstancing)
    {
      EXPECT_EQ(mesolens::molecules_per_tile(warp), 8u);
    }
  }
}

} // namespace
