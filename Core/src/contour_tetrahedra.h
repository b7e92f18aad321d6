// SPDX-License-Identifier: GPL-3.0-or-later
// The zero set of a 1-Lipschitz field as a closed triangle mesh, by marching tetrahedra on a
// sparse grid (private to MesoLensCore): the molecular surfaces' tessellation.
#pragma once

#include "mesolens/parallel_for.h"

#include <Eigen/Core>

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace mesolens {

/// A mesh vertex with what the field knows about where it lies.
struct ContourVertex
{
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  std::int32_t atom = -1;
  std::uint8_t patch = 0;
  std::uint32_t piece = 0; ///< the field's own label (which boundary piece)
};

/// The field near one octree node at a time, with buffers of its own: each block of the grid
/// asks one of these, so that it may prepare once per node what the queries inside need, from
/// what it prepared for the node's parent.
class LocalContourField
{
public:
  virtual ~LocalContourField() = default;
  /// Prepares for queries within `radius` of `centre`; false when no zero lies within. Level 0
  /// is a block; a ball of level k > 0 lies inside the last ball focused at level k - 1.
  /// `single_cell`: the ball is a grid cell's, whose corners and edges come next.
  virtual bool focus(int level, const Eigen::Vector3d& centre, double radius, bool single_cell) = 0;
  /// The value at a point within the last focus, and in `hint` what the field may want to
  /// know about the point when it places a vertex near it (its own label).
  virtual double value(const Eigen::Vector3d& x, std::uint32_t& hint) = 0;
  /// A grid point's value and hint, as value() gave them.
  struct Sample
  {
    Eigen::Vector3d position;
    double value;
    std::uint32_t hint;
  };
  /// The surface vertex on the segment (within the focus) from `outside` (value <= 0) to
  /// `inside` (value > 0).
  virtual ContourVertex vertex(const Sample& outside, const Sample& inside) = 0;
};

/// The field to contour: positive inside, negative outside, changing by at most the distance
/// between two points (1-Lipschitz), so a ball where |value| exceeds the radius holds none of
/// the surface. Values must not depend on which focus they were asked under (their signs at
/// least), as neighbouring blocks share grid points; contour_tetrahedra() throws
/// std::logic_error when they do.
struct ContourField
{
  /// True when no zero lies within `radius` of the point (may be conservative: false): a cheap
  /// test of whole blocks before any focus.
  std::function<bool(const Eigen::Vector3d&, double radius)> empty;
  /// A new local view of the field (called once per block, from any thread).
  std::function<std::unique_ptr<LocalContourField>()> local;
};

struct ContourMesh
{
  std::vector<ContourVertex> vertices;
  std::vector<std::int64_t> triangles; ///< 3 per triangle, counter-clockwise seen from outside
};

/// Contours `field` over the box [low, high] on a grid of `spacing` (> 0). The grid's points
/// are those of the box's low corner plus integer multiples of the spacing; the field must be
/// negative on the box's faces for the mesh to be closed. Cells are found by octree culling with
/// `LocalContourField::focus`, each cell is cut into six tetrahedra of one diagonal (Kuhn's), so
/// the mesh is watertight and 2-manifold without ambiguous cases. `progress` (may be empty) gets
/// the fraction done from the calling thread. Deterministic whatever `parallel_for`.
ContourMesh contour_tetrahedra(const ContourField& field, const Eigen::Vector3d& low,
                               const Eigen::Vector3d& high, double spacing,
                               const ParallelFor& parallel_for,
                               const std::function<void(double)>& progress);

} // namespace mesolens
