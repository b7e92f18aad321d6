// SPDX-License-Identifier: GPL-3.0-or-later
// Membrane mapping (Waltemate, Sommer and Botsch, VCBM 2014): a membrane patch, tiled k x k,
// placed in the shell around a parameterized surface region.
#pragma once

#include "mesolens/common/parallel_for.h"
#include "mesolens/common/point_span.h"
#include "mesolens/mapping/mapping_method.h"
#include "mesolens/mapping/polynomial_warp.h"
#include "mesolens/mapping/surface_chart.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace mesolens {

/// A membrane patch in its own frame. Its periodic cell is spanned by the in-plane vectors a and
/// b from `origin` (membrane units, e.g. Å); heights are measured from the bilayer centre.
struct MembranePatch
{
  PointSpan<const float> positions;  ///< one per atom, membrane units
  const int* molecule_ids = nullptr; ///< per atom, >= 0; needed by MoleculeInstancing
  const float* masses = nullptr;     ///< per atom; null: centroids instead of centres of mass
  std::array<double, 2> origin{ { 0, 0 } };
  std::array<double, 2> a{ { 0, 0 } }; ///< first cell vector (x, y), membrane units
  std::array<double, 2> b{ { 0, 0 } }; ///< second cell vector (x, y), membrane units
  double centre_height = 0;            ///< z of the bilayer centre, membrane units

  std::size_t atom_count() const
  {
    return this->positions.size();
  }
};

/// Parameters of map_membrane().
struct MappingParams
{
  /// How atoms are carried onto the surface. Default Displacement.
  MappingMethod method = MappingMethod::Displacement;
  /// k: the patch is repeated k x k times (by its cell vectors). Range >= 1; default 1.
  int tiles = 1;
  /// Mesh units per membrane unit (e.g. 1e-4 for Å onto a mesh in µm, 0.1 for Å onto nm).
  /// > 0; default 1.
  double scale = 1;
  /// (u, v) where the centre of the tiled region goes: the picked point's. Default (0, 0).
  std::array<double, 2> centre_uv{ { 0, 0 } };
  /// Polynomial: the fit samples heights -e, 0, +e (membrane units). > 0; default 25 Å (about
  /// half a bilayer).
  double layer_half_thickness = 25;
  /// Polynomial: samples per tile edge (samples x samples per layer). Range >= 3; default 6
  /// (the paper's 6 x 6).
  int samples = 6;
  /// Polynomial: the largest fit residual accepted in a tile, membrane units (Å for Å patches).
  /// A tile whose largest sample residual exceeds it is split into 2 x 2 pieces, each with its
  /// own polynomial, then 4 x 4 ... up to max_polynomial_splits pieces per side; a tile still
  /// above it has its atoms mapped by displacement (tile_fallback). <= 0: no bound. Default
  /// 1 Å, which keeps the polynomial's mid-sheet within 1 Å of the surface.
  double max_polynomial_residual = 1.0;
  /// Polynomial: most pieces per tile side, a power of two in [1, 8]. Default 4.
  int max_polynomial_splits = 4;
  /// Atoms whose (u, v) falls outside the chart are dropped with their molecule (atom_mapped)
  /// instead of failing the mapping: a tile cut to the disk. Default false.
  bool cut_to_disk = false;
  /// Polynomial and MoleculeInstancing: also map every atom (false: only the coefficients or
  /// matrices, for a renderer that evaluates them itself; positions stay empty). Displacement
  /// always maps the atoms. Default true.
  bool map_atoms = true;
  /// The tiles whose atoms are mapped: [first_atom_tile, end_atom_tile) in tile order
  /// (t = j k + i); end -1: through the last tile. The coefficients and matrices are computed
  /// for every tile (they are small); only the atoms, the costly part, are limited, so that
  /// processes can share the atoms of many tiles. 0 <= first <= end <= k^2; default all tiles.
  int first_atom_tile = 0;
  int end_atom_tile = -1;
};

/// The mapped atoms and what each method leaves for the renderer. Tile t = j k + i holds the
/// patch shifted by i a + j b.
struct MappedMembrane
{
  std::vector<double> positions;   ///< 3 per atom per tile of the atom tiles (all by default);
                                   ///< tile first_atom_tile + t: atoms [t n, (t+1) n) (double:
                                   ///< Å-sized bonds on µm meshes need it); empty when
                                   ///< params.map_atoms is false (not for Displacement)
  std::size_t first_atom_tile = 0; ///< the tile of the first block of positions
  std::vector<double> instance_matrices;       ///< MoleculeInstancing: 16 per instance (row-major
                                               ///< 4x4, patch coordinates to mesh coordinates)
  std::vector<int> instance_molecules;         ///< molecule id of each instance
  std::vector<int> instance_tiles;             ///< tile of each instance
  std::vector<double> polynomial_coefficients; ///< Polynomial: 30 (QuadraticWarp) per piece;
                                               ///< tile t's m_t x m_t pieces from piece
                                               ///< polynomial_first_piece[t], its piece (i, j)
                                               ///< at j m_t + i
  std::vector<int> polynomial_splits;          ///< Polynomial: per tile, m_t, its pieces per side
  std::vector<std::size_t> polynomial_first_piece; ///< Polynomial: per tile, and the total
  std::vector<double> polynomial_rms_residual;     ///< Polynomial: per tile (largest over its
                                                   ///< pieces), mesh units
  std::vector<double> polynomial_max_residual;     ///< Polynomial: per tile, mesh units
  std::vector<std::uint8_t> tile_fallback; ///< Polynomial: per tile, 1 when no polynomial met
                                           ///< the residual bound and atoms were displaced
  std::vector<std::uint8_t> atom_mapped;   ///< cut_to_disk: per atom per atom tile, 0 where the
                                           ///< atom was dropped (its position is NaN);
                                           ///< empty otherwise
};

/// The polynomial's local coordinates of a patch point: (s, t) = 2 f - 1 where f are the
/// fractional coordinates of (x, y) - origin in the basis (a, b), and h = (z - centre) / e.
/// The renderer computes the same from atom positions, so the warp of a tile applies to every
/// atom of the patch.
std::array<double, 3> polynomial_coordinates(const MembranePatch& patch,
                                             double layer_half_thickness, const float* position);

/// The piece of a tile split m x m that tile coordinates (s, t) fall in, and the piece's own
/// (s, t) in [-1, 1] (points outside the tile go to the nearest piece, extrapolated). Returns
/// the piece index j m + i.
int polynomial_piece(int splits, double& s, double& t);

/// Where a tile's polynomial takes patch point `position`: the piece's warp evaluated at the
/// piece's coordinates (the CPU twin of the renderer's vertex shader). `coefficients` holds
/// the tile's `splits` x `splits` pieces.
std::array<double, 3> evaluate_tile_polynomial(const MembranePatch& patch,
                                               double layer_half_thickness, int splits,
                                               const double* coefficients, const float* position);

/// The largest distance from the patch's cell centre (in x, y, membrane units) of any atom of
/// k x k tiles: the geodesic radius below which some atoms cannot fit in the disk.
double tiled_extent(const MembranePatch& patch, int tiles);
/// Maps the patch onto the chart, k x k tiles centred at params.centre_uv. Throws InvalidInput
/// for bad parameters, a degenerate cell, missing molecule ids (instancing), non-finite
/// coordinates, or an atom whose (u, v) falls outside the chart (the geodesic disk is too
/// small: its radius should be twice the tiled width; OutsideChart, unless cut_to_disk). Runs
/// through `parallel_for` per tile; the result does not depend on the threads.
MappedMembrane map_membrane(const SurfaceChart& chart, const MembranePatch& patch,
                            const MappingParams& params, const ParallelFor& parallel_for = {});

/// Relative length change of each bond in each tile: |mapped| / (scale |patch|) - 1, tile-major
/// (tile t: values [t bonds, (t+1) bonds)). `bonds` holds atom index pairs into the patch.
std::vector<double> bond_length_changes(const MembranePatch& patch, const MappedMembrane& mapped,
                                        const std::vector<std::array<std::uint32_t, 2>>& bonds,
                                        double scale);

} // namespace mesolens
