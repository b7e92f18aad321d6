// SPDX-License-Identifier: GPL-3.0-or-later
// The fields whose zero sets are the molecular surfaces, as the tessellation asks them (private
// to MesoLensCore): per octree node, the boundary pieces near it are gathered once (from its
// parent's), and every corner value and vertex inside looks at those alone.
#pragma once

#include "contour_tetrahedra.h"
#include "probe_distance.h"
#include "sas_boundary.h"

#include <Eigen/Core>

#include <memory>
#include <vector>

namespace mesolens {

/// The solvent-excluded surface: the distance to the probe positions (the inflated spheres'
/// boundary, `distance`) less the probe radius `probe`, exact up to `limit` (> probe) inside the
/// union. Vertices lie on the exact surface to 1e-5 Å, each on its own grid edge; they carry the
/// outward normal (towards the probe), the patch kind, the boundary piece and the nearest atom
/// of that piece (`centres`, `atom_radii`: the uninflated atoms).
std::unique_ptr<LocalContourField> excluded_surface_field(
  const ProbeDistance& distance, const SasBoundary& boundary,
  const std::vector<Eigen::Vector3d>& centres, const std::vector<double>& atom_radii, double probe,
  double limit);

/// The boundary of the union of the spheres behind `distance` (the SAS with inflated radii, the
/// van der Waals surface with the atoms' own): max over spheres of (R - |x - c|), whose zero set
/// it is. Vertices are convex, on the sphere that holds them.
std::unique_ptr<LocalContourField> union_surface_field(const ProbeDistance& distance,
                                                       const std::vector<Eigen::Vector3d>& centres,
                                                       const std::vector<double>& radii);

} // namespace mesolens
