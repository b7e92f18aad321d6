// SPDX-License-Identifier: GPL-3.0-or-later
// The boundary of a union of spheres as pieces (private to MesoLensCore): per sphere its exposed
// area and normal integral, and the exposed arcs of the spheres' intersection circles and the
// points where three spheres meet. With the atoms inflated by a probe these are the probe
// positions of the solvent-accessible surface, from which the solvent-excluded surface follows.
#pragma once

#include "mesolens/common/parallel_for.h"
#include "mesolens/common/point_span.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <vector>

namespace mesolens {

/// An exposed arc of the circle where spheres `first` < `second` meet: the points
/// centre + radius (cos a e1 + sin a e2) for azimuths a in [start, start + span] (radians,
/// 0 < span <= 2 pi; a full circle has span 2 pi). axis runs from `first`'s centre to
/// `second`'s; (e1, e2, axis) is right-handed.
struct SasArc
{
  std::uint32_t first = 0, second = 0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero(), axis = Eigen::Vector3d::UnitZ(),
                  e1 = Eigen::Vector3d::UnitX(), e2 = Eigen::Vector3d::UnitY();
  double radius = 0, start = 0, span = 0;

  Eigen::Vector3d point(double azimuth) const
  {
    return this->centre +
      this->radius * (std::cos(azimuth) * this->e1 + std::sin(azimuth) * this->e2);
  }
};

/// An exposed point where three spheres meet (spheres in increasing order).
struct SasVertex
{
  std::array<std::uint32_t, 3> spheres{};
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
};

/// A closed curve bounding a sphere's exposed part (the exposed side on its left): its share
/// of the Gauss-Bonnet turning on the unit sphere (geodesic curvature and corners, radians) and
/// of the normal integral (length^2), and a point on it. The exposed area of a region bounded by
/// loops L is R^2 (2 pi (2 - |L|) - sum of their turning).
struct SasLoop
{
  std::uint32_t sphere = 0;
  double turning = 0;
  Eigen::Vector3d normal_integral = Eigen::Vector3d::Zero();
  Eigen::Vector3d sample = Eigen::Vector3d::Zero();
};

/// The pieces of a union's boundary. Per sphere (radius R): `area` (exposed, length^2),
/// `normal_integral` (integral of the outward unit normal over the exposed part, length^2),
/// `neighbours` (the spheres that overlap it, neither inside the other, and where it has many,
/// those bounding its power cell near it: every point of it that another sphere covers, one of
/// these covers; those that cover more of it first). Arcs and vertices only when asked for.
struct SasBoundary
{
  std::vector<double> area;
  std::vector<Eigen::Vector3d> normal_integral;
  std::vector<std::vector<std::uint32_t>> neighbours;
  std::vector<SasArc> arcs;
  std::vector<SasVertex> vertices;
  std::vector<SasLoop> loops; ///< ordered by sphere
  /// Vertices where four or more spheres meet (to 1e-9 of the unit sphere), as each sphere
  /// sees them: there the pieces are ambiguous and the SES's exact figures unreliable.
  std::size_t degenerate_vertices = 0;
};

/// A cap of the unit sphere: the directions u with u . axis > height (axis a unit vector,
/// height in (-1, 1)).
struct UnitCap
{
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  double height = 0;
};

/// The part of the unit sphere that no cap covers, exactly (the arrangement of the caps'
/// circles and Gauss-Bonnet, as for each sphere of sas_boundary()): its `area` (steradians) and
/// `direction_integral`, the integral of u over it. False, and nothing set, when two circles
/// are within 1e-9 of tangent or a third passes within 1e-9 of their crossing (unless a fourth
/// cap holds that crossing deeper than 1e-7), where the arrangement would depend on rounding.
bool uncovered_unit_area(const std::vector<UnitCap>& caps, double& area,
                         Eigen::Vector3d& direction_integral);

/// The exposed parts of each sphere (see sphere_union_area() for the method and the input
/// checks), and with `with_pieces` the exposed arcs and vertices, each once, ordered by their
/// lowest sphere, and every sphere's loops (deterministic whatever `parallel_for`).
SasBoundary sas_boundary(PointSpan<const double> centres, const std::vector<double>& radii,
                         bool with_pieces, const ParallelFor& parallel_for);

} // namespace mesolens
