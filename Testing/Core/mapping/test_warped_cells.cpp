// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/mapping/warped_cells.h"

#include "mesolens/common/errors.h"
#include "mesolens/mapping/membrane_mapper.h"
#include "mesolens/mapping/membrane_warp.h"
#include "mesolens_test_meshes.h"
#include "mesolens_test_patch.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>

namespace {

/// A patch mapped onto a sphere of radius 60 (tiles of 20 Å on a strongly curved surface),
/// grouped into cells of about 16 atoms.
struct WarpedPatch
{
  mesolens_test::SyntheticPatch patch = mesolens_test::synthetic_patch(60);
  mesolens::MembraneWarp warp;
  mesolens::AtomCells cells;
  std::vector<float> slot_xyz;
  std::vector<float> cell_boxes;
  std::vector<unsigned short> molecule_of_slot;

  WarpedPatch(mesolens::MappingMethod method, double max_residual = 1.0)
  {
    const mesolens::MembraneMapper mapper(mesolens_test::icosphere(60.0, 4));
    mesolens::MapRequest request;
    request.mapping.method = method;
    request.mapping.tiles = 3;
    request.mapping.layer_half_thickness = 15;
    request.mapping.max_polynomial_residual = max_residual;
    request.mapping.map_atoms = false;
    const auto result =
      mapper.map(mapper.seed_near({ 0.0, 0.0, 60.0 }), this->patch.view(), request);
    this->warp = mesolens::membrane_warp(result, this->patch.view(), request);
    const mesolens::PointSpan<const float> xyz(this->patch.positions);
    this->cells = mesolens::group_atoms_into_cells(xyz, 16);
    this->slot_xyz.resize(this->patch.positions.size());
    mesolens::gather_cell_positions(xyz, this->cells, mesolens::PointSpan<float>(this->slot_xyz),
                                    this->cell_boxes);
    if (method == mesolens::MappingMethod::MoleculeInstancing)
    {
      std::map<int, unsigned short> index;
      for (std::size_t i = 0; i < mesolens::molecules_per_tile(this->warp); ++i)
      {
        index.emplace(this->warp.instance_molecules[i], static_cast<unsigned short>(i));
      }
      for (const std::uint32_t atom : this->cells.atom_of_slot)
      {
        this->molecule_of_slot.push_back(index.at(this->patch.molecule_ids[atom]));
      }
    }
  }

  mesolens::PointSpan<const float> slots() const
  {
    return mesolens::PointSpan<const float>(this->slot_xyz);
  }

  /// Where the renderer puts slot `slot` in tile `tile`.
  std::array<double, 3> warped(std::size_t tile, std::size_t slot) const
  {
    const float* p = this->slot_xyz.data() + 3 * slot;
    if (this->warp.method == mesolens::MappingMethod::Polynomial)
    {
      const auto first = mesolens::polynomial_first_pieces(this->warp);
      const int splits =
        this->warp.polynomial_splits.empty() ? 1 : this->warp.polynomial_splits[tile];
      return mesolens::evaluate_tile_polynomial(
        this->warp.frame(), this->warp.layer_half_thickness, splits,
        this->warp.polynomial_coefficients.data() + 30 * first[tile], p);
    }
    const double* m = this->warp.instance_matrices.data() +
      16 * (tile * mesolens::molecules_per_tile(this->warp) + this->molecule_of_slot[slot]);
    std::array<double, 3> x{};
    for (std::size_t r = 0; r < 3; ++r)
    {
      x[r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
    }
    return x;
  }
};

bool inside(const float* box, const std::array<double, 3>& x, double tolerance)
{
  for (std::size_t d = 0; d < 3; ++d)
  {
    if (x[d] < box[d] - tolerance || x[d] > box[d + 3] + tolerance)
    {
      return false;
    }
  }
  return true;
}

double volume(const float* box)
{
  return double(box[3] - box[0]) * double(box[4] - box[1]) * double(box[5] - box[2]);
}

void expect_boxes_hold_every_atom(const WarpedPatch& patch)
{
  const mesolens::WarpedCellBoxes boxes = mesolens::warped_cell_boxes(
    patch.warp, patch.cells, patch.cell_boxes, patch.slots(), patch.molecule_of_slot);
  const std::size_t cells = patch.cells.cell_count();
  const std::size_t tiles = patch.warp.tile_count();
  ASSERT_EQ(boxes.frames.size(), 12 * tiles);
  ASSERT_EQ(boxes.local.size(), 6 * tiles * cells);
  ASSERT_EQ(boxes.world.size(), 6 * tiles * cells);
  double local_volume = 0;
  double world_volume = 0;
  for (std::size_t tile = 0; tile < tiles; ++tile)
  {
    const double* frame = boxes.frames.data() + 12 * tile;
    for (std::size_t cell = 0; cell < cells; ++cell)
    {
      const std::size_t k = tile * cells + cell;
      local_volume += volume(boxes.local.data() + 6 * k);
      world_volume += volume(boxes.world.data() + 6 * k);
      for (std::uint32_t slot = patch.cells.cell_start[cell];
           slot < patch.cells.cell_start[cell + 1]; ++slot)
      {
        const auto x = patch.warped(tile, slot);
        EXPECT_TRUE(inside(boxes.world.data() + 6 * k, x, 1e-9))
          << "tile " << tile << " slot " << slot;
        // The frame maps local to mesh coordinates by an orthonormal rotation: back by its
        // transpose.
        std::array<double, 3> local{};
        for (std::size_t c = 0; c < 3; ++c)
        {
          for (std::size_t r = 0; r < 3; ++r)
          {
            local[c] += frame[4 * r + c] * (x[r] - frame[4 * r + 3]);
          }
        }
        EXPECT_TRUE(inside(boxes.local.data() + 6 * k, local, 1e-9))
          << "tile " << tile << " slot " << slot;
      }
    }
  }
  // On a curved surface the tiles are tilted: the boxes in their frames are the tighter ones.
  EXPECT_LT(local_volume, 0.8 * world_volume);
}

TEST(WarpedCells, PolynomialBoxesHoldEveryWarpedAtom)
{
  const WarpedPatch patch(mesolens::MappingMethod::Polynomial);
  expect_boxes_hold_every_atom(patch);
}

TEST(WarpedCells, SplitPolynomialBoxesHoldEveryWarpedAtom)
{
  const WarpedPatch patch(mesolens::MappingMethod::Polynomial, 1e-4);
  ASSERT_FALSE(patch.warp.polynomial_splits.empty());
  EXPECT_GT(
    *std::max_element(patch.warp.polynomial_splits.begin(), patch.warp.polynomial_splits.end()), 1);
  expect_boxes_hold_every_atom(patch);
}

TEST(WarpedCells, InstancingBoxesHoldEveryMovedAtom)
{
  const WarpedPatch patch(mesolens::MappingMethod::MoleculeInstancing);
  expect_boxes_hold_every_atom(patch);
}

TEST(WarpedCells, AtomsAreLoadedWarpedTileByTile)
{
  for (const auto method :
       { mesolens::MappingMethod::Polynomial, mesolens::MappingMethod::MoleculeInstancing })
  {
    const WarpedPatch patch(method, method == mesolens::MappingMethod::Polynomial ? 1e-4 : 1.0);
    const std::vector<std::uint8_t> elements(2 * patch.cells.atom_of_slot.size(), 6);
    std::vector<float> radii(128, 0.0f);
    radii[6] = 1.7f;
    const mesolens::WarpedCellAtoms atoms(patch.warp, patch.cells, patch.cell_boxes, patch.slots(),
                                          patch.molecule_of_slot, elements, 2, radii, 1e-6);
    const std::size_t cells = patch.cells.cell_count();
    const std::size_t n = patch.cells.atom_of_slot.size();
    ASSERT_EQ(atoms.cell_count(), 9 * cells);
    EXPECT_EQ(atoms.first_slot(atoms.cell_count()), 9 * n);
    EXPECT_GT(atoms.margin(), 0.0);
    EXPECT_LT(atoms.margin(), 1e-3);
    std::vector<float> xyz, loaded_radii;
    for (std::size_t k = 0; k < atoms.cell_count(); ++k)
    {
      const std::size_t tile = k / cells;
      const std::size_t cell = k % cells;
      ASSERT_EQ(atoms.first_slot(k), tile * n + patch.cells.cell_start[cell]);
      atoms.load(k, xyz, loaded_radii);
      const std::uint32_t first = patch.cells.cell_start[cell];
      ASSERT_EQ(loaded_radii.size(), patch.cells.cell_start[cell + 1] - first);
      for (std::size_t i = 0; i < loaded_radii.size(); ++i)
      {
        const auto x = patch.warped(tile, first + i);
        for (std::size_t d = 0; d < 3; ++d)
        {
          EXPECT_NEAR(xyz[3 * i + d], x[d], 1e-4);
        }
        EXPECT_FLOAT_EQ(loaded_radii[i], float(1.7 + atoms.margin()));
      }
    }
  }
}

TEST(WarpedCells, BadInputIsRefused)
{
  WarpedPatch patch(mesolens::MappingMethod::MoleculeInstancing);
  const std::vector<std::uint8_t> elements(2 * patch.cells.atom_of_slot.size(), 6);
  const std::vector<float> radii(128, 1.0f);
  auto make = [&](const WarpedPatch& p) {
    return mesolens::WarpedCellAtoms(p.warp, p.cells, p.cell_boxes, p.slots(), p.molecule_of_slot,
                                     elements, 2, radii, 0.0);
  };
  EXPECT_NO_THROW(make(patch));
  // Boxes of another number of cells.
  WarpedPatch fewer_boxes = patch;
  fewer_boxes.cell_boxes.resize(fewer_boxes.cell_boxes.size() - 6);
  EXPECT_THROW(make(fewer_boxes), mesolens::InvalidInput);
  // A molecule index beyond tile 0's instances.
  WarpedPatch stray = patch;
  stray.molecule_of_slot[3] = 60000;
  EXPECT_THROW(make(stray), mesolens::InvalidInput);
  // Molecule indices of another count.
  WarpedPatch short_molecules = patch;
  short_molecules.molecule_of_slot.pop_back();
  EXPECT_THROW(make(short_molecules), mesolens::InvalidInput);
  // A displacement mapping has no warp to carry the cells through.
  WarpedPatch displaced = patch;
  displaced.warp.method = mesolens::MappingMethod::Displacement;
  EXPECT_THROW(make(displaced), mesolens::InvalidInput);
  // Matrices missing for a tile.
  WarpedPatch truncated = patch;
  truncated.warp.instance_matrices.resize(truncated.warp.instance_matrices.size() - 16);
  EXPECT_THROW(make(truncated), mesolens::InvalidInput);
}

TEST(WarpedCells, ACollapsedTileStillHoldsItsAtoms)
{
  // A warp that collapses a tile to a point: the frame falls back to the axes and the boxes
  // still hold every atom (a point).
  WarpedPatch patch(mesolens::MappingMethod::Polynomial);
  std::fill(patch.warp.polynomial_coefficients.begin(),
            patch.warp.polynomial_coefficients.begin() + 30, 0.0);
  patch.warp.polynomial_coefficients[0] = 5;
  const mesolens::WarpedCellBoxes boxes = mesolens::warped_cell_boxes(
    patch.warp, patch.cells, patch.cell_boxes, patch.slots(), patch.molecule_of_slot);
  for (std::size_t k = 0; k < patch.cells.cell_count(); ++k)
  {
    for (const float value : { boxes.world[6 * k], boxes.world[6 * k + 3] })
    {
      EXPECT_NEAR(value, 5.0, 1e-6);
    }
    for (std::size_t d = 0; d < 3; ++d)
    {
      EXPECT_TRUE(std::isfinite(boxes.local[6 * k + d]));
    }
  }
}

} // namespace
