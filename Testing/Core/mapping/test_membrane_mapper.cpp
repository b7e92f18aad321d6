// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/mapping/membrane_mapper.h"

#include "mesolens/common/errors.h"
#include "mesolens_test_meshes.h"
#include "mesolens_test_patch.h"
#include "mesolens_test_threads.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <thread>

namespace {

mesolens::MapRequest request(mesolens::MappingMethod method, int tiles, double scale = 1)
{
  mesolens::MapRequest r;
  r.mapping.method = method;
  r.mapping.tiles = tiles;
  r.mapping.scale = scale;
  r.mapping.layer_half_thickness = 15;
  return r;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b)
{
  // memcmp must not see the null data of empty vectors.
  return a.size() == b.size() &&
    (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

/// A ParallelFor on `threads` threads, each taking interleaved chunks of 3.
mesolens::ParallelFor threads(int count)
{
  return [count](std::size_t size, const mesolens::RangeKernel& kernel) {
    std::vector<std::thread> pool;
    for (int t = 0; t < count; ++t)
    {
      pool.emplace_back([=, &kernel] {
        for (std::size_t begin = 3 * std::size_t(t); begin < size; begin += 3 * std::size_t(count))
        {
          kernel(begin, std::min(size, begin + 3));
        }
      });
    }
    for (auto& thread : pool)
    {
      thread.join();
    }
  };
}
} // namespace

TEST(MembraneMapper, CoarseMeshesAreRefinedOnTheSmoothSurfaceWhoseVerticesStayPut)
{
  // 20 triangles of edge 5 µm (in Å: 50 000), a patch of 20 Å: the disk lies inside one
  // triangle, far smaller than it.
  const auto icosahedron = mesolens_test::icosphere(47553.0, 0);
  const mesolens::MembraneMapper mapper(icosahedron);
  const auto patch = mesolens_test::synthetic_patch(30);
  // Seeded exactly at a vertex: the smooth surface passes through it.
  const auto seed = mesolens_test::surface_point(icosahedron, 0, { 1, 0, 0 });
  const auto result =
    mapper.map(seed, patch.view(), request(mesolens::MappingMethod::Displacement, 1));
  ASSERT_EQ(result.tiles_mapped, 1);
  EXPECT_TRUE(result.note.empty()) << result.note;
  const mesolens::MappingChart& chart = *result.chart;
  EXPECT_GE(chart.disk.mesh.triangle_count(), 1500u);
  EXPECT_GE(chart.disk.refinement_levels, 20);
  mesolens::SurfaceFrame frame;
  ASSERT_TRUE(chart.chart.frame(chart.seed_uv[0], chart.seed_uv[1], frame));
  const auto vertex = icosahedron.point(icosahedron.triangles[0]);
  for (std::size_t d = 0; d < 3; ++d)
  {
    EXPECT_NEAR(frame.position[d], vertex[d], 1e-6);
    EXPECT_NEAR(frame.normal[d], vertex[d] / 47553.0, 1e-6);
  }
  // Along a line through the disk the surface bends smoothly: no kinks between samples.
  std::array<double, 3> previous{};
  for (int i = -30; i <= 30; ++i)
  {
    ASSERT_TRUE(chart.chart.frame(chart.seed_uv[0] + i, chart.seed_uv[1] + 0.5 * i, frame));
    if (i > -30)
    {
      const double cosine = previous[0] * frame.normal[0] + previous[1] * frame.normal[1] +
        previous[2] * frame.normal[2];
      EXPECT_GT(cosine, std::cos(0.01)) << i; // under 0.6 degrees per Å
    }
    previous = frame.normal;
  }
  // The disk's size does not grow with how much larger the triangles are (bisection ends
  // between half and all of the target area, so counts differ up to twice).
  const auto huge = mesolens_test::icosphere(100 * 47553.0, 0);
  const mesolens::MembraneMapper huge_mapper(huge);
  const auto huge_result =
    huge_mapper.map(mesolens_test::surface_point(huge, 0, { 1, 0, 0 }), patch.view(),
                    request(mesolens::MappingMethod::Displacement, 1));
  const double ratio = double(huge_result.chart->disk.mesh.triangle_count()) /
    double(chart.disk.mesh.triangle_count());
  EXPECT_GT(ratio, 0.5);
  EXPECT_LT(ratio, 2.0);
}

TEST(MembraneMapper, FlatCoarseMeshKeepsTheMidSheetOnIt)
{
  // Two triangles of 2 km: every point the mapping places at height 0 lies on the plane z = 0.
  mesolens::TriangleMesh square;
  square.points = { -1e6, -1e6, 0, 1e6, -1e6, 0, 1e6, 1e6, 0, -1e6, 1e6, 0 };
  square.triangles = { 0, 1, 2, 0, 2, 3 };
  const mesolens::MembraneMapper mapper(square);
  mesolens_test::SyntheticPatch mid;
  mid.positions = { 0, 0, 0, 5, -3, 0, -7, 8, 0 };
  mid.molecule_ids = { 0, 1, 2 };
  const auto seed = mapper.seed_near({ 10.0, 20.0, 0.0 });
  // The patch's x axis follows the mesh's, whatever the disk's triangles.
  const auto chart = mapper.chart(seed, 100.0);
  mesolens::SurfaceFrame frame;
  ASSERT_TRUE(chart->chart.frame(chart->seed_uv[0], chart->seed_uv[1], frame));
  EXPECT_NEAR(frame.tangent_u[0], 1.0, 1e-6); // within 0.1 degree
  EXPECT_NEAR(frame.tangent_v[1], 1.0, 1e-6);
  for (const auto method :
       { mesolens::MappingMethod::Displacement, mesolens::MappingMethod::MoleculeInstancing,
         mesolens::MappingMethod::Polynomial })
  {
    const auto result = mapper.map(seed, mid.view(), request(method, 2));
    ASSERT_EQ(result.tiles_mapped, 2);
    for (std::size_t i = 2; i < result.mapped.positions.size(); i += 3)
    {
      EXPECT_NEAR(result.mapped.positions[i], 0.0, 1e-6) << int(method);
    }
  }
}

TEST(MembraneMapper, WhatDoesNotFitMapsTheLargestPatchThatDoes)
{
  const auto patch = mesolens_test::synthetic_patch(30);
  // A tube of radius 10 (half way round: 31): 3 x 3 tiles of 20 wrap it, one tile fits.
  {
    const auto ring = mesolens_test::torus(300, 10, 360, 24);
    const mesolens::MembraneMapper mapper(ring);
    const auto seed = mapper.seed_near({ 310, 0, 0 });
    for (const auto method :
         { mesolens::MappingMethod::Displacement, mesolens::MappingMethod::MoleculeInstancing,
           mesolens::MappingMethod::Polynomial })
    {
      const auto result = mapper.map(seed, patch.view(), request(method, 3));
      EXPECT_EQ(result.tiles_asked, 3);
      EXPECT_GE(result.tiles_mapped, 1);
      EXPECT_LT(result.tiles_mapped, 3);
      EXPECT_FALSE(result.cut_to_disk);
      EXPECT_NE(result.note.find("instead of 3 x 3"), std::string::npos) << result.note;
      EXPECT_NE(result.note.find("wraps a handle"), std::string::npos) << result.note;
      for (const double x : result.mapped.positions)
      {
        ASSERT_TRUE(std::isfinite(x));
      }
      mesolens::MapRequest strict = request(method, 3);
      strict.fit_what_fits = false;
      EXPECT_THROW(mapper.map(seed, patch.view(), strict), mesolens::TopologyError);
    }
  }
  // A tube of radius 3 (half way round: 9.4) holds no whole tile: one tile cut to a disk.
  {
    const auto ring = mesolens_test::torus(300, 3, 720, 16);
    const mesolens::MembraneMapper mapper(ring);
    const auto seed = mapper.seed_near({ 303, 0, 0 });
    const auto result =
      mapper.map(seed, patch.view(), request(mesolens::MappingMethod::Displacement, 2));
    EXPECT_EQ(result.tiles_mapped, 1);
    EXPECT_TRUE(result.cut_to_disk);
    EXPECT_NE(result.note.find("cut to a geodesic disk"), std::string::npos) << result.note;
    ASSERT_EQ(result.mapped.atom_mapped.size(), patch.molecule_ids.size());
    std::size_t kept = 0;
    for (std::size_t a = 0; a < patch.molecule_ids.size(); ++a)
    {
      const bool mapped = result.mapped.atom_mapped[a] != 0;
      kept += mapped;
      EXPECT_EQ(mapped, std::isfinite(result.mapped.positions[3 * a])) << a;
      // Whole molecules only.
      EXPECT_EQ(mapped, result.mapped.atom_mapped[a - a % 5] != 0) << a;
    }
    EXPECT_GT(kept, 0u);
    EXPECT_LT(kept, patch.molecule_ids.size());
  }
  // A tube thinner than a molecule's footprint (radius 2.9 here): nothing to map.
  {
    const auto ring = mesolens_test::torus(300, 0.4, 1800, 8);
    const mesolens::MembraneMapper mapper(ring);
    const auto seed = mapper.seed_near({ 300.4, 0, 0 });
    try
    {
      mapper.map(seed, patch.view(), request(mesolens::MappingMethod::Displacement, 1));
      FAIL() << "a patch was mapped onto a tube thinner than a molecule";
    }
    catch (const mesolens::TopologyError& e)
    {
      EXPECT_NE(std::string(e.what()).find("footprint"), std::string::npos) << e.what();
    }
  }
  // At the border of an open mesh not even a footprint is a disk.
  {
    const auto plane = mesolens_test::plane_grid(41, 100.0);
    const mesolens::MembraneMapper mapper(plane);
    const auto seed = mesolens_test::surface_point(plane, 0, { 1, 0, 0 });
    try
    {
      mapper.map(seed, patch.view(), request(mesolens::MappingMethod::Displacement, 1));
      FAIL() << "a patch was mapped across the border";
    }
    catch (const mesolens::TopologyError& e)
    {
      EXPECT_NE(std::string(e.what()).find("boundary"), std::string::npos) << e.what();
    }
  }
}

TEST(MembraneMapper, DisksThatWouldStretchTheTilesDoNotFit)
{
  // 3 x 3 tiles of 20 (corners 43 from the centre) need a disk of radius 47 or more on a
  // sphere of radius 25: a disk, but more than a hemisphere, squeezed into the plane near its
  // rim; 2 x 2 tiles fit on a smaller cap.
  const auto sphere = mesolens_test::icosphere(25, 4);
  const mesolens::MembraneMapper mapper(sphere);
  const auto patch = mesolens_test::synthetic_patch(30);
  const auto seed = mapper.seed_near({ 0, 0, 25 });
  auto r = request(mesolens::MappingMethod::Displacement, 3);
  const auto result = mapper.map(seed, patch.view(), r);
  EXPECT_LT(result.tiles_mapped, 3);
  EXPECT_NE(result.note.find("stretch"), std::string::npos) << result.note;
  const double reach = std::hypot(result.chart->seed_uv[0], result.chart->seed_uv[1]) +
    mesolens::tiled_extent(patch.view(), result.tiles_mapped);
  EXPECT_LE(result.chart->largest_stretch_within(reach), 1.5);
  // The same chart stretches more further out, and not at all at its centre.
  EXPECT_GE(result.chart->largest_stretch_within(result.chart->radius),
            result.chart->largest_stretch_within(reach));
  EXPECT_LT(result.chart->largest_stretch_within(0.0), 1.2); // the seed's own triangles
  // A looser bound lets all 9 tiles in; a bound of 1 or less is refused.
  r.max_stretch = 1000;
  EXPECT_EQ(mapper.map(seed, patch.view(), r).tiles_mapped, 3);
  r.max_stretch = 1;
  EXPECT_THROW(mapper.map(seed, patch.view(), r), mesolens::InvalidInput);
}

TEST(MembraneMapper, BitwiseIdenticalRunToRunAndOnAnyThreads)
{
  const auto surface = mesolens_test::torus(120, 40, 90, 36);
  const auto patch = mesolens_test::synthetic_patch(40);
  std::vector<std::vector<double>> results;
  for (const int thread_count : { 0, 1, 2, 8 })
  {
    for (int run = 0; run < 2; ++run)
    {
      const mesolens::MembraneMapper mapper(surface); // a fresh mapper: nothing cached
      const auto seed = mapper.seed_near({ 0, 160, 0 });
      const mesolens::ParallelFor parallel =
        thread_count == 0 ? mesolens::ParallelFor{} : threads(thread_count);
      std::vector<double> all;
      for (const auto method :
           { mesolens::MappingMethod::Displacement, mesolens::MappingMethod::MoleculeInstancing,
             mesolens::MappingMethod::Polynomial })
      {
        const auto result = mapper.map(seed, patch.view(), request(method, 4), parallel);
        const auto& m = result.mapped;
        all.insert(all.end(), m.positions.begin(), m.positions.end());
        all.insert(all.end(), m.instance_matrices.begin(), m.instance_matrices.end());
        all.insert(all.end(), m.polynomial_coefficients.begin(), m.polynomial_coefficients.end());
        all.push_back(double(result.tiles_mapped));
        all.push_back(double(result.chart->disk.mesh.triangle_count()));
        all.insert(all.end(), result.chart->parameterization.uv.begin(),
                   result.chart->parameterization.uv.end());
      }
      results.push_back(all);
    }
  }
  ASSERT_FALSE(results.front().empty());
  for (std::size_t i = 1; i < results.size(); ++i)
  {
    EXPECT_TRUE(same_bits(results[i], results.front())) << "run " << i;
  }
}

TEST(MembraneMapper, PoorPolynomialFitsAreSplit)
{
  // Tiles of 20 on a sphere of radius 40 bend too much for one quadratic within 0.05.
  const auto sphere = mesolens_test::icosphere(40, 4);
  const mesolens::MembraneMapper mapper(sphere);
  const auto patch = mesolens_test::synthetic_patch(30);
  const auto seed = mapper.seed_near({ 0, 0, 40 });
  auto r = request(mesolens::MappingMethod::Polynomial, 2);
  r.mapping.max_polynomial_residual = 0; // no bound: one polynomial per tile
  const auto single = mapper.map(seed, patch.view(), r);
  EXPECT_EQ(single.mapped.polynomial_splits, std::vector<int>(4, 1));
  const double single_worst = *std::max_element(single.mapped.polynomial_max_residual.begin(),
                                                single.mapped.polynomial_max_residual.end());
  r.mapping.max_polynomial_residual = 0.05;
  const auto split = mapper.map(seed, patch.view(), r);
  const auto& m = split.mapped.polynomial_splits;
  EXPECT_GE(*std::max_element(m.begin(), m.end()), 2);
  ASSERT_EQ(split.mapped.polynomial_first_piece.size(), 5u);
  std::size_t pieces = 0;
  for (std::size_t tile = 0; tile < 4; ++tile)
  {
    EXPECT_EQ(split.mapped.polynomial_first_piece[tile], pieces);
    pieces += std::size_t(m[tile] * m[tile]);
    // Split only as far as needed: the bound is met, or the finest split was reached.
    EXPECT_TRUE(split.mapped.polynomial_max_residual[tile] <= 0.05 || m[tile] == 4) << tile;
  }
  EXPECT_EQ(split.mapped.polynomial_coefficients.size(), 30 * pieces);
  const double split_worst = *std::max_element(split.mapped.polynomial_max_residual.begin(),
                                               split.mapped.polynomial_max_residual.end());
  EXPECT_LT(split_worst, 0.5 * single_worst);
  // The atoms come from the piece their (s, t) falls in: the same as the GPU evaluates.
  const auto view = patch.view();
  for (std::size_t tile = 0; tile < 4; ++tile)
  {
    if (split.mapped.tile_fallback[tile])
    {
      continue;
    }
    for (std::size_t a = 0; a < view.atom_count(); a += 7)
    {
      const auto x =
        mesolens::evaluate_tile_polynomial(view, 15, m[tile],
                                           split.mapped.polynomial_coefficients.data() +
                                             30 * split.mapped.polynomial_first_piece[tile],
                                           view.positions[a]);
      for (std::size_t d = 0; d < 3; ++d)
      {
        EXPECT_DOUBLE_EQ(split.mapped.positions[3 * (tile * view.atom_count() + a) + d], x[d]);
      }
    }
  }
  // A bound no polynomial meets: every tile falls back to displacement.
  r.mapping.max_polynomial_residual = 1e-9;
  const auto fallback = mapper.map(seed, patch.view(), r);
  for (const auto flag : fallback.mapped.tile_fallback)
  {
    EXPECT_EQ(flag, 1);
  }
  auto d = request(mesolens::MappingMethod::Displacement, 2);
  const auto displaced = mapper.map(seed, patch.view(), d);
  EXPECT_TRUE(same_bits(fallback.mapped.positions, displaced.mapped.positions));
}

TEST(MembraneMapper, PiecesOfATile)
{
  double s = -1, t = 1;
  EXPECT_EQ(mesolens::polynomial_piece(2, s, t), 2);
  EXPECT_DOUBLE_EQ(s, -1.0);
  EXPECT_DOUBLE_EQ(t, 1.0);
  s = 0.25;
  t = -0.75;
  EXPECT_EQ(mesolens::polynomial_piece(4, s, t), 2);
  EXPECT_DOUBLE_EQ(s, 0.0);
  EXPECT_DOUBLE_EQ(t, 0.0);
  s = 1.5; // beyond the tile: the last piece, extrapolated
  t = 0.1;
  EXPECT_EQ(mesolens::polynomial_piece(2, s, t), 3);
  EXPECT_DOUBLE_EQ(s, 2.0);
}

TEST(MembraneMapper, BadRequests)
{
  const auto sphere = mesolens_test::icosphere(100, 3);
  const mesolens::MembraneMapper mapper(sphere);
  const auto patch = mesolens_test::synthetic_patch(10);
  const auto seed = mapper.seed_near({ 0, 0, 100 });
  auto r = request(mesolens::MappingMethod::Displacement, 0);
  EXPECT_THROW(mapper.map(seed, patch.view(), r), mesolens::InvalidInput);
  r = request(mesolens::MappingMethod::Displacement, 1, -1);
  EXPECT_THROW(mapper.map(seed, patch.view(), r), mesolens::InvalidInput);
  r = request(mesolens::MappingMethod::Displacement, 1);
  r.radius_factor = 0.1;
  EXPECT_THROW(mapper.map(seed, patch.view(), r), mesolens::InvalidInput);
  r.radius_factor = std::nan("");
  EXPECT_THROW(mapper.map(seed, patch.view(), r), mesolens::InvalidInput);
  mesolens_test::SyntheticPatch empty;
  EXPECT_THROW(mapper.map(seed, empty.view(), request(mesolens::MappingMethod::Displacement, 1)),
               mesolens::InvalidInput);
  EXPECT_THROW(mapper.seed_near({ 0, 0, 1000 }), mesolens::InvalidInput);
  EXPECT_THROW(mapper.seed_near({ std::nan(""), 0, 0 }), mesolens::InvalidInput);
  // A non-manifold surface is refused when the mapper is made.
  auto pinched = sphere;
  pinched.triangles.insert(pinched.triangles.end(), { 0, 1, 2 });
  EXPECT_THROW(mesolens::MembraneMapper{ pinched }, mesolens::TopologyError);
}

TEST(MembraneMapper, PiecesMapTheirShareOfTheTilesAndTogetherTheWhole)
{
  const auto surface = mesolens_test::torus(120, 40, 90, 36);
  const auto patch = mesolens_test::synthetic_patch(40);
  const mesolens::MembraneMapper mapper(surface);
  const auto seed = mapper.seed_near({ 0, 160, 0 });
  for (const auto method :
       { mesolens::MappingMethod::Displacement, mesolens::MappingMethod::MoleculeInstancing,
         mesolens::MappingMethod::Polynomial })
  {
    SCOPED_TRACE(int(method));
    auto r = request(method, 3);
    const auto whole = mapper.map(seed, patch.view(), r);
    const std::size_t n = patch.view().atom_count();
    for (const int pieces : { 2, 4, 9, 12 })
    {
      std::vector<double> joined;
      for (int piece = 0; piece < pieces; ++piece)
      {
        r.piece = piece;
        r.pieces = pieces;
        const auto share = mapper.map(seed, patch.view(), r);
        EXPECT_EQ(share.mapped.first_atom_tile, std::size_t(9 * piece / pieces));
        EXPECT_EQ(share.mapped.positions.size(),
                  3 * n * std::size_t(9 * (piece + 1) / pieces - 9 * piece / pieces));
        // What is per tile and small is every piece's.
        EXPECT_TRUE(
          same_bits(share.mapped.polynomial_coefficients, whole.mapped.polynomial_coefficients));
        EXPECT_TRUE(same_bits(share.mapped.instance_matrices, whole.mapped.instance_matrices));
        joined.insert(joined.end(), share.mapped.positions.begin(), share.mapped.positions.end());
      }
      EXPECT_TRUE(same_bits(joined, whole.mapped.positions)) << pieces << " pieces";
    }
  }
  auto bad = request(mesolens::MappingMethod::Displacement, 2);
  for (const auto& [piece, pieces] : { std::pair{ 2, 2 }, std::pair{ -1, 2 }, std::pair{ 0, 0 } })
  {
    bad.piece = piece;
    bad.pieces = pieces;
    EXPECT_THROW(mapper.map(seed, patch.view(), bad), mesolens::InvalidInput);
  }
}
