// SPDX-License-Identifier: GPL-3.0-or-later
// A cell surface and its coarser copies, from which a geodesic disk is grown at the resolution
// its radius needs (private).
#pragma once

#include "mesolens/mapping/cell_surface.h"
#include "mesolens/mapping/smooth_surface.h"
#include "mesolens/mesh/surface_locator.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

namespace mesolens {
namespace detail {

/// One copy of the surface: its mesh, whose vertices are input vertices, with the input's
/// normals there (its smooth interpolant then follows the input's closely), its adjacency and,
/// on first use, a closest-point index.
struct SurfaceLevel
{
  std::shared_ptr<const SmoothSurface> smooth;
  MeshAdjacency adjacency;
  std::vector<std::int64_t> input_vertex;    ///< per vertex: the input vertex it is
  std::vector<std::int64_t> anchor_triangle; ///< per vertex: an input triangle at it (-1: none)
  double mean_triangle_area = 0;             ///< mesh units squared

  const TriangleMesh& mesh() const
  {
    return this->smooth->mesh();
  }
  /// The point of this copy closest to `point`.
  SurfacePoint closest_point(const std::array<double, 3>& point) const;
  /// The closest-point index, built on first use.
  const SurfaceLocator& locator() const;
  /// Sets mean_triangle_area from the mesh.
  void measure();

private:
  mutable std::once_flag LocatorBuilt;
  mutable std::unique_ptr<SurfaceLocator> Locator;
};

/// Copies of the input, each made from the one before by collapsing short edges into one of
/// their ends (in rounds of independent collapses that keep the topology and the boundary and
/// turn no triangle by more than 60 degrees) down to about a quarter of its vertices, while it
/// has more than `smallest` vertices and collapses succeed. Deterministic.
std::vector<std::unique_ptr<SurfaceLevel>> coarser_levels(const SurfaceLevel& input,
                                                          std::size_t smallest);

/// The point of `mesh` closest to `point` found by walking from `start` (a triangle) across
/// edges while the distance shrinks: the closest point on the part of the surface connected to
/// where the walk starts, in a few steps when it starts nearby. -1 triangle after `max_steps`.
SurfacePoint walk_to_closest(const TriangleMesh& mesh, const MeshAdjacency& adjacency,
                             std::int64_t start, const std::array<double, 3>& point,
                             int max_steps = 256);

/// Where the line through `point` along `direction` meets `mesh`, found by walking from
/// `start` across the edges its crossing lies beyond: a projection that varies continuously
/// with the point (a closest-point projection sends every point above a convex corner to that
/// corner). -1 triangle when the walk leaves the mesh, turns parallel to a triangle or takes
/// more than `max_steps`.
SurfacePoint walk_along_line(const TriangleMesh& mesh, const MeshAdjacency& adjacency,
                             std::int64_t start, const std::array<double, 3>& point,
                             const std::array<double, 3>& direction, int max_steps = 64);

} // namespace detail
} // namespace mesolens
