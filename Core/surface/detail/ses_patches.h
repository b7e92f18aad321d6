// SPDX-License-Identifier: GPL-3.0-or-later
// Area and volume of the solvent-excluded surface's analytic patches (private to MesoLensCore).
#pragma once

#include "surface/detail/probe_distance.h"
#include "surface/detail/sas_boundary.h"

#include "mesolens/common/parallel_for.h"

#include <Eigen/Core>

#include <vector>

namespace mesolens {

/// Per piece of the solvent-accessible boundary, the area of the SES patch it carries (Å²) and
/// its volume term, one third of the integral of x . n over the patch (Å³; the terms sum to the
/// enclosed volume). Faces carry convex patches, arcs toroidal ones, vertices concave ones.
struct SesPatchIntegrals
{
  std::vector<double> face_area, arc_area, vertex_area;
  std::vector<double> face_volume, arc_volume, vertex_volume;
  std::size_t singular_count = 0; ///< patches integrated numerically because something cuts them
  /// Per arc (toroidal patch) and per vertex (concave patch): 1 when no probe position but the
  /// patch's own comes within the probe radius of it (certified): nothing else trims the patch
  /// (a torus the probe passes through is still cut at its axis), and each of its points lies
  /// on the surface.
  std::vector<char> arc_uncut, vertex_uncut;
};

/// The patches of probe `probe` (> 0) rolling over atoms `centres` with radii `atom_radii`;
/// `boundary` is that of the atoms inflated by the probe (with its pieces) and `distance` a
/// query structure over it with reach at least twice the probe radius plus the largest
/// inflated radius.
///
/// Convex patches are the exposed parts of the inflated spheres scaled onto the atoms. Toroidal
/// patches run between the two contact circles and are cut at the axis when the probe passes
/// between the atoms (there the torus intersects itself). Concave patches are spherical
/// triangles on the probe. Each comes in closed form unless a probe position that does not
/// belong to the patch may come within the probe radius of it: most patches are too narrow for
/// any to (torus_clear_of_every_position(), concave_clear_of_every_position()); for the others,
/// the foreign pieces within the probe radius of a ball around the patch, each certified
/// against the patch itself (patch_clearance.h), and other probes overlapping a concave patch,
/// which cut it exactly (caps on its sphere). Only patches something may cut are split
/// recursively, looking at those pieces alone, keeping the parts no other probe position
/// reaches, and taking the pieces no foreign piece reaches exactly.
SesPatchIntegrals ses_patch_integrals(const std::vector<Eigen::Vector3d>& centres,
                                      const std::vector<double>& atom_radii, double probe,
                                      const SasBoundary& boundary, const ProbeDistance& distance,
                                      const ParallelFor& parallel_for);

/// The probe positions that may come within `probe` (Å) of the toroidal patch of
/// `boundary.arcs[k]` (on the side of the axis of the arc's own positions, where a probe passing
/// between the atoms leaves it), appended to `arcs` and `vertices` (sorted, each once): the arcs
/// and vertices touching neither of its atoms near it. No other probe position comes nearer
/// than `probe` to the patch (see ses_patch_integrals()).
void toroidal_patch_cutters(const std::vector<Eigen::Vector3d>& centres, double probe,
                            const SasBoundary& boundary, const ProbeDistance& distance,
                            std::uint32_t k, std::vector<std::uint32_t>& arcs,
                            std::vector<std::uint32_t>& vertices);

/// The same for the concave patch of `boundary.vertices[k]`: the arcs that may cut it and the
/// other vertices within 2 `probe` (overlapping probes).
void concave_patch_cutters(const std::vector<Eigen::Vector3d>& centres, double probe,
                           const SasBoundary& boundary, const ProbeDistance& distance,
                           std::uint32_t k, std::vector<std::uint32_t>& arcs,
                           std::vector<std::uint32_t>& vertices);

} // namespace mesolens
