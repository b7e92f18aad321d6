// SPDX-License-Identifier: GPL-3.0-or-later
// Topological and geometric sanity report of a triangle mesh.
#pragma once

#include "mesolens/common/point_span.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace mesolens {

/// Read-only view of a triangle mesh: vertex positions and triangles (3 vertex indices each).
struct TriangleMeshView
{
  PointSpan<const double> points;
  const std::int64_t* triangles = nullptr;
  std::size_t triangle_count = 0;
};

/// What mesh_report() found. Counts refer to the input indices.
struct MeshReport
{
  std::size_t vertices = 0;              ///< points of the mesh
  std::size_t triangles = 0;             ///< triangles of the mesh
  std::size_t edges = 0;                 ///< unique undirected edges
  std::size_t boundary_edges = 0;        ///< edges with one triangle
  std::size_t boundary_loops = 0;        ///< closed boundary curves
  std::size_t non_manifold_edges = 0;    ///< edges with more than two triangles
  std::size_t non_manifold_vertices = 0; ///< vertices whose triangle fan is not one disk/half-disk
  std::size_t inconsistently_oriented_edges = 0; ///< interior edges used twice in one direction
  std::size_t degenerate_triangles = 0;          ///< repeated vertex or area < area_epsilon
  std::size_t unreferenced_vertices = 0;         ///< points used by no triangle
  std::size_t invalid_triangles = 0;             ///< an index out of range or a non-finite vertex
  std::size_t components = 0;                    ///< edge-connected triangle components
  long euler_characteristic = 0;                 ///< V - E + F over referenced vertices
  std::vector<std::uint8_t> triangle_is_degenerate; ///< per triangle, 1 = degenerate or invalid
  std::vector<std::uint8_t> vertex_is_non_manifold; ///< per vertex, 1 = non-manifold

  /// A closed, consistently oriented 2-manifold without degenerate triangles.
  bool is_closed_manifold() const;
  /// A 2-manifold (boundary allowed) without degenerate or invalid triangles.
  bool is_manifold() const;
  /// One line per defect found, e.g. "4 boundary edges in 1 loop"; empty when clean.
  std::string describe_defects() const;
};

/// Analyses the mesh. Degenerate means two equal indices or an area below
/// area_epsilon × (mean edge length)² (default 1e-12, relative). Invalid triangles (index out of
/// range, non-finite point) are counted and excluded from the topology. O(F log F).
MeshReport mesh_report(const TriangleMeshView& mesh, double area_epsilon = 1e-12);

} // namespace mesolens
