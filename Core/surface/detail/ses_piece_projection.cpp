// SPDX-License-Identifier: GPL-3.0-or-later
#include <Eigen/Dense>

#include "surface/detail/ses_piece_projection.h"

#include "surface/detail/ses_patches.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace mesolens {

namespace {
using Vec = Eigen::Vector3d;
/// How far (Å) a point may lie off the sphere or torus it is said to be on.
constexpr double on_carrier = 1e-9;
/// How deep (Å) a neighbour may cover a convex point's probe position: as far as the general
/// search lets a point count as on the surface.
constexpr double covered = 1e-7;
/// Directions this close to a cone's side count as inside (the side is shared with the
/// neighbouring patch, which holds the point as well).
constexpr double side_slack = 1e-12;

/// The point of the sphere about `centre` of `radius` nearest `x` (false at the centre).
bool onto_sphere(const Vec& x, const Vec& centre, double radius, Vec& point)
{
  const Vec offset = x - centre;
  const double gap = offset.norm();
  if (!(gap > 0))
  {
    return false;
  }
  point = centre + (radius / gap) * offset;
  return true;
}

/// The point of `arc`'s whole circle nearest `x` (false on the axis).
bool nearest_on_circle(const SasArc& arc, const Vec& x, Vec& point)
{
  const Vec offset = x - arc.centre;
  const Vec radial = offset - offset.dot(arc.axis) * arc.axis;
  const double from_axis = radial.norm();
  if (!(from_axis > 0))
  {
    return false;
  }
  point = arc.centre + (arc.radius / from_axis) * radial;
  return true;
}

} // namespace

SesPieceProjection::SesPieceProjection(const std::vector<Vec>& centres,
                                       const std::vector<double>& atom_radii, double probe,
                                       const SasBoundary& boundary, const ProbeDistance& distance)
  : centres_(centres)
  , atom_radii_(atom_radii)
  , probe_(probe)
  , boundary_(boundary)
  , distance_(distance)
  , arc_cutters_(boundary.arcs.size())
  , vertex_cutters_(boundary.vertices.size())
{
  // Each atom's arcs and vertices.
  const auto by_atom = [&](std::size_t item_count, const auto& atoms_of,
                           std::vector<std::uint32_t>& start, std::vector<std::uint32_t>& items) {
    start.assign(centres.size() + 1, 0);
    for (std::size_t k = 0; k < item_count; ++k)
    {
      atoms_of(k, [&](std::uint32_t atom) { ++start[atom + 1]; });
    }
    for (std::size_t i = 0; i < centres.size(); ++i)
    {
      start[i + 1] += start[i];
    }
    items.resize(start.back());
    std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
    for (std::size_t k = 0; k < item_count; ++k)
    {
      atoms_of(k, [&](std::uint32_t atom) { items[next[atom]++] = static_cast<std::uint32_t>(k); });
    }
  };
  by_atom(
    boundary.arcs.size(),
    [&](std::size_t k, const auto& add) {
      add(boundary.arcs[k].first);
      add(boundary.arcs[k].second);
    },
    this->atom_arc_start_, this->atom_arc_items_);
  by_atom(
    boundary.vertices.size(),
    [&](std::size_t k, const auto& add) {
      for (const std::uint32_t atom : boundary.vertices[k].spheres)
      {
        add(atom);
      }
    },
    this->atom_vertex_start_, this->atom_vertex_items_);
  this->vertex_cones_.resize(boundary.vertices.size());
  for (std::size_t k = 0; k < boundary.vertices.size(); ++k)
  {
    const SasVertex& vertex = boundary.vertices[k];
    Vec u[3];
    for (int s = 0; s < 3; ++s)
    {
      u[s] = (centres[vertex.spheres[std::size_t(s)]] - vertex.position).normalized();
    }
    VertexCone& cone = this->vertex_cones_[k];
    cone.orientation = u[0].dot(u[1].cross(u[2]));
    for (int s = 0; s < 3; ++s)
    {
      cone.sides[s] = u[(s + 1) % 3].cross(u[(s + 2) % 3]);
    }
  }
}

void SesPieceProjection::take_uncut_patches(const std::vector<char>& arc_uncut,
                                            const std::vector<char>& vertex_uncut)
{
  const auto take = [](const std::vector<char>& uncut, std::vector<Cutters>& lists) {
    for (std::size_t k = 0; k < std::min(uncut.size(), lists.size()); ++k)
    {
      if (uncut[k])
      {
        lists[k].arcs.clear();
        lists[k].vertices.clear();
        lists[k].state.store(Cutters::listed, std::memory_order_release);
      }
    }
  };
  take(arc_uncut, this->arc_cutters_);
  take(vertex_uncut, this->vertex_cutters_);
}

bool SesPieceProjection::certifies_at_once(PieceKind kind, std::uint32_t index) const
{
  switch (kind)
  {
    case PieceKind::Face:
      return true;
    case PieceKind::Arc:
      return this->arc_cutters_[index].state.load(std::memory_order_acquire) == Cutters::listed;
    case PieceKind::Vertex:
      return this->vertex_cutters_[index].state.load(std::memory_order_acquire) == Cutters::listed;
    case PieceKind::None:
      break;
  }
  return false;
}

void SesPieceProjection::list_cutters(bool torus, std::uint32_t k, Cutters& cutters) const
{
  cutters.arcs.clear();
  cutters.vertices.clear();
  if (torus)
  {
    toroidal_patch_cutters(this->centres_, this->probe_, this->boundary_, this->distance_, k,
                           cutters.arcs, cutters.vertices);
  }
  else
  {
    concave_patch_cutters(this->centres_, this->probe_, this->boundary_, this->distance_, k,
                          cutters.arcs, cutters.vertices);
  }
}

bool SesPieceProjection::nearest(const Vec& x, PieceKind kind, std::uint32_t index, Vec& point,
                                 ClosestPiece& nearest) const
{
  switch (kind)
  {
    case PieceKind::Face:
      return onto_sphere(x, this->centres_[index], this->atom_radii_[index], point) &&
        this->certify_face(point, index, nearest);
    case PieceKind::Vertex:
      return onto_sphere(x, this->boundary_.vertices[index].position, this->probe_, point) &&
        this->certify_vertex(point, index, nearest);
    case PieceKind::Arc: {
      // The probe's nearest position on the arc's circle, then radially from it.
      Vec position;
      return nearest_on_circle(this->boundary_.arcs[index], x, position) &&
        onto_sphere(x, position, this->probe_, point) && this->certify_arc(point, index, nearest);
    }
    case PieceKind::None:
      break;
  }
  return false;
}

bool SesPieceProjection::nearest_near(const Vec& x, const std::pair<PieceKind, std::uint32_t>& a,
                                      const std::pair<PieceKind, std::uint32_t>& b, Vec& point,
                                      ClosestPiece& nearest) const
{
  return this->nearest(x, a.first, a.second, point, nearest) ||
    (b != a && this->nearest(x, b.first, b.second, point, nearest)) ||
    this->visit_pieces_near(a, b, [&](PieceKind kind, std::uint32_t index) {
      return this->nearest(x, kind, index, point, nearest);
    });
}

bool SesPieceProjection::visit_pieces_near(
  const std::pair<PieceKind, std::uint32_t>& a, const std::pair<PieceKind, std::uint32_t>& b,
  const std::function<bool(PieceKind, std::uint32_t)>& visit) const
{
  // The atoms of both pieces (at most six), each marked with its place among them plus one.
  thread_local std::vector<std::uint8_t> place;
  if (place.size() < this->centres_.size())
  {
    place.assign(this->centres_.size(), 0);
  }
  std::uint32_t atoms[6];
  int atom_count = 0;
  const auto add_atoms = [&](const std::pair<PieceKind, std::uint32_t>& piece) {
    std::array<std::uint32_t, 3> spheres{};
    const int count = piece_spheres(this->boundary_, piece.first, piece.second, spheres);
    for (int c = 0; c < count; ++c)
    {
      const std::uint32_t atom = spheres[std::size_t(c)];
      if (place[atom] == 0)
      {
        atoms[atom_count] = atom;
        place[atom] = static_cast<std::uint8_t>(++atom_count);
      }
    }
  };
  add_atoms(a);
  add_atoms(b);
  const auto other_than_ends = [&](PieceKind kind, std::uint32_t index) {
    return !(a.first == kind && a.second == index) && !(b.first == kind && b.second == index);
  };
  const auto search = [&] {
    for (int n = 0; n < atom_count; ++n)
    {
      // Each arc once, from whichever of its atoms comes first among them.
      for (std::uint32_t e = this->atom_arc_start_[atoms[n]];
           e < this->atom_arc_start_[atoms[n] + 1]; ++e)
      {
        const std::uint32_t k = this->atom_arc_items_[e];
        const SasArc& arc = this->boundary_.arcs[k];
        const std::uint32_t other = arc.first == atoms[n] ? arc.second : arc.first;
        if (place[other] > n + 1 && other_than_ends(PieceKind::Arc, k) && visit(PieceKind::Arc, k))
        {
          return true;
        }
      }
    }
    for (int n = 0; n < atom_count; ++n)
    {
      // Each vertex from its lowest atom.
      for (std::uint32_t e = this->atom_vertex_start_[atoms[n]];
           e < this->atom_vertex_start_[atoms[n] + 1]; ++e)
      {
        const std::uint32_t k = this->atom_vertex_items_[e];
        const auto& spheres = this->boundary_.vertices[k].spheres;
        if (spheres[0] == atoms[n] && place[spheres[1]] != 0 && place[spheres[2]] != 0 &&
            other_than_ends(PieceKind::Vertex, k) && visit(PieceKind::Vertex, k))
        {
          return true;
        }
      }
    }
    for (int n = 0; n < atom_count; ++n)
    {
      if (other_than_ends(PieceKind::Face, atoms[n]) && visit(PieceKind::Face, atoms[n]))
      {
        return true;
      }
    }
    return false;
  };
  const bool found = search();
  for (int n = 0; n < atom_count; ++n)
  {
    place[atoms[n]] = 0;
  }
  return found;
}

bool SesPieceProjection::certify(const Vec& y, PieceKind kind, std::uint32_t index,
                                 ClosestPiece& nearest) const
{
  switch (kind)
  {
    case PieceKind::Face:
      return this->certify_face(y, index, nearest);
    case PieceKind::Arc:
      return this->certify_arc(y, index, nearest);
    case PieceKind::Vertex:
      return this->certify_vertex(y, index, nearest);
    case PieceKind::None:
      break;
  }
  return false;
}

bool SesPieceProjection::certify_face(const Vec& y, std::uint32_t i, ClosestPiece& nearest) const
{
  const double p = this->probe_, r = this->atom_radii_[i];
  const Vec offset = y - this->centres_[i];
  const double gap = offset.norm();
  if (!(std::abs(gap - r) <= on_carrier))
  {
    return false;
  }
  // The probe touching the atom at y must fit: outside every neighbour's inflated sphere.
  const Vec probe_position = this->centres_[i] + ((r + p) / gap) * offset;
  for (const std::uint32_t j : this->boundary_.neighbours[i])
  {
    const double least = this->atom_radii_[j] + p - covered;
    if ((probe_position - this->centres_[j]).squaredNorm() < least * least)
    {
      return false;
    }
  }
  nearest = { p, probe_position, PieceKind::Face, i };
  return true;
}

bool SesPieceProjection::certify_arc(const Vec& y, std::uint32_t k, ClosestPiece& nearest) const
{
  const double p = this->probe_;
  const SasArc& arc = this->boundary_.arcs[k];
  // The probe's position is on y's side of the axis: no other position on its circle comes
  // nearer to y, even where the probe passes between the atoms.
  Vec position;
  if (!nearest_on_circle(arc, y, position))
  {
    return false;
  }
  const Vec towards_y = y - position;
  const Vec radial = position - arc.centre;
  if (!(std::abs(towards_y.norm() - p) <= on_carrier) ||
      !this->distance_.within_span(k, radial.dot(arc.e1), radial.dot(arc.e2)))
  {
    return false;
  }
  // Between the directions to the two atoms (all three lie in the plane of the axis and y).
  const Vec to_first = (this->centres_[arc.first] - position).normalized();
  const Vec to_second = (this->centres_[arc.second] - position).normalized();
  const Vec normal = to_first.cross(to_second);
  if (!(normal.squaredNorm() > 0) || to_first.cross(towards_y).dot(normal) < -side_slack ||
      towards_y.cross(to_second).dot(normal) < -side_slack || !this->clear_of_cutters(y, true, k))
  {
    return false;
  }
  nearest = { p, position, PieceKind::Arc, k };
  return true;
}

bool SesPieceProjection::certify_vertex(const Vec& y, std::uint32_t k, ClosestPiece& nearest) const
{
  const double p = this->probe_;
  const SasVertex& vertex = this->boundary_.vertices[k];
  const Vec towards_y = y - vertex.position;
  if (!(std::abs(towards_y.norm() - p) <= on_carrier))
  {
    return false;
  }
  // Within the cone of the directions to the three atoms.
  const VertexCone& cone = this->vertex_cones_[k];
  if (!(std::abs(cone.orientation) > 0))
  {
    return false;
  }
  for (int s = 0; s < 3; ++s)
  {
    if (towards_y.dot(cone.sides[s]) * cone.orientation < -side_slack)
    {
      return false;
    }
  }
  if (!this->clear_of_cutters(y, false, k))
  {
    return false;
  }
  nearest = { p, vertex.position, PieceKind::Vertex, k };
  return true;
}

bool SesPieceProjection::clear_of_cutters(const Vec& y, bool torus, std::uint32_t k) const
{
  // Listed once, by whichever thread comes first; one that finds the list being made lists its
  // own copy (the same) rather than wait.
  Cutters& shared = (torus ? this->arc_cutters_ : this->vertex_cutters_)[k];
  const Cutters* cutters = &shared;
  thread_local Cutters own;
  std::uint8_t state = shared.state.load(std::memory_order_acquire);
  if (state != Cutters::listed)
  {
    if (state == Cutters::unlisted &&
        shared.state.compare_exchange_strong(state, Cutters::listing, std::memory_order_acq_rel))
    {
      this->list_cutters(torus, k, shared);
      shared.state.store(Cutters::listed, std::memory_order_release);
    }
    else if (state != Cutters::listed)
    {
      this->list_cutters(torus, k, own);
      cutters = &own;
    }
  }
  const double least = this->probe_ - covered;
  for (const std::uint32_t arc : cutters->arcs)
  {
    double d = 0;
    if (this->distance_.arc_nearer(arc, y, least, d))
    {
      return false;
    }
  }
  for (const std::uint32_t vertex : cutters->vertices)
  {
    if ((y - this->boundary_.vertices[vertex].position).norm() < least)
    {
      return false;
    }
  }
  return true;
}

} // namespace mesolens
