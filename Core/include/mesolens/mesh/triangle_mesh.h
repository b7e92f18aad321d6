// SPDX-License-Identifier: GPL-3.0-or-later
// A plain triangle mesh (the cell-component surfaces), and points on it.
#pragma once

#include "mesolens/mesh/mesh_report.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace mesolens {

/// Vertex positions (3 per vertex, mesh units) and triangles (3 vertex indices each, counter-
/// clockwise seen from outside, so normals point out).
struct TriangleMesh
{
  std::vector<double> points;
  std::vector<std::int64_t> triangles;

  std::size_t vertex_count() const
  {
    return this->points.size() / 3;
  }
  std::size_t triangle_count() const
  {
    return this->triangles.size() / 3;
  }
  std::array<double, 3> point(std::int64_t vertex) const
  {
    const std::size_t i = 3 * static_cast<std::size_t>(vertex);
    return { this->points[i], this->points[i + 1], this->points[i + 2] };
  }
  /// The view mesh_report() takes.
  TriangleMeshView view() const;
};

/// A point on a mesh: a triangle and barycentric coordinates (weights of its three vertices,
/// summing to 1), with the 3D position they give.
struct SurfacePoint
{
  std::int64_t triangle = -1;
  std::array<double, 3> barycentric{ { 1.0 / 3, 1.0 / 3, 1.0 / 3 } };
  std::array<double, 3> position{};
};

/// Throws TopologyError naming `what` and the defects (mesh_report()) unless the mesh is a
/// consistently oriented 2-manifold (boundary allowed) without degenerate or invalid triangles;
/// InvalidInput when it has no triangles or a non-finite point.
void require_manifold(const TriangleMesh& mesh, const char* what);

/// The boundary loops of a manifold mesh: vertex sequences in the triangles' orientation
/// (counter-clockwise around the surface seen from outside), each starting at its smallest
/// vertex index, ordered by that index. Empty for a closed mesh.
std::vector<std::vector<std::int64_t>> boundary_loops(const TriangleMesh& mesh);

/// Unit normal of a triangle (zero vector for a degenerate one).
std::array<double, 3> triangle_normal(const TriangleMesh& mesh, std::int64_t triangle);

/// Area-weighted unit vertex normals.
std::vector<double> vertex_normals(const TriangleMesh& mesh);

} // namespace mesolens
