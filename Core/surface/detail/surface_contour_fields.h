// SPDX-License-Identifier: GPL-3.0-or-later
// The fields whose zero sets are the molecular surfaces, as their contouring samples them
// (private to MesoLensCore): a block of the grid at a time, each boundary piece near the block
// visiting the grid points within its reach (a narrow band), so that no point searches.
#pragma once

#include "surface/detail/contour_tetrahedra.h"
#include "surface/detail/probe_distance.h"
#include "surface/detail/sas_boundary.h"
#include "surface/detail/ses_piece_projection.h"

#include <Eigen/Core>

#include <memory>
#include <vector>

namespace mesolens {

/// The solvent-excluded surface of probe radius `probe` (Å) over atoms `centres` with radii
/// `atom_radii`, whose inflated spheres (radii `radii`) have the boundary `boundary` (with its
/// pieces, indexed by `distance`). The field is the distance to the nearest probe position (the
/// least over the boundary's pieces: the exposed parts of spheres, exposed arcs and vertices)
/// less the probe radius, inside the union; deeper than `limit` (> probe) it reports the limit,
/// and outside the union it is negative. Vertices lie on the exact surface to 1e-5 Å, each on its
/// own grid edge; they carry the outward normal (towards the probe), the patch kind, the
/// boundary piece and the nearest atom of that piece. `pieces` certifies them on their patch;
/// where it cannot, the general search decides.
std::unique_ptr<ContourField> excluded_surface_field(
  const ProbeDistance& distance, const SesPieceProjection& pieces, const SasBoundary& boundary,
  const std::vector<Eigen::Vector3d>& centres, const std::vector<double>& radii,
  const std::vector<double>& atom_radii, double probe, double limit);

/// The boundary of the union of spheres `centres`, `radii` (the SAS with inflated radii, the van
/// der Waals surface with the atoms' own): max over spheres of (R - |x - c|), whose zero set it
/// is. Vertices are convex, on the sphere that holds them.
std::unique_ptr<ContourField> union_surface_field(const std::vector<Eigen::Vector3d>& centres,
                                                  const std::vector<double>& radii);

} // namespace mesolens
