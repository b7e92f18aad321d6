// SPDX-License-Identifier: GPL-3.0-or-later
// What a membrane mapping hands on to whoever draws it: the contract between the mapping filter
// and the atom mapper (written into VTK data and read back by vtkMesoMembraneWarp).
#pragma once

#include "mesolens/common/parallel_for.h"
#include "mesolens/mapping/mapping_method.h"
#include "mesolens/mapping/membrane_mapping.h"
#include "mesolens/molecules/molecule_groups.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace mesolens {

struct MapResult;
struct MapRequest;

/// One mapping of a membrane patch: the patch's frame, the k x k tiling, what was mapped, and
/// the method's per-tile polynomials or per-molecule rigid motions, from which a renderer warps
/// the patch's own atoms tile by tile (the atoms themselves are not part of it). Tile t = j k + i
/// holds the patch shifted by i a + j b.
struct MembraneWarp
{
  MappingMethod method = MappingMethod::Displacement;
  int tiles = 0;            ///< k mapped (k x k tiles); 0: nothing mapped
  int tiles_requested = 0;  ///< k asked for
  bool cut_to_disk = false; ///< a single tile cut to the disk: molecules outside it dropped, so
                            ///< only the mapped atoms, not a warp of the patch, show it
  std::string note;         ///< what was mapped instead of what was asked, and why; or empty
  double scale = 1;         ///< mesh units per membrane unit

  // The patch's frame (MembranePatch without its atoms), membrane units.
  std::array<double, 2> origin{ { 0, 0 } };
  std::array<double, 2> a{ { 0, 0 } }; ///< first cell vector (x, y)
  std::array<double, 2> b{ { 0, 0 } }; ///< second cell vector (x, y)
  double centre_height = 0;            ///< z of the bilayer centre
  double layer_half_thickness = 25;    ///< e of the polynomial coordinate h = (z - centre) / e

  // Where it lies on the surface.
  double geodesic_radius = 0;                       ///< of the disk mapped onto, mesh units
  std::array<double, 2> seed_uv{ { 0, 0 } };        ///< the picked point in (u, v)
  std::array<double, 3> seed_normal{ { 0, 0, 0 } }; ///< the surface's unit normal there: where
                                                    ///< the patch's +z (heights) go
  int refinement_levels = 0; ///< the disk's triangle bisections (GeodesicDisk)

  // Polynomial (see MappedMembrane): 30 per piece, pieces per side per tile, residuals per tile
  // (mesh units) and tiles whose atoms were displaced instead.
  std::vector<double> polynomial_coefficients;
  std::vector<int> polynomial_splits;
  std::vector<double> polynomial_rms_residual;
  std::vector<double> polynomial_max_residual;
  std::vector<std::uint8_t> tile_fallback;

  // MoleculeInstancing: 16 per instance (row-major 4 x 4, patch to mesh coordinates), and each
  // instance's molecule id and tile; tile 0's instances first, in the same molecule order as
  // every other tile's.
  std::vector<double> instance_matrices;
  std::vector<int> instance_molecules;
  std::vector<int> instance_tiles;

  /// Tiles that are no k x k grid of a patch (an assembly's copies drawn by instancing, one
  /// tile per copy); 0: `tiles` x `tiles`.
  std::size_t copy_tiles = 0;

  /// k x k, or copy_tiles.
  std::size_t tile_count() const
  {
    return this->copy_tiles > 0 ? this->copy_tiles
                                : std::size_t(this->tiles) * std::size_t(this->tiles);
  }
  /// The frame as a MembranePatch without atoms (for polynomial_coordinates()).
  MembranePatch frame() const;
};

/// The warp of a mapping: `patch` is the patch that was mapped, `request` what was asked. From
/// an rvalue result the method's arrays (matrices, coefficients) are moved, not copied: a
/// mapping for the GPU hands them on once per frame.
MembraneWarp membrane_warp(const MapResult& result, const MembranePatch& patch,
                           const MapRequest& request);
MembraneWarp membrane_warp(MapResult&& result, const MembranePatch& patch,
                           const MapRequest& request);

/// Per tile of a polynomial warp, the index of its first piece, and the total number of pieces
/// at the end (tile_count() + 1 values; polynomial_splits absent: one piece per tile). Throws
/// InvalidInput unless every tile has 1 to 64 pieces per side and the coefficients hold 30 per
/// piece.
std::vector<std::size_t> polynomial_first_pieces(const MembraneWarp& warp);

/// Throws InvalidInput, saying why, unless a renderer can warp the patch by `warp` from the
/// patch's atoms alone: at least one tile, a positive layer thickness and a non-degenerate cell,
/// not cut to the disk, and the Polynomial coefficients or the MoleculeInstancing matrices of
/// every tile (Displacement has no such form: its mapped atoms are drawn directly).
void check_drawable(const MembraneWarp& warp);

/// Molecules per tile of a MoleculeInstancing warp: the instances of tile 0.
std::size_t molecules_per_tile(const MembraneWarp& warp);

/// Where a renderer that warps `patch` by `warp` puts its molecules: per tile t and molecule m
/// of `groups` (the patch's molecules; for MoleculeInstancing in the order of its instances), the
/// mean of the molecule's warped atom positions (mesh units), computed as from the atoms the
/// mapping maps on the CPU (the same arithmetic, so a cut of these centres decides as a cut of
/// the mapped atoms does): 3 values per molecule, tile-major. Throws InvalidInput unless `warp`
/// is drawable (check_drawable) and `groups` groups the patch's atoms, with, for
/// MoleculeInstancing, as many molecules as the warp has per tile.
std::vector<double> warped_molecule_centres(const MembraneWarp& warp, const MembranePatch& patch,
                                            const MoleculeGroups& groups,
                                            const ParallelFor& parallel_for = {});

} // namespace mesolens
