// SPDX-License-Identifier: GPL-3.0-or-later
// Refining a mesh whose vertices lie on a known surface until its edges follow the surface to a
// chord error (private to MesoLensCore): the molecular surfaces' fine level, on top of the
// coarse mesh that contouring gives.
#pragma once

#include "surface/detail/contour_tetrahedra.h"
#include "mesolens/common/parallel_for.h"

#include <Eigen/Core>

#include <functional>
#include <limits>
#include <memory>

namespace mesolens {

/// Projects points near a surface onto it, one ball of space at a time, with buffers of its own
/// (one per thread).
class LocalSurfaceProjection
{
public:
  virtual ~LocalSurfaceProjection() = default;
  /// Prepares for points within `radius` (Å, > 0) of `centre` (others may be slower to
  /// project).
  virtual void focus(const Eigen::Vector3d& centre, double radius) = 0;
  /// The surface point nearest `x` as a mesh vertex (normal, atom, patch kind, piece); false
  /// when `x` is too far from the surface or its nearest point cannot be told exactly (then
  /// `vertex` is left as it was).
  virtual bool project(const Eigen::Vector3d& x, ContourVertex& vertex) = 0;
  /// A surface point for `x`, the middle of the edge from `from` to `to` (mesh vertices): by
  /// default project(); a surface may instead give the nearest point of a patch near the ends
  /// (the same where `x` lies inside the ball carrying that patch, else a surface point no
  /// nearer to `x`, which at worst splits an edge that did not need it).
  virtual bool project_between(const Eigen::Vector3d& x, const ContourVertex& from,
                               const ContourVertex& to, ContourVertex& vertex)
  {
    static_cast<void>(from);
    static_cast<void>(to);
    return this->project(x, vertex);
  }
  /// Whether the surface runs smoothly (without a crease) from vertex `a`'s piece to `b`'s: the
  /// same piece, or pieces known to meet tangentially. By default only the same piece.
  virtual bool smoothly_joined(const ContourVertex& a, const ContourVertex& b) const
  {
    return a.patch == b.patch && a.piece == b.piece;
  }
  /// When vertices `a` and `b` lie on one smooth piece of the surface (a sphere, a torus), the
  /// distance from `x` to that piece's whole surface, without a focus: the deviation of a
  /// chord whose midpoint projects onto the same piece. NaN otherwise.
  virtual double piece_gap(const ContourVertex& a, const ContourVertex& b,
                           const Eigen::Vector3d& x) const = 0;
  /// When vertices `a` and `b` lie on different pieces: the distance from `x` to the surface as
  /// it would be were the piece nearest `x` one of theirs (as it is near the middle of most
  /// short edges), from those two pieces' whole surfaces alone. NaN by default (unknown).
  virtual double end_pieces_gap(const ContourVertex& a, const ContourVertex& b,
                                const Eigen::Vector3d& x) const
  {
    static_cast<void>(a);
    static_cast<void>(b);
    static_cast<void>(x);
    return std::numeric_limits<double>::quiet_NaN();
  }
};

/// A new local projection (called once per chunk of work, from any thread).
using SurfaceProjection = std::function<std::unique_ptr<LocalSurfaceProjection>()>;

/// Splits every edge of `mesh` (closed, 2-manifold, counter-clockwise triangles, vertices on the
/// surface with their unit normals) whose midpoint lies farther than `tolerance` (Å, > 0) from the
/// surface, at the midpoint's projection (project_between()), then the new edges likewise, for at
/// most `max_rounds` rounds. Triangles are cut along their split edges (into 2, 3 or 4), so the
/// mesh stays closed and 2-manifold. Splits that could fold the mesh are not made: a projection
/// whose normal faces away from either end's, or lying farther from the midpoint than half the
/// edge; any split of a triangle at a crease (two corners' normals more than about 70 degrees
/// apart, unless their pieces are smoothly joined; or the triangle's own normal that far from a
/// corner's), which stays as it was; and the splits of a triangle whose pieces would face away from
/// it, lie across the surface or pass through a triangle at a crease. Edges are kept without a
/// projection when both ends lie on one piece and the midpoint lies within the tolerance of that
/// piece, when their ends' normals show them bending by less than half the tolerance (the
/// sagitta of a circular arc through both ends), or when they bend by less than the tolerance
/// and end_pieces_gap() is within it. Rounds after the first look at the triangles the last one
/// cut alone. Deterministic whatever `parallel_for`; triangles keep the order of the ones they
/// come from. Midpoints are projected in groups, those in one cube of `focus_size` (Å, > 0; a
/// few times the edges' length) under one focus.
void refine_chords(ContourMesh& mesh, const SurfaceProjection& projection, double tolerance,
                   double focus_size, int max_rounds, const ParallelFor& parallel_for);

} // namespace mesolens
