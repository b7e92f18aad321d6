// SPDX-License-Identifier: GPL-3.0-or-later
// The geodesic disk of the membrane-mapping paper: the part of a surface within geodesic
// distance r of a picked point, cut exactly on the isoline d = r.
#pragma once

#include "mesolens/mapping/cell_surface.h"
#include "mesolens/mapping/geodesic_distance.h"
#include "mesolens/mapping/surface_chart.h"
#include "mesolens/mesh/triangle_mesh.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace mesolens {

/// The smallest disk radius geodesic_disk() takes, as a fraction of the mesh's size (the larger
/// of its bounding diagonal and the seed's largest coordinate): smaller disks have no digits
/// left for their triangles.
constexpr double smallest_relative_disk_radius = 1e-9;

/// Parameters of geodesic_disk().
struct GeodesicDiskParams
{
  /// Geodesic radius r, mesh units. Must be finite and at least smallest_relative_disk_radius
  /// times the mesh's size; no default (0, the initial value, is rejected).
  double radius = 0;
  /// Resolution: triangles of the surface that come within r of the seed and are longer than
  /// the edge giving about this many triangles in a flat disk of radius r (r sqrt(4 pi / n)) are
  /// bisected, their new vertices placed on the smooth surface (SmoothSurface), so a disk on a
  /// coarse mesh holds at least about this many triangles. Finer input is used as it is. 0: no
  /// refinement. Default 2000.
  std::size_t min_triangles = 2000;
  /// Speed on fine meshes: when more than this many of the input's triangles lie within r of
  /// the seed, the disk is grown on the finest coarser copy of the surface (CellSurface) where
  /// fewer do, and its points are placed on the input surface. 0: always the input's
  /// triangles. Default 16000.
  std::size_t max_triangles = 16000;
};

/// A geodesic disk: a triangle mesh that is a topological disk (one boundary loop, Euler
/// characteristic 1) whose boundary lies on the isoline d = radius. Its vertices lie on the
/// surface's smooth interpolant, and each triangle knows the input triangle it lies in, so any
/// point of it can be placed exactly on that smooth surface.
struct GeodesicDisk
{
  TriangleMesh mesh;
  std::vector<double> distance;              ///< per disk vertex: geodesic distance, mesh units
  std::vector<double> normals;               ///< per disk vertex: 3 components, the smooth
                                             ///< surface's unit normal
  std::vector<std::int64_t> original_vertex; ///< per disk vertex: input vertex id, -1 if new
  std::vector<std::int64_t> nearby_triangle; ///< per disk vertex: an input triangle at or near
                                             ///< it, where lookups on the input start; -1 for
                                             ///< points made by the cut
  std::vector<std::int64_t> source_triangle; ///< per disk triangle: the triangle of the surface
                                             ///< copy it was grown on that it lies in
  std::vector<double> source_barycentric;    ///< per disk triangle: 9, its corners' barycentric
                                             ///< coordinates in that input triangle
  SurfacePoint seed;                         ///< the picked point, on the disk mesh
  int refinement_levels = 0;                 ///< most times a surface triangle was halved
  std::size_t surface_level = 0;             ///< the copy of the surface it was grown on: 0 the
                                             ///< input, k its k-th coarser copy
  std::size_t holes_closed = 0;              ///< regions farther than the radius that the disk
                                             ///< encloses (a bump's top), taken with their own
                                             ///< triangles
};

/// Grows the geodesic disk of `params.radius` around `seed` (a point on surface.mesh()) on the
/// local surface around it (only triangles within the radius are visited). Throws InvalidInput
/// for a bad radius or seed, SolverFailure when the mesh is too coarse and curved around the
/// seed for the radius (bisection would add more than max(2e5, 100 min_triangles) triangles:
/// subdivide the mesh or choose a larger radius), and TopologyError (with a message saying
/// where) when the disk reaches a boundary of the mesh, wraps a handle or covers a whole closed
/// component (radius too large), or is not a manifold disk. Deterministic.
GeodesicDisk geodesic_disk(const CellSurface& surface, const SurfacePoint& seed,
                           const GeodesicDiskParams& params);

/// The placement (for SurfaceChart) that puts a point of `disk` on `surface`'s smooth
/// interpolant: directly for a disk grown on the input's triangles; for one grown on a coarser
/// copy, the copy's smooth point moved along the copy's normal onto the input. Keeps a copy of what
/// it needs of the disk; `surface` must outlive it.
SurfacePlacement smooth_placement(const GeodesicDisk& disk, const CellSurface& surface);

} // namespace mesolens
