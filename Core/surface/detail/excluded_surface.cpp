// SPDX-License-Identifier: GPL-3.0-or-later
#include <Eigen/Dense>

#include "surface/detail/excluded_surface.h"

#include <array>

namespace mesolens {

SurfacePatch surface_patch(PieceKind kind)
{
  switch (kind)
  {
    case PieceKind::Arc:
      return SurfacePatch::Toroidal;
    case PieceKind::Vertex:
      return SurfacePatch::Concave;
    default:
      return SurfacePatch::Convex;
  }
}

PieceKind piece_kind(std::uint8_t patch)
{
  switch (static_cast<SurfacePatch>(patch))
  {
    case SurfacePatch::Toroidal:
      return PieceKind::Arc;
    case SurfacePatch::Concave:
      return PieceKind::Vertex;
    default:
      return PieceKind::Face;
  }
}

ContourVertex ExcludedSurface::vertex(const Eigen::Vector3d& position,
                                      const ClosestPiece& piece) const
{
  ContourVertex vertex;
  vertex.position = position;
  const Eigen::Vector3d towards_probe = piece.point - position;
  vertex.normal = towards_probe.norm() > 0 ? Eigen::Vector3d(towards_probe.normalized())
                                           : Eigen::Vector3d::UnitZ();
  vertex.piece = piece.index;
  vertex.patch = static_cast<std::uint8_t>(surface_patch(piece.kind));
  const PieceKind kind = piece_kind(vertex.patch); // a face also when no piece was within reach
  std::array<std::uint32_t, 3> candidates{};
  const int candidate_count = piece_spheres(this->boundary, kind, piece.index, candidates);
  double nearest = 1e300;
  for (int c = 0; c < candidate_count; ++c)
  {
    const std::uint32_t atom = candidates[std::size_t(c)];
    const double gap = (position - this->centres[atom]).norm() - this->atom_radii[atom];
    if (gap < nearest)
    {
      nearest = gap;
      vertex.atom = static_cast<std::int32_t>(atom);
    }
  }
  return vertex;
}

} // namespace mesolens
