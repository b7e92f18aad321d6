// SPDX-License-Identifier: GPL-3.0-or-later
// The structure mesh of a flat membrane that spans its periodic box (private to MesoLensCore):
// a lattice of near-equilateral triangles over the box's cell in the membrane's plane, lifted
// to the membrane's middle sheet.
#pragma once

#include "mesolens/molecules/periodic_box.h"
#include "mesolens/mesh/triangle_mesh.h"

#include <array>
#include <optional>
#include <vector>

namespace mesolens {

/// The cell of a periodic box that a flat membrane spans: the parallelogram origin + u a + v b
/// (u, v in [0, 1]) in the membrane's plane, with a and b the two box vectors along it.
struct SheetCell
{
  std::array<double, 3> origin{}; ///< with no component along `normal`
  std::array<double, 3> a{};
  std::array<double, 3> b{};
  std::array<double, 3> normal{}; ///< unit, a x b
};

/// The cell when `points` (3 coordinates each, Å) spread over exactly two of `box`'s vectors
/// and not over the third: along a vector they spread over, their fractional coordinates leave
/// no gap wider than 1/8 of the period (a bilayer leaves the water's gap along its normal; a
/// vesicle gaps along all three). The cell is centred on the points' mean in the plane.
/// Nothing when the box is not set or the points spread otherwise.
std::optional<SheetCell> periodic_sheet_cell(const std::vector<double>& points,
                                             const PeriodicBox& box);

/// `points` followed by their periodic images (shifted by -1, 0 or 1 times a and b, not both 0)
/// that lie within `margin` (Å, >= 0) of the cell, measured in the plane.
std::vector<double> with_periodic_images(const std::vector<double>& points, const SheetCell& cell,
                                         double margin);

/// The lattice's columns (edges along a, >= 2) and rows (edges along b, >= 1).
struct LatticeShape
{
  int columns = 2;
  int rows = 1;
};

/// The lattice shape whose triangles are nearest to equilateral with edges of about `edge`
/// (Å) when `edge` > 0; else, with the rows' spacing within 0.75-1.33 times sqrt(3) / 2 of the
/// edge, the one that best trades a vertex count near `vertices` (>= 4) against equilateral
/// triangles (a count 5 % off weighs as much as rows 10 % too far apart or too close).
LatticeShape lattice_shape(const SheetCell& cell, std::size_t vertices, double edge);

/// A lattice mesh over the cell: `shape.rows` + 1 rows along a, `shape.columns` edges of
/// |a| / columns in each, each row shifted half an edge from the last, so that in the plane
/// every triangle is isosceles with its base along a (angles within 47-75°, mostly 55-65°; the
/// sides along b are zigzags). Each vertex is lifted along the normal to the Gaussian-weighted
/// mean height (standard deviation `smoothing`, Å, > 0) of the middle-sheet points `sheet` (3
/// coordinates each, with their periodic images) near it in the plane, or of the 8 nearest where
/// fewer than 3 lie within 2.5 deviations (a protein's hole). Throws TopologyError without
/// sheet points.
TriangleMesh sheet_lattice(const SheetCell& cell, const LatticeShape& shape,
                           const std::vector<double>& sheet, double smoothing);

} // namespace mesolens
