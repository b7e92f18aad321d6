// SPDX-License-Identifier: GPL-3.0-or-later
// A cell-component surface prepared once for any number of clicks: the membrane-mapping chain
// (geodesic disk, parameterization, chart) reads it for every seed.
#pragma once

#include "mesolens/mapping/smooth_surface.h"
#include "mesolens/mesh/triangle_mesh.h"

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace mesolens {

namespace detail {
struct SurfaceLevel;
}

/// Which triangles touch which: the triangle across each edge and the triangles around each
/// vertex.
struct MeshAdjacency
{
  /// 3 per triangle: the triangle across edge (corner k, corner k+1), -1 on a boundary.
  std::vector<std::int64_t> across;
  /// Triangles around vertex v: vertex_triangles[vertex_start[v] .. vertex_start[v + 1]).
  std::vector<std::size_t> vertex_start;
  std::vector<std::int64_t> vertex_triangles;
};

/// The edge adjacency of a manifold triangle mesh (each edge in at most two triangles).
MeshAdjacency mesh_adjacency(const TriangleMesh& mesh);

/// The surface a membrane is mapped onto: the input mesh (any genus, any triangle size, any
/// unit; a consistently oriented 2-manifold, boundary allowed, without degenerate triangles),
/// its smooth interpolant (SmoothSurface, which every mapped point lies on), its adjacency and
/// a closest-point index; for meshes of more than coarse_copies_above triangles also coarser
/// copies of it, on which disks too large for the input's resolution are grown. Building is
/// O(F log F) (the coarser copies, by quadric simplification, cost about a second per million
/// triangles); the index is built on first use. Queries are const and thread-safe.
class CellSurface
{
public:
  /// Throws InvalidInput (no triangles, a non-finite point) or TopologyError (not a clean
  /// 2-manifold: the defects mesh_report() finds, phrased as it phrases them).
  explicit CellSurface(TriangleMesh mesh);
  ~CellSurface();
  CellSurface(const CellSurface&) = delete;
  CellSurface& operator=(const CellSurface&) = delete;

  const TriangleMesh& mesh() const;
  const SmoothSurface& smooth() const;
  const MeshAdjacency& adjacency() const;
  /// Diagonal of the mesh's bounding box, mesh units.
  double bounding_diagonal() const;

  /// The point of the mesh closest to `point`; `distance` gets how far it is (mesh units).
  SurfacePoint closest_point(const std::array<double, 3>& point, double* distance = nullptr) const;

  /// Meshes with more triangles than this get coarser copies.
  static constexpr std::size_t coarse_copies_above = 16000;
  /// The input (0) and its coarser copies (1, 2, ...: a quarter of the vertices each), for
  /// Core's own algorithms.
  std::size_t level_count() const;
  const detail::SurfaceLevel& level(std::size_t index) const;

private:
  struct Impl;
  std::unique_ptr<Impl> Internal;
};

} // namespace mesolens
