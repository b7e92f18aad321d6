// SPDX-License-Identifier: GPL-3.0-or-later
// Which neighbours of a sphere bound its power cell near it (private to MesoLensCore): the only
// ones whose caps can bound its exposed part. Spheres with hundreds of neighbours (large probes)
// keep a few dozen.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <vector>

namespace mesolens {

/// The half-space u . axis <= height (unit axis, height in [-1, 1]) in the frame of a sphere
/// scaled to the unit sphere: the points no nearer in power distance to a neighbour than to the
/// sphere. On the unit sphere it leaves out exactly the neighbour's cap (height: the cosine of
/// the cap's angular radius).
struct PowerPlane
{
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  double height = 0;
};

/// Buffers of power_cell_faces(), reused from sphere to sphere.
struct PowerCellWork
{
  /// A corner of the clipped cube, on three planes (cube faces: -1 .. -6).
  struct Corner
  {
    Eigen::Vector3d position;
    std::array<std::int32_t, 3> planes;
    /// The corners at the other ends of its edges: edge e runs along planes[e], planes[e + 1].
    std::array<std::int32_t, 3> next;
  };
  std::vector<Corner> corners;
  std::vector<double> side;
  std::vector<std::int32_t> beyond, pending, pending_planes;
};

/// What the cube [-1, 1]^3 (which holds the unit sphere) keeps under `planes`, cut in order
/// (largest caps first is fastest). Returns 0 when nothing is kept, with a margin of 1e-9:
/// every point of the unit sphere lies beyond some plane, inside some neighbour. Else returns 1
/// and sets `bounding[k]` to 1 for each plane k that touches what is kept (within 1e-9), 0 for
/// the others: the unit sphere less the caps of the bounding planes alone is the sphere's part
/// outside every plane (the others hold what is kept strictly inside them, so that dropping
/// them changes nothing). Where the clipping meets corners it cannot tell apart (more than three
/// planes through one within the margin), every plane is marked bounding, and 2 returned.
int power_cell_faces(const std::vector<PowerPlane>& planes, std::vector<char>& bounding,
                     PowerCellWork& work);

} // namespace mesolens
