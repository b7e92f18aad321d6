// SPDX-License-Identifier: GPL-3.0-or-later
// The exact area of the surface of a union of spheres, per sphere: the van der Waals surface of
// atoms, or (the atoms inflated by a probe) their solvent-accessible surface.
#pragma once

#include "mesolens/common/parallel_for.h"
#include "mesolens/common/point_span.h"

#include <array>
#include <vector>

namespace mesolens {

/// The largest magnitude of a centre coordinate or radius the sphere union and the molecular
/// surface take, in their length unit (1 cm for Å): farther out, doubles keep too few digits
/// below the Å for the geometry. Translate distant molecules towards the origin first.
constexpr double largest_sphere_coordinate = 1e8;

/// Per sphere, the area of its part of the union's surface (length units squared), the total,
/// and the union's volume (length units cubed).
struct SphereUnionArea
{
  std::vector<double> per_sphere;
  double total = 0;
  double volume = 0;
};

/// The exact exposed area of each sphere of a union (centres and radii in one length unit;
/// radii > 0): each sphere's surface less the caps its neighbours cover, from the arcs that
/// bound what stays exposed, by the Gauss-Bonnet theorem (no sampling, no slices); and the
/// exact volume of the union by the divergence theorem over the same patches (their normal
/// integrals from the same arcs). For the
/// solvent-accessible surface pass the atoms' radii plus the probe radius. Spheres inside
/// another have no exposed area; coincident equal spheres count once (the first). Throws
/// InvalidInput for lists of different lengths, a non-finite centre or radius, a radius <= 0, or
/// a coordinate or radius beyond largest_sphere_coordinate.
/// Deterministic whatever `parallel_for`; time about O(n k^2) for k neighbours per sphere.
SphereUnionArea sphere_union_area(PointSpan<const double> centres, const std::vector<double>& radii,
                                  const ParallelFor& parallel_for = {});

} // namespace mesolens
