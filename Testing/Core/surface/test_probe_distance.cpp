// SPDX-License-Identifier: GPL-3.0-or-later
// The distance to a union of spheres' boundary (a private part of MesoLensCore) where its
// index is stretched: spheres far apart along a row of its cells, whose empty cells must cost
// nothing, and queries next to each of them.
#include "surface/detail/probe_distance.h"
#include "surface/detail/sas_boundary.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <array>
#include <cmath>
#include <vector>

namespace {
using Vec = Eigen::Vector3d;
}

TEST(ProbeDistance, SpheresFarApartOnOneRowCostTheirCellsNotTheGap)
{
  // A pair of touching spheres at the origin and one alone 3.4e7 Å along x, on the same row of
  // cells: about 7e7 cells between them (280 MB at 4 bytes each, were the row stored whole).
  const double far = 3.4e7;
  const std::vector<std::array<double, 3>> centre_list{ { 0, 0, 0 }, { 2.5, 0, 0 }, { far, 0, 0 } };
  const std::vector<double> radii{ 1.6, 1.6, 1.8 };
  std::vector<Vec> centres;
  for (const auto& c : centre_list)
  {
    centres.emplace_back(c[0], c[1], c[2]);
  }
  const mesolens::SasBoundary boundary = mesolens::sas_boundary(centre_list, radii, true, {});
  ASSERT_EQ(boundary.arcs.size(), 1u); // the pair's circle
  const double reach = 2.0;
  const mesolens::ProbeDistance distance(centres, radii, boundary, reach);
  EXPECT_LT(distance.table_bytes(), std::size_t(1) << 20);

  // Outside the union (within the reach less the largest radius): the distance to the nearest
  // sphere, negative.
  const mesolens::ClosestPiece beside_alone = distance.closest(Vec(far, 1.9, 0));
  EXPECT_NEAR(beside_alone.distance, -(1.9 - 1.8), 1e-6);
  const mesolens::ClosestPiece beside_pair = distance.closest(Vec(-1.7, 0, 0));
  EXPECT_NEAR(beside_pair.distance, -(1.7 - 1.6), 1e-12);
  // Inside the lone sphere: its face, as deep as the point is.
  const mesolens::ClosestPiece in_alone = distance.closest(Vec(far + 0.5, 0, 0));
  EXPECT_EQ(in_alone.kind, mesolens::PieceKind::Face);
  EXPECT_EQ(in_alone.index, 2u);
  EXPECT_NEAR(in_alone.distance, 1.3, 1e-6);
  // Inside the pair, on the axis between the centres: the circle where the spheres meet.
  const mesolens::ClosestPiece in_pair = distance.closest(Vec(1.25, 0, 0));
  EXPECT_EQ(in_pair.kind, mesolens::PieceKind::Arc);
  const double circle = std::sqrt(1.6 * 1.6 - 1.25 * 1.25);
  EXPECT_NEAR(in_pair.distance, circle, 1e-12);
  // The arc is found from beside it, through the spans of its row.
  std::vector<std::uint32_t> arcs;
  distance.arcs_within(Vec(1.25, 0, circle + 0.1), 0.2, arcs);
  EXPECT_EQ(arcs, std::vector<std::uint32_t>{ 0 });
  arcs.clear();
  distance.arcs_within(Vec(far, 0, 0), 1.0, arcs);
  EXPECT_TRUE(arcs.empty());
}
