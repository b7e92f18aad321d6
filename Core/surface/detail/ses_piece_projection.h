// SPDX-License-Identifier: GPL-3.0-or-later
// The solvent-excluded surface one analytic patch at a time (private to MesoLensCore): the
// nearest surface point of a point near a known patch, in closed form, with a cheap certificate
// that it is exact; the general search (ProbeDistance) answers where none can be given.
#pragma once

#include "surface/detail/probe_distance.h"
#include "surface/detail/sas_boundary.h"

#include <Eigen/Core>

#include <atomic>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

namespace mesolens {

/// Projections onto single patches of the solvent-excluded surface of probe `probe` rolling
/// over atoms `centres` (radii `atom_radii`), whose accessible boundary is `boundary` (with its
/// pieces). Every point given lies on the surface exactly (as the general search would tell, to
/// 1e-7 Å); refusals say nothing about the point.
///
/// Why a point of a patch can be certified cheaply: a convex point lies on the surface when its
/// probe position lies outside every neighbour's inflated sphere; a toroidal or concave point
/// when its direction from the probe lies between those of the probe's atoms and no probe
/// position that may cut the patch (listed once per patch, see toroidal_patch_cutters() and
/// concave_patch_cutters()) comes nearer than the probe radius. And no surface point lies inside
/// an atom's ball, nor inside the probe's ball at an accessible position: so for a point inside
/// the ball that carries a patch (the atom's for a convex patch, the probe's nearest to it for a
/// toroidal or concave one), its radial projection onto that ball's sphere, once certified, is
/// its nearest surface point.
class SesPieceProjection
{
public:
  /// `distance` indexes the inflated spheres. The arguments must outlive this object, which
  /// may be used from several threads at once.
  SesPieceProjection(const std::vector<Eigen::Vector3d>& centres,
                     const std::vector<double>& atom_radii, double probe,
                     const SasBoundary& boundary, const ProbeDistance& distance);

  /// A surface point near `x` from the patch of `piece` (kind and index, as ClosestPiece reports
  /// the nearest probe position of surface points): the nearest point of that patch's sphere or
  /// torus, when it is certified on the surface (true; then `point` and its nearest probe
  /// position `nearest`). It is the nearest surface point of `x` when `x` lies inside the ball
  /// carrying the patch.
  bool nearest(const Eigen::Vector3d& x, PieceKind kind, std::uint32_t index,
               Eigen::Vector3d& point, ClosestPiece& nearest) const;

  /// nearest() for `x` near two surface points whose nearest probe positions are pieces `a`
  /// and `b`: tried on those pieces, then on the others of their atoms (arcs between two,
  /// vertices of three, faces), each once; true at the first certified.
  bool nearest_near(const Eigen::Vector3d& x, const std::pair<PieceKind, std::uint32_t>& a,
                    const std::pair<PieceKind, std::uint32_t>& b, Eigen::Vector3d& point,
                    ClosestPiece& nearest) const;

  /// Calls `visit(kind, index)` with each piece near pieces `a` and `b`, as nearest_near() tries
  /// them after those two (the arcs between two of their atoms, the vertices of three, the
  /// atoms' faces, each once, `a` and `b` left out), until it returns true; whether one did.
  /// `visit` must not call this again on the same thread (the atoms are marked in a buffer of
  /// the thread's).
  bool visit_pieces_near(const std::pair<PieceKind, std::uint32_t>& a,
                         const std::pair<PieceKind, std::uint32_t>& b,
                         const std::function<bool(PieceKind, std::uint32_t)>& visit) const;

  /// Whether `y`, on the sphere or torus carrying the patch of the piece (to 1e-9 Å), is
  /// certified on the surface with that piece's position nearest (then set in `nearest`, the
  /// probe radius away). False: not certified.
  bool certify(const Eigen::Vector3d& y, PieceKind kind, std::uint32_t index,
               ClosestPiece& nearest) const;

  /// Whether certify() can answer for the piece without listing what may cut its patch: a face,
  /// or a patch whose list is made or known empty.
  bool certifies_at_once(PieceKind kind, std::uint32_t index) const;

  /// Takes, per arc and per vertex, whether nothing cuts the patch (as ses_patch_integrals()
  /// certifies it: SesPatchIntegrals::arc_uncut, vertex_uncut): those need no list. Call before
  /// any other use.
  void take_uncut_patches(const std::vector<char>& arc_uncut,
                          const std::vector<char>& vertex_uncut);

private:
  bool certify_face(const Eigen::Vector3d& y, std::uint32_t i, ClosestPiece& nearest) const;
  bool certify_arc(const Eigen::Vector3d& y, std::uint32_t k, ClosestPiece& nearest) const;
  bool certify_vertex(const Eigen::Vector3d& y, std::uint32_t k, ClosestPiece& nearest) const;
  /// Whether no probe position that may cut the torus of arc `k` (`torus`) or the concave
  /// patch of vertex `k` comes nearer than the probe radius to `y`.
  bool clear_of_cutters(const Eigen::Vector3d& y, bool torus, std::uint32_t k) const;

  /// The probe positions that may cut a patch (arcs, vertices), listed by the first thread that
  /// needs them.
  struct Cutters
  {
    static constexpr std::uint8_t unlisted = 0, listing = 1, listed = 2;
    std::atomic<std::uint8_t> state{ unlisted };
    std::vector<std::uint32_t> arcs, vertices;
  };
  /// Lists the cutters of the torus of arc `k` (`torus`) or of the concave patch of vertex `k`.
  void list_cutters(bool torus, std::uint32_t k, Cutters& cutters) const;

  const std::vector<Eigen::Vector3d>& centres_;
  const std::vector<double>& atom_radii_;
  double probe_;
  const SasBoundary& boundary_;
  const ProbeDistance& distance_;
  /// Per atom (compressed rows): its arcs and its vertices.
  std::vector<std::uint32_t> atom_arc_start_, atom_arc_items_, atom_vertex_start_,
    atom_vertex_items_;
  /// Per vertex, the sides of the cone of directions from the probe to its three atoms: u_b x u_c
  /// for each atom a (unit directions u), and the cone's orientation u_0 . (u_1 x u_2).
  struct VertexCone
  {
    Eigen::Vector3d sides[3];
    double orientation = 0;
  };
  std::vector<VertexCone> vertex_cones_;
  mutable std::vector<Cutters> arc_cutters_, vertex_cutters_; ///< per arc, per vertex
};

} // namespace mesolens
