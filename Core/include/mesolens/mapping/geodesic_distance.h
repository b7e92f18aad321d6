// SPDX-License-Identifier: GPL-3.0-or-later
// Geodesic distances on triangle meshes by fast marching (Kimmel and Sethian, "Computing
// geodesic paths on manifolds", PNAS 1998), as the membrane-mapping paper grows its disks.
#pragma once

#include "mesolens/mesh/triangle_mesh.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace mesolens {

/// Distances of the vertices reached by one march, in the order they became final (increasing
/// distance). Vertices not listed are farther than the march went.
struct GeodesicField
{
  std::vector<std::uint32_t> vertices;
  std::vector<double> distances; ///< mesh units, same order as `vertices`

  /// Per-vertex distances for a mesh of `vertex_count` vertices; +infinity where not reached.
  std::vector<double> dense(std::size_t vertex_count) const;
};

/// Fast marching on one mesh, set up once and run for any seed and radius.
///
/// Each triangle corner is updated from its two neighbours with the exact planar solution for a
/// point source (the seed seen through the unfolded strip), falling back to edge updates when the
/// source lies outside the corner's wedge. Obtuse corners, where fast marching loses accuracy,
/// are split as Kimmel and Sethian propose: the triangles across the opposite edge are unfolded
/// into the corner's plane until a vertex falls inside the obtuse angle, and that vertex joins the
/// update through a virtual edge. Distances from a point source on a plane are exact; on a sphere
/// subdivided to ~80 k triangles the error is below 1 % up to 90 degrees (see the tests).
///
/// Construction is O(F) (corner stencils, vertex-to-stencil index, a search tree for seeds);
/// distances() touches only the vertices it reaches. Not thread-safe for concurrent calls.
class GeodesicSolver
{
public:
  /// Throws TopologyError for a non-manifold or degenerate mesh, InvalidInput for an empty one.
  explicit GeodesicSolver(TriangleMesh mesh);
  ~GeodesicSolver();
  GeodesicSolver(const GeodesicSolver&) = delete;
  GeodesicSolver& operator=(const GeodesicSolver&) = delete;

  const TriangleMesh& mesh() const;

  /// The surface point closest to `point` (mesh units); `distance` gets how far it is.
  SurfacePoint closest_point(const std::array<double, 3>& point, double* distance = nullptr) const;

  /// Marches from `seed` (a point inside a triangle, or on its edges) until every vertex closer
  /// than `stop_distance` (mesh units, > 0) is final. Throws InvalidInput for a seed outside the
  /// mesh's triangles or a non-positive or non-finite distance.
  GeodesicField distances(const SurfacePoint& seed, double stop_distance) const;

  /// Length of the longest mesh edge (mesh units).
  double longest_edge() const;

  /// True when the vertex lies on a boundary edge of the mesh (the mesh is open there).
  bool on_boundary(std::uint32_t vertex) const;

private:
  struct Impl;
  std::unique_ptr<Impl> Internal;
};

} // namespace mesolens
