// SPDX-License-Identifier: GPL-3.0-or-later
// The zero set of a 1-Lipschitz field as a closed triangle mesh, by marching tetrahedra on a
// sparse grid (private to MesoLensCore): the molecular surfaces' tessellation.
#pragma once

#include "mesolens/parallel_for.h"

#include <Eigen/Core>

#include <cstdint>
#include <functional>
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

/// The field to contour: positive inside, negative outside, changing by at most the distance
/// between two points (1-Lipschitz), so a ball where |value| exceeds the radius holds none of
/// the surface.
struct ContourField
{
  /// The value at a point.
  std::function<double(const Eigen::Vector3d&)> value;
  /// True when no zero lies within `radius` of the point (may be conservative: false).
  std::function<bool(const Eigen::Vector3d&, double radius)> empty;
  /// The surface vertex on the segment from `outside` (value <= 0) to `inside` (value > 0).
  std::function<ContourVertex(const Eigen::Vector3d& outside, double outside_value,
                              const Eigen::Vector3d& inside, double inside_value)>
    vertex;
};

struct ContourMesh
{
  std::vector<ContourVertex> vertices;
  std::vector<std::int64_t> triangles; ///< 3 per triangle, counter-clockwise seen from outside
};

/// Contours `field` over the box [low, high] on a grid of `spacing` (> 0). The grid's points
/// are those of the box's low corner plus integer multiples of the spacing; the field must be
/// negative on the box's faces for the mesh to be closed. Cells are found by octree culling with
/// `field.empty`, each cell is cut into six tetrahedra of one diagonal (Kuhn's), so the mesh is
/// watertight and 2-manifold without ambiguous cases. `progress` (may be empty) gets the
/// fraction done from the calling thread. Deterministic whatever `parallel_for`.
ContourMesh contour_tetrahedra(const ContourField& field, const Eigen::Vector3d& low,
                               const Eigen::Vector3d& high, double spacing,
                               const ParallelFor& parallel_for,
                               const std::function<void(double)>& progress);

} // namespace mesolens
