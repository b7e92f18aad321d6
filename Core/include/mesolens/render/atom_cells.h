// SPDX-License-Identifier: GPL-3.0-or-later
// Atoms grouped into small spatial cells so that a renderer can skip whole cells that are out
// of view or hidden behind what it has already drawn (occlusion culling, as in Grottel et al.,
// "Coherent culling and shading for large molecular dynamics visualization", EuroVis 2010).
#pragma once

#include "mesolens/common/parallel_for.h"
#include "mesolens/common/point_span.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace mesolens {

/// A grouping of atoms into cells. The atoms are given "draw slots": the atoms of cell c occupy
/// slots [cell_start[c], cell_start[c + 1]), in their input order.
struct AtomCells
{
  std::vector<std::uint32_t> atom_of_slot; ///< input atom index of each slot
  std::vector<std::uint32_t> cell_start;   ///< one per cell plus the end (empty: no cells)

  std::size_t cell_count() const
  {
    return cell_start.empty() ? 0 : cell_start.size() - 1;
  }
};

/// Groups atoms into the occupied cells of a uniform cubic grid whose edge is chosen so that an
/// occupied cell holds about `atoms_per_cell` atoms (the edge shrinks for sparse sets, such as a
/// membrane curved over a large box, so that the occupied cells keep that size). `xyz`: finite
/// positions, one per atom; `atoms_per_cell` >= 1. Deterministic: cells in grid order, atoms in
/// input order within a cell. No atoms: no cells.
AtomCells group_atoms_into_cells(PointSpan<const float> xyz, std::size_t atoms_per_cell);

/// Copies the positions (`xyz`, one per atom) into slot order (`slot_xyz`, one per slot) and
/// computes each cell's box of atom centres (`boxes`, 6 per cell: min x, y, z, max x, y, z). For
/// a new time step of the same atoms the grouping stays and only this runs. Throws InvalidInput
/// when `xyz` or `slot_xyz` has another length than the cells' atoms.
void gather_cell_positions(PointSpan<const float> xyz, const AtomCells& cells,
                           PointSpan<float> slot_xyz, std::vector<float>& boxes,
                           const ParallelFor& parallel_for = {});

/// The box of all points, VTK's layout (min x, max x, min y, max y, min z, max z); for no points
/// (1, -1, 1, -1, 1, -1). Every point counts, used by a cell or not. Deterministic whatever
/// `parallel_for`: fixed blocks, reduced in order.
std::array<double, 6> point_bounds(PointSpan<const float> xyz,
                                   const ParallelFor& parallel_for = {});

/// The summed box diagonals: how spread the cells are (it grows as the atoms of a trajectory
/// drift from the cells they were grouped into).
double total_cell_diagonal(const std::vector<float>& boxes);

/// A cell that may be visible, as seen through a camera.
struct CellInView
{
  std::uint32_t cell = 0;
  double depth = 0;       ///< normalised device depth of the box's centre; -1 when must_draw
  bool must_draw = false; ///< the box reaches the eye or the near plane: it cannot be tested
};

/// The cells whose boxes, grown by `pad` (the largest atom radius), are not entirely outside the
/// view volume of `model_to_clip` (row-major 4 x 4: clip = M (x, y, z, 1)), nearest centre
/// first (a cell hidden behind a neighbour then mostly comes after it).
/// Conservative: a cell is left out only when all its box corners lie outside one clip plane.
std::vector<CellInView> cells_in_view(const std::vector<float>& boxes, double pad,
                                      const double model_to_clip[16]);

} // namespace mesolens
