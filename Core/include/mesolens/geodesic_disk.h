// SPDX-License-Identifier: GPL-3.0-or-later
// The geodesic disk of the membrane-mapping paper: the part of a surface within geodesic
// distance r of a picked point, cut exactly on the isoline d = r.
#pragma once

#include "mesolens/geodesic_distance.h"
#include "mesolens/triangle_mesh.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace mesolens {

/// Parameters of geodesic_disk().
struct GeodesicDiskParams
{
  /// Geodesic radius r, mesh units. Must be > 0 and finite.
  double radius = 0;
  /// A disk with fewer triangles is refined: the surrounding region is Loop-subdivided (as the
  /// paper's meshes were) and the disk grown again, until it holds at least this many triangles
  /// or max_refinement_levels is reached. 0 disables refinement. Default 2000.
  std::size_t min_triangles = 2000;
  /// Most Loop subdivision levels applied to the region. Range [0, 8]; default 5.
  int max_refinement_levels = 5;
};

/// A geodesic disk: a triangle mesh that is a topological disk (one boundary loop, Euler
/// characteristic 1) whose boundary lies on the isoline d = radius.
struct GeodesicDisk
{
  TriangleMesh mesh;
  std::vector<double> distance;              ///< per disk vertex: geodesic distance, mesh units
  std::vector<std::int64_t> original_vertex; ///< per disk vertex: input vertex id, -1 if new
  SurfacePoint seed;                         ///< the picked point, on the disk mesh
  int refinement_levels = 0;                 ///< Loop subdivision levels applied
  std::size_t holes_closed = 0;              ///< small holes left by the front and filled (loops
                                             ///< shorter than 1/4 of the outer boundary)
};

/// Grows the geodesic disk of `params.radius` around `seed` (a point on solver.mesh()).
/// Throws InvalidInput for a bad radius or seed, and TopologyError (with a message saying where)
/// when the disk reaches a boundary of the mesh, wraps a handle or covers a whole closed
/// component (radius too large), or is not a manifold disk.
GeodesicDisk geodesic_disk(const GeodesicSolver& solver, const SurfacePoint& seed,
                           const GeodesicDiskParams& params);

} // namespace mesolens
