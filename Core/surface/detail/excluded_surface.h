// SPDX-License-Identifier: GPL-3.0-or-later
// What the solvent-excluded surface's contour field and projection share (private to
// MesoLensCore): the surface as the set of points one probe radius from the nearest probe
// position, its pieces as labels, and its vertices.
#pragma once

#include "surface/detail/contour_tetrahedra.h"
#include "surface/detail/probe_distance.h"
#include "surface/detail/sas_boundary.h"
#include "surface/detail/ses_piece_projection.h"

#include "mesolens/surface/molecular_surface.h"

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <vector>

namespace mesolens {

/// A piece as a field's hint: its kind in the top two bits, its index below.
constexpr std::uint32_t piece_index_mask = (1u << 30) - 1;
constexpr std::uint32_t encode_piece(PieceKind kind, std::uint32_t index)
{
  return (static_cast<std::uint32_t>(kind) << 30) | (index & piece_index_mask);
}
inline PieceKind hint_kind(std::uint32_t hint)
{
  return static_cast<PieceKind>(hint >> 30);
}
inline std::uint32_t hint_index(std::uint32_t hint)
{
  return hint & piece_index_mask;
}

/// The kind of patch on the piece of `kind` (convex on faces, and when there is no piece).
SurfacePatch surface_patch(PieceKind kind);

/// The boundary piece whose patch a vertex of `patch` kind lies on.
PieceKind piece_kind(std::uint8_t patch);

/// The solvent-excluded surface of probe radius `probe` (Å) over atoms `centres` with radii
/// `atom_radii`: the points `probe` from the nearest position on the inflated spheres'
/// boundary (`boundary`, indexed by `distance`); `pieces` certifies points on single patches.
/// Searches of the index look `limit` (> probe) deep into the union.
struct ExcludedSurface
{
  const ProbeDistance& distance;
  const SesPieceProjection& pieces;
  const SasBoundary& boundary;
  const std::vector<Eigen::Vector3d>& centres;
  const std::vector<double>& atom_radii;
  double probe, limit;

  /// Whether `position` lies on the surface, to 1e-7 Å: its nearest probe position, in
  /// `piece`, is the probe radius away. The search need not look farther than that.
  bool holds(const Eigen::Vector3d& position, ClosestPiece& piece) const
  {
    piece = this->distance.closest(position, {}, this->probe + 1e-6);
    return std::abs(piece.distance - this->probe) <= 1e-7;
  }

  /// The mesh vertex at `position` on the surface, whose nearest probe position is `piece`:
  /// its normal towards the probe, patch kind, piece and atom (the face's own, else the one of
  /// the piece's atoms whose surface is nearest).
  ContourVertex vertex(const Eigen::Vector3d& position, const ClosestPiece& piece) const;
};

} // namespace mesolens
