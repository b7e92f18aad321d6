// SPDX-License-Identifier: GPL-3.0-or-later
// The triangles a chord refinement leaves as they are at the surface's creases, and whether
// triangles cut beside them would pass through them (private to MesoLensCore).
#pragma once

#include "surface/detail/contour_tetrahedra.h"
#include "common/detail/grid_cells.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

namespace mesolens {

/// Whether the closed segment [p, q] meets the closed triangle (a, b, c): the segment's ends on
/// both sides of the triangle's plane (or on it) and the line through them inside its edges (or
/// on one). Coplanar segments count as missing it. Conservative at touching: true.
bool segment_meets_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                            const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& c);

/// Whether triangles (corner indices into `vertices`) `first` and `second` meet anywhere but at
/// the corners they share: with no corner shared, where an edge of one meets the other; with
/// one, where the edge opposite it meets the other (their common part starts at that corner and
/// leaves one of them through that edge); with two or three, never (they meet along the shared
/// edge alone unless they lie in one plane, which the refinement's fold tests rule out).
bool triangles_meet(const std::array<std::int64_t, 3>& first,
                    const std::array<std::int64_t, 3>& second,
                    const std::vector<ContourVertex>& vertices);

/// A mesh's frozen triangles (never cut, so their corners stay) found in space: those meeting a
/// box, by cells of a fixed width; and per vertex, the frozen triangles around it. A triangle
/// none of whose edges is split is never cut, so the refinement asks frozen_edge() alone to keep
/// them.
class FrozenCreases
{
public:
  /// `frozen`: per triangle of `mesh`, whether it stays. `cell_width` (Å, > 0): a few times the
  /// triangles' size.
  FrozenCreases(const ContourMesh& mesh, const std::vector<char>& frozen, double cell_width);

  /// Whether edge (a, b) belongs to a frozen triangle.
  bool frozen_edge(std::int64_t a, std::int64_t b) const;

  /// Whether some of `triangles` (three corner indices each, into `vertices`) meets a frozen
  /// triangle anywhere but at shared corners (see triangles_meet()).
  bool meets(const std::vector<std::int64_t>& triangles,
             const std::vector<ContourVertex>& vertices) const;

  bool empty() const
  {
    return this->cells_.empty();
  }

private:
  /// A box, low and high corners.
  using Box = std::array<Eigen::Vector3d, 2>;

  std::vector<std::array<std::int64_t, 3>> corners_; ///< per frozen triangle, in order
  std::vector<Box> boxes_;                           ///< per frozen triangle
  std::vector<GridCell> first_cells_; ///< per frozen triangle, the cell of its box's low corner
  /// (cell key, frozen triangle) sorted by key: every cell a triangle's box meets.
  std::vector<std::pair<std::uint64_t, std::uint32_t>> cells_;
  /// Per cell key, its entries' range in cells_.
  std::unordered_map<std::uint64_t, std::pair<std::uint32_t, std::uint32_t>> cell_ranges_;
  /// Per vertex of the mesh at construction, its frozen triangles (compressed rows).
  std::vector<std::uint32_t> around_start_, around_;
  double cell_width_;
};

} // namespace mesolens
