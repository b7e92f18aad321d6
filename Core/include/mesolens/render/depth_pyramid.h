// SPDX-License-Identifier: GPL-3.0-or-later
// Conservative per-atom occlusion tests against a depth image: a pyramid of the farthest depth
// over ever larger squares of pixels (a "hierarchical Z" of maxima, as in Greene et al. 1993
// and Grottel et al. 2010). Whatever it calls hidden has no visible pixel in front of that
// depth image; it may call some hidden things visible.
#pragma once

#include "mesolens/common/point_span.h"
#include "mesolens/render/atom_cells.h"
#include "mesolens/common/parallel_for.h"

#include <array>
#include <cstdint>
#include <vector>

namespace mesolens {

/// The rectangle an object may cover in a depth image (pixel units, x right, y up, pixel (i, j)
/// spanning [i, i + 1] x [j, j + 1]) and the nearest window depth (0 near plane, 1 far plane)
/// any of its points can have.
struct ScreenFootprint
{
  double x0 = 0;
  double y0 = 0;
  double x1 = 0;
  double y1 = 0;
  double depth = 0;
};

/// The footprint of the axis-aligned box [low, high] (model units) seen through
/// `model_to_clip` (row-major 4 x 4) and a viewport of `width` x `height` pixels. False when
/// the box reaches the eye's plane or the near plane (no footprint can be trusted then).
bool box_footprint(const double low[3], const double high[3], const double model_to_clip[16],
                   int width, int height, ScreenFootprint& footprint);

/// A camera's transforms, row-major 4 x 4 (y = M (x, 1)).
struct ViewTransform
{
  double model_to_view[16];  ///< model to eye coordinates (the eye looks down -z)
  double view_to_clip[16];   ///< projection: perspective (w = -z) or parallel (w = 1)
  double model_to_clip[16];  ///< their product
  double view_per_model = 1; ///< length of one model unit in eye coordinates (uniform scale)

  /// Fills model_to_clip and view_per_model from the other two.
  void Complete();
};

/// A sphere in eye coordinates.
struct EyeSphere
{
  double centre[3] = { 0, 0, 0 };
  double radius = 0;
};

/// The footprint of a sphere (centre and radius in model units): the exact extent of its
/// outline in x and y and the depth of its nearest point, in both perspective and parallel
/// projections; the sphere in eye coordinates in `eye` if given. False when it reaches the eye's
/// plane or the near plane.
bool sphere_footprint(const double centre[3], double radius, const ViewTransform& view, int width,
                      int height, ScreenFootprint& footprint, EyeSphere* eye = nullptr);

/// Farthest-depth pyramid of one depth image.
class DepthPyramid
{
public:
  /// Level 0 is the image (`width` x `height` window depths, rows bottom to top, as
  /// glReadPixels gives them); each next level holds the maximum of 2 x 2 texels of the one
  /// below (edges clamped). An empty image (0 x 0) makes a pyramid that hides nothing.
  void Build(const float* depth, int width, int height);

  /// Whether the footprint is hidden: everything drawn at the pixels of the image whose centres
  /// lie in its rectangle is nearer than its depth (only those pixels can get its fragments;
  /// none at all: hidden). Reads 2 x 2 texels of a coarse level first, then up to
  /// (2 most_texels)^2 pixels one by one, or most_texels^2 texels of the level where the
  /// rectangle spans that many (more texels: a sharper answer for more reads).
  bool Hidden(const ScreenFootprint& footprint, int most_texels = 4) const;

  /// The farthest depth drawn at the pixels of the image whose centres lie in the footprint's
  /// rectangle, or an upper bound of it from a coarser level (as Hidden reads them); 0 when
  /// there are none, 1 for an empty pyramid.
  double Farthest(const ScreenFootprint& footprint, int most_texels = 4) const;

  /// Whether a sphere (its footprint, and itself in eye coordinates seen through
  /// `view_to_clip`) is hidden: Hidden, or, over at most 16 x 16 pixels, at every pixel whose
  /// ray meets the sphere (the impostors' own test, with a little slack) something nearer than
  /// the sphere's nearest point is drawn.
  bool SphereHidden(const ScreenFootprint& footprint, const EyeSphere& sphere,
                    const double view_to_clip[16]) const;

  int Width() const
  {
    return this->Levels.empty() ? 0 : this->Sizes[0][0];
  }
  int Height() const
  {
    return this->Levels.empty() ? 0 : this->Sizes[0][1];
  }

private:
  /// Whether every texel of the rectangle (inclusive) of `level` is nearer than visible_from.
  bool Covered(std::size_t level, int i0, int j0, int i1, int j1, double visible_from) const;
  /// The first, coarse test of Hidden: 1 hidden, 0 visible, -1 undecided; the footprint's pixel
  /// rectangle (i0, j0, i1, j1) in `pixels` when it has one.
  int HiddenCoarse(const ScreenFootprint& footprint, int pixels[4]) const;

  std::vector<std::vector<float>> Levels;
  std::vector<std::array<int, 2>> Sizes;
};

/// Bits of an atom's visibility state (one byte per atom, in slot order).
enum AtomVisibility : std::uint8_t
{
  /// Visible in the last test: drawn first in the next frame.
  SEEN = 1,
  /// Visible now and not drawn first this frame: drawn after the test.
  NEWLY_SEEN = 2,
};

/// What one frame's test found, per cell: whether any of its atoms is SEEN (NEWLY_SEEN).
struct CellVisibility
{
  std::vector<std::uint8_t> seen;
  std::vector<std::uint8_t> newly_seen;
  std::size_t drawn_first = 0; ///< atoms of the cells in view that were SEEN on entry
  std::size_t drawn_after = 0; ///< atoms now NEWLY_SEEN
};

/// The atoms of the cells a visibility test visits, one cell at a time: their positions may be
/// computed only then (a patch warped tile by tile). The atoms of cell c have the slots
/// [first_slot(c), first_slot(c + 1)), the cells' slots in order.
class CellAtoms
{
public:
  virtual ~CellAtoms() = default;
  /// The number of cells.
  virtual std::size_t cell_count() const = 0;
  /// The first slot of `cell`, for cell in [0, cell_count()] (the last: the number of slots).
  virtual std::uint32_t first_slot(std::size_t cell) const = 0;
  /// The positions (3 per atom, model units) and radii (model units) of the cell's atoms, in
  /// slot order. Called from several threads at once.
  virtual void load(std::size_t cell, std::vector<float>& xyz, std::vector<float>& radii) const = 0;
  /// The footprint of what holds the cell's atom centres, grown by `padding`: by default its
  /// box in `boxes` (6 per cell) through box_footprint. False when it reaches the eye's plane or
  /// the near plane.
  virtual bool cell_footprint(std::size_t cell, const std::vector<float>& boxes, double padding,
                              const ViewTransform& view, int width, int height,
                              ScreenFootprint& footprint) const;
};

/// Atoms stored in slot order (`slot_xyz` one per slot, radius
/// `radius_of_element[element_of_slot[slot * element_stride]]`), grouped by `cells`. The
/// arrays are referenced, not copied.
class StoredCellAtoms : public CellAtoms
{
public:
  StoredCellAtoms(PointSpan<const float> slot_xyz, const std::uint8_t* element_of_slot,
                  std::size_t element_stride, const float* radius_of_element,
                  const AtomCells& cells);
  std::size_t cell_count() const override;
  std::uint32_t first_slot(std::size_t cell) const override;
  void load(std::size_t cell, std::vector<float>& xyz, std::vector<float>& radii) const override;

private:
  PointSpan<const float> SlotXYZ;
  const std::uint8_t* ElementOfSlot;
  std::size_t ElementStride;
  const float* RadiusOfElement;
  const AtomCells& Cells;
};

/// Tests every atom of the cells in view against the pyramid and rewrites `flags` (one per
/// slot; the SEEN bit on entry says what was drawn first this frame): SEEN when not hidden,
/// NEWLY_SEEN when not hidden and not drawn first. Atoms of cells that are not in view, or
/// whose box (`boxes`, 6 per cell, grown by `padding`) is hidden, get 0. Cells in view that
/// reach the eye keep all their atoms SEEN (NEWLY_SEEN unless drawn first). Throws
/// InvalidInput for boxes of another count than the cells.
CellVisibility test_atom_visibility(const DepthPyramid& pyramid, const ViewTransform& view,
                                    const CellAtoms& atoms, const std::vector<float>& boxes,
                                    const std::vector<CellInView>& in_view, double padding,
                                    std::vector<std::uint8_t>& flags,
                                    const ParallelFor& parallel_for = {});

/// The same for atoms stored in slot order (StoredCellAtoms).
CellVisibility test_atom_visibility(
  const DepthPyramid& pyramid, const ViewTransform& view, PointSpan<const float> slot_xyz,
  const std::uint8_t* element_of_slot, std::size_t element_stride, const float* radius_of_element,
  const AtomCells& cells, const std::vector<float>& boxes, const std::vector<CellInView>& in_view,
  double padding, std::vector<std::uint8_t>& flags, const ParallelFor& parallel_for = {});

} // namespace mesolens
