// SPDX-License-Identifier: GPL-3.0-or-later
// Projections onto the molecular surfaces, as their meshes' refinement asks for them (private
// to MesoLensCore).
#pragma once

#include "surface/detail/chord_refinement.h"
#include "surface/detail/probe_distance.h"
#include "surface/detail/sas_boundary.h"
#include "surface/detail/ses_piece_projection.h"

#include <Eigen/Core>

#include <memory>
#include <vector>

namespace mesolens {

/// Solvent-excluded surface of probe radius `probe` over atoms `centres` with radii
/// `atom_radii` (the inflated spheres' boundary `boundary`, indexed by `distance`): points
/// within `limit` - `probe` inside it, or in the solvent nearer the surface than the probe
/// radius, go to the nearest surface point (along the line from their nearest probe position);
/// those where that point lies inside another probe's sphere are refused. Edge middles go first
/// onto the patches near their ends, where `pieces` certifies them (project_between()).
std::unique_ptr<LocalSurfaceProjection> excluded_surface_projection(
  const ProbeDistance& distance, const SesPieceProjection& pieces, const SasBoundary& boundary,
  const std::vector<Eigen::Vector3d>& centres, const std::vector<double>& atom_radii, double probe,
  double limit);

/// Union of spheres (`centres`, `radii`, indexed by `distance`): points within `reach` (Å) of
/// the boundary go radially onto the sphere they lie deepest in; those whose foot another sphere
/// covers are refused.
std::unique_ptr<LocalSurfaceProjection> union_surface_projection(
  const ProbeDistance& distance, const std::vector<Eigen::Vector3d>& centres,
  const std::vector<double>& radii, double reach);

} // namespace mesolens
