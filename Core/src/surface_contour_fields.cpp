// SPDX-License-Identifier: GPL-3.0-or-later
#include <Eigen/Dense>

#include "surface_contour_fields.h"

#include "segment_roots.h"

#include "mesolens/molecular_surface.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace mesolens {

namespace {
using Vec = Eigen::Vector3d;

/// A piece as a field's hint: its kind in the top two bits, its index below.
constexpr std::uint32_t index_mask = (1u << 30) - 1;
std::uint32_t encode(PieceKind kind, std::uint32_t index)
{
  return (static_cast<std::uint32_t>(kind) << 30) | (index & index_mask);
}

class ExcludedSurfaceField final : public LocalContourField
{
public:
  ExcludedSurfaceField(const ProbeDistance& distance, const SasBoundary& boundary,
                       const std::vector<Vec>& centres, const std::vector<double>& atom_radii,
                       double probe, double limit)
    : distance_(distance)
    , boundary_(boundary)
    , centres_(centres)
    , atom_radii_(atom_radii)
    , probe_(probe)
    , limit_(limit)
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
      // A cell asks few queries: its parent's pieces serve them, unrefined.
      const LocalPieces& parent = this->levels_[static_cast<std::size_t>(level) - 1];
      this->local_ = &parent;
      // Whether the distance lies within the radius of the probe's: no need to look farther.
      const double beyond = this->probe_ + radius * (1.0 + 1e-9);
      return std::abs(this->distance_.closest(parent, centre, {}, beyond).distance -
                      this->probe_) <= radius;
    }
    LocalPieces& local = this->levels_[static_cast<std::size_t>(level)];
    if (level == 0)
    {
      this->distance_.gather(centre, radius, this->limit_, local);
    }
    else
    {
      this->distance_.refine(this->levels_[static_cast<std::size_t>(level) - 1], centre, radius,
                             local);
    }
    this->local_ = &local;
    return std::abs(local.centre_distance - this->probe_) <= radius;
  }

  double value(const Vec& x, std::uint32_t& hint) override
  {
    const ClosestPiece piece = this->distance_.closest(*this->local_, x);
    hint = encode(piece.kind, piece.index);
    return piece.distance - this->probe_;
  }

  ContourVertex vertex(const Sample& outside, const Sample& inside) override
  {
    const double p = this->probe_;
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
        return this->distance_.piece_distance(x, kind, index) - p;
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
        const Vec& centre = face ? this->centres_[index] : this->boundary_.vertices[index].position;
        const double radius = face ? this->atom_radii_[index] : p;
        position = on_segment(outside.position, inside.position,
                              sphere_crossing(outside.position, inside.position, centre, radius));
      }
      // Kept when no piece is nearer: the search need not look past the probe radius.
      piece = this->distance_.closest(*this->local_, position, {}, p + 1e-6);
      return std::abs(piece.distance - p) <= 1e-7;
    };
    bool placed = along(inside.hint) || along(outside.hint);
    if (!placed)
    {
      const Vec guess = outside.position +
        outside.value / (outside.value - inside.value) * (inside.position - outside.position);
      const ClosestPiece near_guess = this->distance_.closest(*this->local_, guess);
      placed = near_guess.distance > 0 && along(encode(near_guess.kind, near_guess.index));
    }
    if (!placed)
    {
      std::uint32_t hint = 0;
      position = segment_root(outside.position, outside.value, inside.position, inside.value,
                              [&](const Vec& x) { return this->value(x, hint); });
      piece = this->distance_.closest(*this->local_, position);
    }
    ContourVertex vertex;
    vertex.position = position;
    const Vec towards_probe = piece.point - position;
    vertex.normal = towards_probe.norm() > 0 ? Vec(towards_probe.normalized()) : Vec::UnitZ();
    vertex.piece = piece.index;
    // The atom: the face's own, else the one whose surface is nearest.
    std::array<std::uint32_t, 3> candidates{};
    int candidate_count = 0;
    switch (piece.kind)
    {
      case PieceKind::Arc:
        vertex.patch = static_cast<std::uint8_t>(SurfacePatch::Toroidal);
        candidates = { this->boundary_.arcs[piece.index].first,
                       this->boundary_.arcs[piece.index].second, 0 };
        candidate_count = 2;
        break;
      case PieceKind::Vertex:
        vertex.patch = static_cast<std::uint8_t>(SurfacePatch::Concave);
        candidates = this->boundary_.vertices[piece.index].spheres;
        candidate_count = 3;
        break;
      default:
        vertex.patch = static_cast<std::uint8_t>(SurfacePatch::Convex);
        candidates = { piece.index, 0, 0 };
        candidate_count = 1;
    }
    double nearest = 1e300;
    for (int c = 0; c < candidate_count; ++c)
    {
      const double gap =
        (position - this->centres_[candidates[c]]).norm() - this->atom_radii_[candidates[c]];
      if (gap < nearest)
      {
        nearest = gap;
        vertex.atom = static_cast<std::int32_t>(candidates[c]);
      }
    }
    return vertex;
  }

private:
  const ProbeDistance& distance_;
  const SasBoundary& boundary_;
  const std::vector<Vec>& centres_;
  const std::vector<double>& atom_radii_;
  double probe_, limit_;
  std::vector<LocalPieces> levels_;    ///< per octree level, the pieces of its last focus
  const LocalPieces* local_ = nullptr; ///< the last focus
};

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
    double best = -1e300;
    for (const std::uint32_t i : *this->spheres_)
    {
      const double d = this->radii_[i] - (x - this->centres_[i]).norm();
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

  const ProbeDistance& distance_;
  const std::vector<Vec>& centres_;
  const std::vector<double>& radii_;
  std::vector<std::vector<std::uint32_t>> levels_; ///< per octree level, its last focus's
  const std::vector<std::uint32_t>* spheres_ = nullptr;
};
} // namespace

std::unique_ptr<LocalContourField> excluded_surface_field(const ProbeDistance& distance,
                                                          const SasBoundary& boundary,
                                                          const std::vector<Vec>& centres,
                                                          const std::vector<double>& atom_radii,
                                                          double probe, double limit)
{
  return std::make_unique<ExcludedSurfaceField>(distance, boundary, centres, atom_radii, probe,
                                                limit);
}

std::unique_ptr<LocalContourField> union_surface_field(const ProbeDistance& distance,
                                                       const std::vector<Vec>& centres,
                                                       const std::vector<double>& radii)
{
  return std::make_unique<UnionSurfaceField>(distance, centres, radii);
}

} // namespace mesolens
