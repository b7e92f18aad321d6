// SPDX-License-Identifier: GPL-3.0-or-later
// The part of a cell surface around a seed, as a mesh fine enough for a geodesic disk (private).
#pragma once

#include "mapping/detail/surface_levels.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace mesolens {
namespace detail {

/// The input triangles within `reach` of a seed, with those coarser than `target_edge` bisected
/// (longest edge first, conforming: Rivara's LEPP) and every new vertex placed on the smooth
/// surface. Only triangles that come within reach are refined, so the work depends on the reach
/// over the target edge, not on the size of the input's triangles (beyond a logarithm).
struct LocalSurface
{
  TriangleMesh mesh;
  std::vector<double> normals;               ///< 3 per vertex: the smooth surface's normal
  std::vector<std::int64_t> original_vertex; ///< per vertex: input vertex, -1 if new
  std::vector<std::int64_t> source_triangle; ///< per triangle: the input triangle it lies in
  std::vector<double> source_barycentric;    ///< 9 per triangle: its corners in that triangle
  SurfacePoint seed;                         ///< the seed, on `mesh`
  int bisection_depth = 0;                   ///< most halvings any triangle went through
  /// More than LocalSurfaceParams::max_region input triangles lie within reach: nothing else
  /// is set.
  bool region_too_large = false;
};

/// Sizes of local_surface(), mesh units.
struct LocalSurfaceParams
{
  /// Triangles farther than this from the seed (straight-line distance, which never exceeds
  /// the geodesic one) are left out. > 0.
  double reach = 0;
  /// Triangles within reach whose longest edge exceeds this are bisected; <= 0: none.
  double target_edge = 0;
  /// With more input triangles than this within reach (> 0), local_surface() stops there
  /// and reports region_too_large; 0: no such limit.
  std::size_t max_region = 0;
  /// Gathering and refinement stop with SolverFailure beyond this many triangles (a safeguard).
  std::size_t max_triangles = 2000000;
  /// Refinement stops with SolverFailure once bisection has added more triangles than this
  /// (on coarse, strongly curved meshes the patches' bulge bound keeps far triangles "within
  /// reach" and bisection would cover them all); 0: only max_triangles applies.
  std::size_t max_new_triangles = 0;
};

/// The local surface around `seed` (a point of surface.mesh()), with new vertices on its smooth
/// interpolant; "input" above means this copy of the surface. The region is edge-connected to
/// the seed's triangle and a manifold: a vertex whose triangles would form several fans gets
/// all of them. Deterministic.
LocalSurface local_surface(const SurfaceLevel& surface, const SurfacePoint& seed,
                           const LocalSurfaceParams& params);

} // namespace detail
} // namespace mesolens
