// SPDX-License-Identifier: GPL-3.0-or-later
// The whole membrane-mapping chain for one cell surface (Waltemate, Sommer and Botsch, VCBM
// 2014): a click's geodesic disk, its parameterization and chart, and the mapping, with what is
// expensive kept between clicks and frames. The filter, the viewer and the benchmarks all map
// through it.
#pragma once

#include "mesolens/mapping/cell_surface.h"
#include "mesolens/mapping/geodesic_disk.h"
#include "mesolens/mapping/harmonic_parameterization.h"
#include "mesolens/mapping/membrane_mapping.h"
#include "mesolens/mapping/surface_chart.h"

#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace mesolens {

/// A geodesic disk with its parameterization and the chart built on them.
struct MappingChart
{
  GeodesicDisk disk;
  DiskParameterization parameterization;
  SurfaceChart chart;
  std::array<double, 2> seed_uv{}; ///< where the picked point lies in (u, v)
  double radius = 0;               ///< geodesic radius, mesh units
  /// The disk's triangles by how near they come to seed_uv in (u, v), and the largest linear
  /// stretch among those up to each (see largest_stretch_within).
  std::vector<double> stretch_radius;
  std::vector<double> stretch_prefix_max;

  /// The largest factor by which the parameterization stretches or shrinks a length (its
  /// Jacobian's singular values s1 >= s2: max(s1, 1 / s2)) over the triangles that come within
  /// `uv_radius` of seed_uv in (u, v); 1 for an isometry.
  double largest_stretch_within(double uv_radius) const;
};

/// What a click asks for.
struct MapRequest
{
  /// Method, k (tiles), scale, polynomial settings and whether atoms are mapped; centre_uv and
  /// cut_to_disk are set by the mapper.
  MappingParams mapping;
  /// The disk's radius over the tiled width d (the paper's r = 2 d). Range [0.8, 10]; default 2.
  double radius_factor = 2;
  /// The largest linear stretch (MappingChart::largest_stretch_within) accepted where the tiles
  /// lie: a disk that distorts them more (say, one that covers most of a small organelle and
  /// squeezes its far side into the rim) does not fit. > 1; default 1.5.
  double max_stretch = 1.5;
  /// Resolution of the disk (GeodesicDiskParams::min_triangles): refine coarse surface
  /// triangles until the disk holds at least about this many. 0: no refinement. Default 2000.
  std::size_t min_disk_triangles = 2000;
  /// Disks over more of the input's triangles than this grow on a coarser copy of the surface
  /// (GeodesicDiskParams::max_triangles). 0: always the input's triangles. Default 16000.
  std::size_t max_disk_triangles = 16000;
  /// When the asked k x k tiles do not fit (their disk wraps a handle, meets the mesh's
  /// boundary, covers the whole component, or the tiles leave it), map the largest k that fits,
  /// then a single tile cut to the largest disk that fits. false: fail instead. Default true.
  bool fit_what_fits = true;
  /// This process's share of the mapped atoms, for many processes: of the k^2 tiles actually
  /// mapped, piece p of P maps the atoms of tiles [k^2 p / P, k^2 (p + 1) / P) (see
  /// MappingParams::first_atom_tile); the chart, coefficients and matrices are every piece's.
  /// 0 <= piece < pieces; default piece 0 of 1 (all atoms).
  int piece = 0;
  int pieces = 1;
};

/// What a click got.
struct MapResult
{
  MappedMembrane mapped;
  int tiles_asked = 0;
  int tiles_mapped = 0;     ///< k actually mapped (<= tiles_asked)
  bool cut_to_disk = false; ///< a single tile cut to the disk (MappedMembrane::atom_mapped)
  std::string note;         ///< what was mapped instead of what was asked, and why; empty when
                            ///< the request was met
  std::shared_ptr<const MappingChart> chart;
};

/// The mapping chain of one surface. Construction prepares the surface (CellSurface); map()
/// grows, parameterizes and charts the disk for a seed and radius once and keeps the most
/// recent ones, so a new frame or method on the same click costs only the mapping. Results are
/// bitwise identical run to run and for any ParallelFor. Calls may come from one thread at a
/// time.
class MembraneMapper
{
public:
  /// Throws as CellSurface does.
  explicit MembraneMapper(TriangleMesh surface);
  ~MembraneMapper();
  MembraneMapper(const MembraneMapper&) = delete;
  MembraneMapper& operator=(const MembraneMapper&) = delete;

  const CellSurface& surface() const;

  /// The surface point closest to `point` (mesh units). Throws InvalidInput when it is farther
  /// than `tolerance` (<= 0: 2 % of the surface's bounding-box diagonal) or not finite.
  SurfacePoint seed_near(const std::array<double, 3>& point, double tolerance = 0) const;

  /// The chart of the geodesic disk of `radius` around `seed` (cached), its u axis along the
  /// mesh's x axis seen in the tangent plane at the seed (y where the surface faces x), so a
  /// patch's orientation depends on the click, not on the disk's triangles. Throws TopologyError
  /// when that disk is not a disk (see geodesic_disk()), SolverFailure when it cannot be
  /// parameterized.
  std::shared_ptr<const MappingChart> chart(const SurfacePoint& seed, double radius,
                                            std::size_t min_disk_triangles = 2000,
                                            std::size_t max_disk_triangles = 16000) const;

  /// Drops the kept charts (the next map() grows its disk again: for timings).
  void forget_charts() const;

  /// Maps `patch` around `seed` as `request` asks, or what fits of it (MapRequest::fit_what_fits).
  /// Throws InvalidInput for bad parameters or patches, TopologyError when not even one lipid's
  /// footprint around the seed is a disk of the surface (or, without fit_what_fits, when the
  /// asked disk is not one), OutsideChart when the tiles leave a disk that is one.
  MapResult map(const SurfacePoint& seed, const MembranePatch& patch, const MapRequest& request,
                const ParallelFor& parallel_for = {}) const;

private:
  struct Impl;
  struct FitSearch;
  std::unique_ptr<Impl> Internal;
};

/// The larger cell vector's length, membrane units: the width d of one tile.
double patch_width(const MembranePatch& patch);

} // namespace mesolens
