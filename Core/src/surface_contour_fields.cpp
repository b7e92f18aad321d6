// SPDX-License-Identifier: GPL-3.0-or-later
#include <Eigen/Dense>

#include "surface_contour_fields.h"

#include "segment_roots.h"
#include "ses_piece_projection.h"

#include "mesolens/molecular_surface.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace mesolens {

namespace {
using Vec = Eigen::Vector3d;

/// A piece as a field's hint: its kind in the top two bits, its index below.
constexpr std::uint32_t index_mask = (1u << 30) - 1;
std::uint32_t encode(PieceKind kind, std::uint32_t index)
{
  return (static_cast<std::uint32_t>(kind) << 30) | (index & index_mask);
}

/// The kind of patch on the piece of `kind` (convex on faces, and when there is no piece).
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

/// The boundary piece whose patch a vertex of `patch` kind lies on.
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

/// The vertex at `position` on the solvent-excluded surface, whose nearest boundary piece (a
/// probe position) is `piece`: its normal towards the probe, patch kind, piece and atom (the
/// face's own, else the one of the piece's atoms whose surface is nearest).
ContourVertex excluded_vertex(const Vec& position, const ClosestPiece& piece,
                              const SasBoundary& boundary, const std::vector<Vec>& centres,
                              const std::vector<double>& atom_radii)
{
  ContourVertex vertex;
  vertex.position = position;
  const Vec towards_probe = piece.point - position;
  vertex.normal = towards_probe.norm() > 0 ? Vec(towards_probe.normalized()) : Vec::UnitZ();
  vertex.piece = piece.index;
  vertex.patch = static_cast<std::uint8_t>(surface_patch(piece.kind));
  const PieceKind kind = piece_kind(vertex.patch); // a face also when no piece was within reach
  std::array<std::uint32_t, 3> candidates{};
  const int candidate_count = piece_spheres(boundary, kind, piece.index, candidates);
  double nearest = 1e300;
  for (int c = 0; c < candidate_count; ++c)
  {
    const double gap = (position - centres[candidates[c]]).norm() - atom_radii[candidates[c]];
    if (gap < nearest)
    {
      nearest = gap;
      vertex.atom = static_cast<std::int32_t>(candidates[c]);
    }
  }
  return vertex;
}

/// What the solvent-excluded surface's field and projection look at (see
/// excluded_surface_field()).
struct ExcludedSurface
{
  const ProbeDistance& distance;
  const SesPieceProjection& pieces;
  const SasBoundary& boundary;
  const std::vector<Vec>& centres;
  const std::vector<double>& atom_radii;
  double probe, limit;

  /// Whether `position` (within the ball of `local`) lies on the surface, to 1e-7 Å: its
  /// nearest probe position, in `piece`, is the probe radius away. The search need not look
  /// farther than that.
  bool holds(const LocalPieces& local, const Vec& position, ClosestPiece& piece) const
  {
    piece = this->distance.closest(local, position, {}, this->probe + 1e-6);
    return std::abs(piece.distance - this->probe) <= 1e-7;
  }
};

class ExcludedSurfaceField final : public LocalContourField
{
public:
  explicit ExcludedSurfaceField(const ExcludedSurface& surface)
    : surface_(surface)
  {
  }

  bool focus(int level, const Vec& centre, double radius, bool single_cell) override
  {
    if (static_cast<std::size_t>(level) >= this->levels_.size())
    {
      this->levels_.resize(static_cast<std::size_t>(level) + 1);
    }
    if (single_cell && level > 0)
    {
      // A cell asks few queries: its parent's pieces serve them, unrefined. Its corners are
      // shared with the cells beside it, so testing whether the surface passes costs more than
      // the corners it would save.
      this->local_ = &this->levels_[static_cast<std::size_t>(level) - 1];
      return true;
    }
    LocalPieces& local = this->levels_[static_cast<std::size_t>(level)];
    if (level == 0)
    {
      this->surface_.distance.gather(centre, radius, this->surface_.limit, local);
    }
    else
    {
      this->surface_.distance.refine(this->levels_[static_cast<std::size_t>(level) - 1], centre,
                                     radius, local);
    }
    this->local_ = &local;
    return std::abs(local.centre_distance - this->surface_.probe) <= radius;
  }

  double value(const Vec& x, std::uint32_t& hint) override
  {
    const ClosestPiece piece = this->surface_.distance.closest(*this->local_, x);
    hint = encode(piece.kind, piece.index);
    return piece.distance - this->surface_.probe;
  }

  ContourVertex vertex(const Sample& outside, const Sample& inside) override
  {
    const double p = this->surface_.probe;
    // The root along the grid edge itself: vertices kept on their edges cannot fold triangles
    // over one another, even at the surface's creases. First along the pieces nearest the
    // edge's ends (mostly one piece for both), then along the one nearest the linear guess
    // (cheap roots on one piece, each kept when the full field agrees there), else on the field.
    Vec position;
    ClosestPiece piece;
    std::uint32_t tried[3];
    int tried_count = 0;
    const auto along = [&](std::uint32_t hint) {
      const PieceKind kind = static_cast<PieceKind>(hint >> 30);
      const std::uint32_t index = hint & index_mask;
      if (kind == PieceKind::None ||
          std::find(tried, tried + tried_count, hint) != tried + tried_count)
      {
        return false;
      }
      tried[tried_count++] = hint;
      const auto along_piece = [&](const Vec& x) {
        return this->surface_.distance.piece_distance(x, kind, index) - p;
      };
      const double at_outside = along_piece(outside.position);
      const double at_inside = along_piece(inside.position);
      if (!(at_outside <= 0 && at_inside > 0))
      {
        return false;
      }
      // Spheres in closed form: the atom's own for a face (the inflated sphere less the
      // probe), the probe's at a vertex; circles by regula falsi.
      if (kind == PieceKind::Arc)
      {
        position =
          segment_root(outside.position, at_outside, inside.position, at_inside, along_piece);
      }
      else
      {
        const bool face = kind == PieceKind::Face;
        const Vec& centre =
          face ? this->surface_.centres[index] : this->surface_.boundary.vertices[index].position;
        const double radius = face ? this->surface_.atom_radii[index] : p;
        position = on_segment(outside.position, inside.position,
                              sphere_crossing(outside.position, inside.position, centre, radius));
      }
      // Kept when no piece is nearer: certified on its patch when that needs no new list of
      // cutters (a convex patch, or one known uncut: the contour touches most patches, and
      // listing a torus's or concave patch's costs more than the searches it would save here),
      // else by a search.
      return (this->surface_.pieces.certifies_at_once(kind, index) &&
              this->surface_.pieces.certify(position, kind, index, piece)) ||
        this->surface_.holds(*this->local_, position, piece);
    };
    bool placed = along(inside.hint) || along(outside.hint);
    if (!placed)
    {
      const Vec guess = outside.position +
        outside.value / (outside.value - inside.value) * (inside.position - outside.position);
      const ClosestPiece near_guess = this->surface_.distance.closest(*this->local_, guess);
      placed = near_guess.distance > 0 && along(encode(near_guess.kind, near_guess.index));
    }
    if (!placed)
    {
      std::uint32_t hint = 0;
      position = segment_root(outside.position, outside.value, inside.position, inside.value,
                              [&](const Vec& x) { return this->value(x, hint); });
      piece = this->surface_.distance.closest(*this->local_, position);
    }
    return excluded_vertex(position, piece, this->surface_.boundary, this->surface_.centres,
                           this->surface_.atom_radii);
  }

private:
  ExcludedSurface surface_;
  std::vector<LocalPieces> levels_;    ///< per octree level, the pieces of its last focus
  const LocalPieces* local_ = nullptr; ///< the last focus
};

/// max over `spheres` of (R - |x - c|): the signed distance to their union's boundary outside
/// it, a lower bound of it inside; `deepest` (may be null) gets the maximising sphere. -1e300
/// for no sphere.
double union_depth(const std::vector<std::uint32_t>& spheres, const std::vector<Vec>& centres,
                   const std::vector<double>& radii, const Vec& x, std::uint32_t* deepest = nullptr)
{
  double best = -1e300;
  for (const std::uint32_t i : spheres)
  {
    const double d = radii[i] - (x - centres[i]).norm();
    if (d > best)
    {
      best = d;
      if (deepest)
      {
        *deepest = i;
      }
    }
  }
  return best;
}

class UnionSurfaceField final : public LocalContourField
{
public:
  UnionSurfaceField(const ProbeDistance& distance, const std::vector<Vec>& centres,
                    const std::vector<double>& radii)
    : distance_(distance)
    , centres_(centres)
    , radii_(radii)
  {
  }

  bool focus(int level, const Vec& centre, double radius, bool /*single_cell*/) override
  {
    if (static_cast<std::size_t>(level) >= this->levels_.size())
    {
      this->levels_.resize(static_cast<std::size_t>(level) + 1);
    }
    std::vector<std::uint32_t>& spheres = this->levels_[static_cast<std::size_t>(level)];
    spheres.clear();
    if (level == 0)
    {
      this->distance_.spheres_near(centre, radius, spheres);
    }
    else
    {
      this->distance_.spheres_near(this->levels_[static_cast<std::size_t>(level) - 1], centre,
                                   radius, spheres);
    }
    this->spheres_ = &spheres;
    // Every sphere reaching the ball is here, so the depth at the centre is exact where it
    // matters (above -radius).
    return std::abs(this->depth(centre)) <= radius;
  }

  double value(const Vec& x, std::uint32_t& hint) override
  {
    return this->depth(x, &hint);
  }

  ContourVertex vertex(const Sample& outside, const Sample& inside) override
  {
    ContourVertex vertex;
    vertex.position = segment_root(outside.position, outside.value, inside.position, inside.value,
                                   [&](const Vec& x) { return this->depth(x); });
    std::uint32_t sphere = 0;
    this->depth(vertex.position, &sphere);
    vertex.normal = (vertex.position - this->centres_[sphere]).normalized();
    vertex.atom = static_cast<std::int32_t>(sphere);
    vertex.piece = sphere;
    vertex.patch = static_cast<std::uint8_t>(SurfacePatch::Convex);
    return vertex;
  }

private:
  double depth(const Vec& x, std::uint32_t* deepest = nullptr) const
  {
    return union_depth(*this->spheres_, this->centres_, this->radii_, x, deepest);
  }

  const ProbeDistance& distance_;
  const std::vector<Vec>& centres_;
  const std::vector<double>& radii_;
  std::vector<std::vector<std::uint32_t>> levels_; ///< per octree level, its last focus's
  const std::vector<std::uint32_t>* spheres_ = nullptr;
};

/// Points onto the solvent-excluded surface: along the line from the nearest probe position,
/// to the probe's sphere, kept when no other probe position is nearer there.
class ExcludedSurfaceProjection final : public LocalSurfaceProjection
{
public:
  explicit ExcludedSurfaceProjection(const ExcludedSurface& surface)
    : surface_(surface)
  {
  }

  void focus(const Vec& centre, double radius) override
  {
    // Gathered when a point first needs the search: most are answered on their edge's patches.
    this->focus_centre_ = centre;
    this->focus_radius_ = radius;
    this->gathered_ = false;
  }

  bool project(const Vec& x, ContourVertex& vertex) override
  {
    const double p = this->surface_.probe;
    if (!this->gathered_)
    {
      this->surface_.distance.gather(this->focus_centre_, this->focus_radius_, this->surface_.limit,
                                     this->local_);
      this->gathered_ = true;
    }
    const ClosestPiece nearest = this->surface_.distance.closest(this->local_, x);
    const Vec away = x - nearest.point;
    const double gap = away.norm();
    if (nearest.kind == PieceKind::None || !(gap > 0))
    {
      return false;
    }
    const Vec position = nearest.point + p / gap * away;
    ClosestPiece piece;
    if (!this->surface_.holds(this->local_, position, piece))
    {
      return false;
    }
    vertex = excluded_vertex(position, piece, this->surface_.boundary, this->surface_.centres,
                             this->surface_.atom_radii);
    return true;
  }

  bool project_between(const Vec& x, const ContourVertex& from, const ContourVertex& to,
                       ContourVertex& vertex) override
  {
    // Onto a patch near the ends when certified there (see SesPieceProjection): the nearest
    // surface point inside the ball carrying the patch, else a surface point close to it.
    Vec position;
    ClosestPiece piece;
    if (this->surface_.pieces.nearest_near(x, { piece_kind(from.patch), from.piece },
                                           { piece_kind(to.patch), to.piece }, position, piece))
    {
      vertex = excluded_vertex(position, piece, this->surface_.boundary, this->surface_.centres,
                               this->surface_.atom_radii);
      return true;
    }
    return this->project(x, vertex);
  }

  /// Patches meet tangentially where one's atoms are among the other's: a convex patch and a
  /// torus or concave patch of its atom, a torus and a concave patch of both its atoms.
  bool smoothly_joined(const ContourVertex& a, const ContourVertex& b) const override
  {
    if (a.patch == b.patch && a.piece == b.piece)
    {
      return true;
    }
    const auto atoms_of = [&](const ContourVertex& v) {
      std::array<std::uint32_t, 3> atoms{};
      piece_spheres(this->surface_.boundary, piece_kind(v.patch), v.piece, atoms);
      return atoms;
    };
    const auto among = [](const std::array<std::uint32_t, 3>& some,
                          const std::array<std::uint32_t, 3>& all) {
      return std::all_of(some.begin(), some.end(), [&](std::uint32_t atom) {
        return std::find(all.begin(), all.end(), atom) != all.end();
      });
    };
    const auto first = atoms_of(a), second = atoms_of(b);
    return among(first, second) || among(second, first);
  }

  double piece_gap(const ContourVertex& a, const ContourVertex& b, const Vec& x) const override
  {
    if (a.patch != b.patch || a.piece != b.piece)
    {
      return std::numeric_limits<double>::quiet_NaN();
    }
    return std::abs(this->surface_.distance.piece_distance(x, piece_kind(a.patch), a.piece) -
                    this->surface_.probe);
  }

private:
  ExcludedSurface surface_;
  LocalPieces local_; ///< the pieces of the last focus, once gathered
  Vec focus_centre_ = Vec::Zero();
  double focus_radius_ = 0;
  bool gathered_ = false;
};

/// Points onto the boundary of a union of spheres: radially onto the sphere the point lies
/// deepest in (or nearest to), kept when no other sphere covers the foot.
class UnionSurfaceProjection final : public LocalSurfaceProjection
{
public:
  UnionSurfaceProjection(const ProbeDistance& distance, const std::vector<Vec>& centres,
                         const std::vector<double>& radii, double reach)
    : distance_(distance)
    , centres_(centres)
    , radii_(radii)
    , reach_(reach)
  {
  }

  void focus(const Vec& centre, double radius) override
  {
    this->spheres_.clear();
    this->distance_.spheres_near(centre, radius + this->reach_, this->spheres_);
  }

  bool project(const Vec& x, ContourVertex& vertex) override
  {
    std::uint32_t sphere = 0;
    const double deepest = union_depth(this->spheres_, this->centres_, this->radii_, x, &sphere);
    const Vec away = x - this->centres_[sphere];
    const double gap = away.norm();
    if (this->spheres_.empty() || std::abs(deepest) > this->reach_ || !(gap > 0))
    {
      return false;
    }
    // The foot, on that sphere, is on the boundary unless another sphere covers it.
    const Vec position = this->centres_[sphere] + this->radii_[sphere] / gap * away;
    if (union_depth(this->spheres_, this->centres_, this->radii_, position) > 1e-9)
    {
      return false;
    }
    vertex.position = position;
    vertex.normal = away / gap;
    vertex.atom = static_cast<std::int32_t>(sphere);
    vertex.piece = sphere;
    vertex.patch = static_cast<std::uint8_t>(SurfacePatch::Convex);
    return true;
  }

  double piece_gap(const ContourVertex& a, const ContourVertex& b, const Vec& x) const override
  {
    return a.piece == b.piece
      ? std::abs((x - this->centres_[a.piece]).norm() - this->radii_[a.piece])
      : std::numeric_limits<double>::quiet_NaN();
  }

private:
  const ProbeDistance& distance_;
  const std::vector<Vec>& centres_;
  const std::vector<double>& radii_;
  double reach_;
  std::vector<std::uint32_t> spheres_; ///< those near the last focus
};
} // namespace

std::unique_ptr<LocalContourField> excluded_surface_field(const ProbeDistance& distance,
                                                          const SesPieceProjection& pieces,
                                                          const SasBoundary& boundary,
                                                          const std::vector<Vec>& centres,
                                                          const std::vector<double>& atom_radii,
                                                          double probe, double limit)
{
  return std::make_unique<ExcludedSurfaceField>(
    ExcludedSurface{ distance, pieces, boundary, centres, atom_radii, probe, limit });
}

std::unique_ptr<LocalContourField> union_surface_field(const ProbeDistance& distance,
                                                       const std::vector<Vec>& centres,
                                                       const std::vector<double>& radii)
{
  return std::make_unique<UnionSurfaceField>(distance, centres, radii);
}

std::unique_ptr<LocalSurfaceProjection> excluded_surface_projection(
  const ProbeDistance& distance, const SesPieceProjection& pieces, const SasBoundary& boundary,
  const std::vector<Vec>& centres, const std::vector<double>& atom_radii, double probe,
  double limit)
{
  return std::make_unique<ExcludedSurfaceProjection>(
    ExcludedSurface{ distance, pieces, boundary, centres, atom_radii, probe, limit });
}

std::unique_ptr<LocalSurfaceProjection> union_surface_projection(const ProbeDistance& distance,
                                                                 const std::vector<Vec>& centres,
                                                                 const std::vector<double>& radii,
                                                                 double reach)
{
  return std::make_unique<UnionSurfaceProjection>(distance, centres, radii, reach);
}

} // namespace mesolens
