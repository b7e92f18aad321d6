// SPDX-License-Identifier: GPL-3.0-or-later
// The fields whose zero sets are the molecular surfaces, as the tessellation asks them (private
// to MesoLensCore): per octree node, the boundary pieces near it are gathered once (from its
// parent's), and every corner value and vertex inside looks at those alone.
#pragma once

#include "chord_refinement.h"
#include "contour_tetrahedra.h"
#include "probe_distance.h"
#include "sas_boundary.h"
#include "ses_piece_projection.h"

#include <Eigen/Core>

#include <memory>
#include <vector>

namespace mesolens {

/// The solvent-excluded surface: the distance to the probe positions (the inflated spheres'
/// boundary, `distance`) less the probe radius `probe`, exact up to `limit` (> probe) inside the
/// union. Vertices lie on the exact surface to 1e-5 Å, each on its own grid edge; they carry the
/// outward normal (towards the probe), the patch kind, the boundary piece and the nearest atom
/// of that piece (`centres`, `atom_radii`: the uninflated atoms). `pieces` certifies vertices on
/// convex patches, and on those it knows uncut, before any search.
std::unique_ptr<LocalContourField> excluded_surface_field(
  const ProbeDistance& distance, const SesPieceProjection& pieces, const SasBoundary& boundary,
  const std::vector<Eigen::Vector3d>& centres, const std::vector<double>& atom_radii, double probe,
  double limit);

/// The boundary of the union of the spheres behind `distance` (the SAS with inflated radii, the
/// van der Waals surface with the atoms' own): max over spheres of (R - |x - c|), whose zero set
/// it is. Vertices are convex, on the sphere that holds them.
std::unique_ptr<LocalContourField> union_surface_field(const ProbeDistance& distance,
                                                       const std::vector<Eigen::Vector3d>& centres,
                                                       const std::vector<double>& radii);

/// Projections onto the same surfaces, for refining their meshes. Solvent-excluded: points
/// within `limit` - `probe` inside it, or in the solvent nearer the surface than the probe radius,
/// go to the nearest surface point (along the line from their nearest probe position); those
/// where that point lies inside another probe's sphere are refused. Edge middles go first onto
/// the patches near their ends, where `pieces` certifies them (project_between()).
std::unique_ptr<LocalSurfaceProjection> excluded_surface_projection(
  const ProbeDistance& distance, const SesPieceProjection& pieces, const SasBoundary& boundary,
  const std::vector<Eigen::Vector3d>& centres, const std::vector<double>& atom_radii, double probe,
  double limit);

/// Union of spheres: points within `reach` (Å) of the boundary go radially onto the sphere they
/// lie deepest in; those whose foot another sphere covers are refused.
std::unique_ptr<LocalSurfaceProjection> union_surface_projection(
  const ProbeDistance& distance, const std::vector<Eigen::Vector3d>& centres,
  const std::vector<double>& radii, double reach);

} // namespace mesolens
