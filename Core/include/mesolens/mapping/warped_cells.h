// SPDX-License-Identifier: GPL-3.0-or-later
// Occlusion culling of a membrane patch that the renderer warps tile by tile: the patch's culling
// cells carried into every tile, as boxes (conservative) and as atoms whose warped positions are
// computed only when a test needs them, so no mapped copy of the atoms is kept.
#pragma once

#include "mesolens/common/parallel_for.h"
#include "mesolens/common/point_span.h"
#include "mesolens/mapping/membrane_mapping.h"
#include "mesolens/mapping/membrane_warp.h"
#include "mesolens/render/atom_cells.h"
#include "mesolens/render/depth_pyramid.h"

#include <cstdint>
#include <vector>

namespace mesolens {

/// The culling cells of a patch carried through every tile of a warp (see warped_cell_boxes).
struct WarpedCellBoxes
{
  /// Per tile, its frame: 12 values, the rows of the 3 x 4 map from local to mesh coordinates
  /// (an orthonormal rotation and the tile's centre): local axes along the surface, the third
  /// along its normal, so that the boxes of a tilted membrane's cells stay tight.
  std::vector<double> frames;
  /// Box t C + c (6 floats: x, y, z minima, then maxima), in tile t's local coordinates.
  std::vector<float> local;
  /// The same boxes' bounds in mesh coordinates (axis-aligned, so larger).
  std::vector<float> world;
};

/// The culling cells of a patch carried through every tile of a warp, for occlusion culling of
/// a patch that is warped when drawn. Box t C + c holds every atom centre of cell c (of the C
/// cells of `cells`) in tile t, rounded outward to float:
/// - Polynomial: warped_box of the cell's box (`cell_boxes`, 6 per cell, patch coordinates, as
///   gather_cell_positions makes them) with the tile's pieces, written in the tile's frame;
/// - MoleculeInstancing: the box of each molecule's atoms in the cell (`slot_xyz`, one per
///   slot; `molecule_of_slot`, the molecule's index among tile 0's instances) moved by that
///   molecule's motion in the tile, joined: exact for rigid (affine) motions.
/// `warp` must be drawable (check_drawable); `slot_xyz` and `molecule_of_slot` are read for
/// MoleculeInstancing only. Throws InvalidInput for inputs of other lengths or molecule indices
/// beyond tile 0's.
WarpedCellBoxes warped_cell_boxes(const MembraneWarp& warp, const AtomCells& cells,
                                  const std::vector<float>& cell_boxes,
                                  PointSpan<const float> slot_xyz,
                                  const std::vector<unsigned short>& molecule_of_slot,
                                  const ParallelFor& parallel_for = {});

/// The atoms of a patch's culling cells in every tile of a warp, for test_atom_visibility:
/// cell t C + c is cell c of `cells` (C cells, n atoms) in tile t; its slots are t n plus the
/// patch slots; its positions are the patch positions (`slot_xyz`, one per slot) warped as the
/// renderer warps them (evaluate_tile_polynomial, or the motion of the atom's molecule,
/// `molecule_of_slot`: its index among tile 0's instances, read for MoleculeInstancing only),
/// computed when loaded; its radii `radius_of_element[element_of_slot[slot * element_stride]]`
/// plus margin(): `relative_margin` times the largest absolute mesh coordinate of the boxes
/// (for the renderer's own rounding of the warp, e.g. a few float epsilons). Its cells' boxes are
/// warped_cell_boxes' (boxes(): the world ones, for cells_in_view and the test; the test's
/// footprints come from the tighter local ones). Every array and `warp` are referenced, not
/// copied: the element and radius vectors may change their values (a new visibility mask)
/// but not their lengths, the rest must stay unchanged while it is used. Throws InvalidInput for a
/// warp that cannot be drawn from the patch, arrays of other lengths, or more than 2^32 - 1 slots
/// in all.
class WarpedCellAtoms : public CellAtoms
{
public:
  WarpedCellAtoms(const MembraneWarp& warp, const AtomCells& cells,
                  const std::vector<float>& cell_boxes, PointSpan<const float> slot_xyz,
                  const std::vector<unsigned short>& molecule_of_slot,
                  const std::vector<std::uint8_t>& element_of_slot, std::size_t element_stride,
                  const std::vector<float>& radius_of_element, double relative_margin,
                  const ParallelFor& parallel_for = {});
  std::size_t cell_count() const override;
  std::uint32_t first_slot(std::size_t cell) const override;
  void load(std::size_t cell, std::vector<float>& xyz, std::vector<float>& radii) const override;
  /// The footprint of the cell's box in its tile's frame (`boxes` is not read).
  bool cell_footprint(std::size_t cell, const std::vector<float>& boxes, double padding,
                      const ViewTransform& view, int width, int height,
                      ScreenFootprint& footprint) const override;

  /// Per cell, the bounds of its atom centres in mesh coordinates (6 floats each).
  const std::vector<float>& boxes() const
  {
    return this->Boxes.world;
  }
  /// What the radii and the boxes are grown by for the renderer's rounding, mesh units.
  double margin() const
  {
    return this->Margin;
  }

private:
  const MembraneWarp& Warp;
  const AtomCells& Cells;
  PointSpan<const float> SlotXYZ;
  const std::vector<unsigned short>& MoleculeOfSlot;
  const std::vector<std::uint8_t>& ElementOfSlot;
  std::size_t ElementStride;
  const std::vector<float>& RadiusOfElement;
  WarpedCellBoxes Boxes;
  double Margin = 0;
  std::vector<std::size_t> FirstPiece; ///< polynomial: per tile
  /// Polynomial: per slot, (s, t, h), the same in every tile.
  std::vector<double> LocalCoordinates;
  std::size_t Molecules = 0; ///< instancing: per tile
};

} // namespace mesolens
