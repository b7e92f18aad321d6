// SPDX-License-Identifier: GPL-3.0-or-later
// Parameterization of a disk-shaped mesh onto a planar disk (Floater's mean-value coordinates),
// as the membrane-mapping paper parameterizes its geodesic disks.
#pragma once

#include "mesolens/mesh/triangle_mesh.h"

#include <cstddef>
#include <vector>

namespace mesolens {

/// A parameterization of a disk mesh: texture coordinates and how much it distorts.
struct DiskParameterization
{
  std::vector<double> uv;               ///< 2 per vertex, in the units of the target radius
  std::vector<double> angle_distortion; ///< per triangle: largest / smallest singular value of
                                        ///< the map's Jacobian (1 = angles preserved)
  std::vector<double> area_distortion;  ///< per triangle: (uv area / 3D area), divided by the same
                                        ///< ratio for the whole disk (1 = areas preserved)
  std::vector<double> stretch;          ///< per triangle: the largest factor by which the map
                                        ///< lengthens or shortens a length, max(s_max, 1 / s_min)
                                        ///< (1 = isometric, infinity for a degenerate triangle)
  std::size_t flipped_triangles = 0;    ///< triangles whose uv orientation is reversed or zero
  bool bijective() const
  {
    return this->flipped_triangles == 0;
  }
};

/// Maps the disk mesh onto the planar disk of `radius` (> 0, e.g. the geodesic radius): the
/// boundary loop onto the circle by arc length (counter-clockwise when the mesh's normals face
/// the viewer; the first boundary vertex, the one with the smallest index, at angle 0), the
/// interior by mean-value weights (Floater 2003) so each interior vertex is the weighted mean
/// of its neighbours. Positive weights and a convex boundary make the map bijective; the result
/// is checked anyway and flipped triangles counted. The sparse system is solved with Eigen's
/// SparseLU. Throws InvalidInput (bad radius), TopologyError (not a disk: no or several boundary
/// loops, degenerate triangles) or SolverFailure.
DiskParameterization harmonic_parameterization(const TriangleMesh& disk, double radius);

} // namespace mesolens
