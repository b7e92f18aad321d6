// SPDX-License-Identifier: GPL-3.0-or-later
#include <Eigen/Dense>

#include "probe_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mesolens {

namespace {
using Vec = Eigen::Vector3d;
constexpr double two_pi = 6.28318530717958647692;

/// Compressed rows from (cell, item) pairs.
void build_rows(std::size_t cell_count, std::vector<std::pair<std::int64_t, std::uint32_t>>& pairs,
                std::vector<std::uint32_t>& starts, std::vector<std::uint32_t>& items)
{
  std::sort(pairs.begin(), pairs.end());
  starts.assign(cell_count + 1, 0);
  for (const auto& pair : pairs)
  {
    ++starts[static_cast<std::size_t>(pair.first) + 1];
  }
  for (std::size_t c = 0; c < cell_count; ++c)
  {
    starts[c + 1] += starts[c];
  }
  items.resize(pairs.size());
  for (std::size_t k = 0; k < pairs.size(); ++k)
  {
    items[k] = pairs[k].second;
  }
}
} // namespace

ProbeDistance::ProbeDistance(const std::vector<Vec>& centres, const std::vector<double>& radii,
                             const SasBoundary& boundary, double reach, double cell_at_least)
  : centres_(centres)
  , radii_(radii)
  , boundary_(boundary)
  , reach_(reach)
{
  double largest = 0;
  Vec low = Vec::Constant(std::numeric_limits<double>::max());
  Vec high = -low;
  for (std::size_t i = 0; i < centres.size(); ++i)
  {
    largest = std::max(largest, radii[i]);
    low = low.cwiseMin(centres[i]);
    high = high.cwiseMax(centres[i]);
  }
  // Every sphere holding a point, and every piece within reach of it, lies in the 27 cells
  // around the point's cell.
  // Fine cells, visited out to the radius each query needs.
  this->largest_ = largest;
  this->outside_exact_ = std::max({ largest, reach, cell_at_least });
  this->cell_ = std::max(0.25 * this->outside_exact_, 0.5);
  if (centres.empty())
  {
    low = high = Vec::Zero();
  }
  const double margin = 2.0 * this->outside_exact_;
  this->origin_ = low - Vec::Constant(margin);
  for (int a = 0; a < 3; ++a)
  {
    this->dims_[a] =
      static_cast<std::int64_t>(std::ceil((high[a] - low[a] + 2 * margin) / this->cell_)) + 1;
  }
  const std::size_t cell_count =
    static_cast<std::size_t>(this->dims_[0] * this->dims_[1] * this->dims_[2]);
  std::array<std::int64_t, 3> ijk{};
  std::vector<std::pair<std::int64_t, std::uint32_t>> pairs;
  for (std::size_t i = 0; i < centres.size(); ++i)
  {
    pairs.emplace_back(this->cell_of(centres[i], ijk), static_cast<std::uint32_t>(i));
  }
  build_rows(cell_count, pairs, this->sphere_start_, this->sphere_items_);
  pairs.clear();
  for (std::size_t k = 0; k < boundary.vertices.size(); ++k)
  {
    pairs.emplace_back(this->cell_of(boundary.vertices[k].position, ijk),
                       static_cast<std::uint32_t>(k));
  }
  build_rows(cell_count, pairs, this->vertex_start_, this->vertex_items_);
  pairs.clear();
  std::vector<Vec> middles;
  // Arcs by the middles of their pieces of at most 22.5 degrees, each within arc_extent_ of its
  // middle (small: queries look a little beyond their radius).
  for (std::size_t k = 0; k < boundary.arcs.size(); ++k)
  {
    const SasArc& arc = boundary.arcs[k];
    const int pieces = std::max(1, static_cast<int>(std::ceil(arc.span / (two_pi / 16))));
    const double piece_span = arc.span / pieces;
    this->arc_extent_ = std::max(this->arc_extent_, 2.0 * arc.radius * std::sin(0.25 * piece_span));
    for (int piece = 0; piece < pieces; ++piece)
    {
      const Vec middle = arc.point(arc.start + (piece + 0.5) * piece_span);
      pairs.emplace_back(this->cell_of(middle, ijk), static_cast<std::uint32_t>(k));
      middles.push_back(middle);
    }
  }
  this->arc_extent_ += 1e-9;
  {
    // Entries point at (arc, piece middle) pairs, in cell order.
    std::vector<std::pair<std::int64_t, std::uint32_t>> entries(pairs.size());
    for (std::size_t e = 0; e < pairs.size(); ++e)
    {
      entries[e] = { pairs[e].first, static_cast<std::uint32_t>(e) };
    }
    build_rows(cell_count, entries, this->arc_start_, this->arc_entries_);
    this->arc_items_.resize(pairs.size());
    this->arc_piece_middle_.resize(pairs.size());
    for (std::size_t e = 0; e < this->arc_entries_.size(); ++e)
    {
      const std::uint32_t original = this->arc_entries_[e];
      this->arc_items_[e] = pairs[original].second;
      this->arc_piece_middle_[e] = middles[original];
      this->arc_entries_[e] = static_cast<std::uint32_t>(e);
    }
  }
}

std::int64_t ProbeDistance::cell_of(const Vec& x, std::array<std::int64_t, 3>& ijk) const
{
  for (int a = 0; a < 3; ++a)
  {
    ijk[a] =
      std::clamp(static_cast<std::int64_t>(std::floor((x[a] - this->origin_[a]) / this->cell_)),
                 std::int64_t(0), this->dims_[a] - 1);
  }
  return ijk[0] + this->dims_[0] * (ijk[1] + this->dims_[1] * ijk[2]);
}

template<typename Visit>
void ProbeDistance::for_cells(const Vec& x, double radius, const std::vector<std::uint32_t>& starts,
                              const std::vector<std::uint32_t>& items, Visit&& visit) const
{
  std::array<std::int64_t, 3> from{}, to{};
  this->cell_of(x - Vec::Constant(radius), from);
  this->cell_of(x + Vec::Constant(radius), to);
  for (std::int64_t z = from[2]; z <= to[2]; ++z)
    for (std::int64_t y = from[1]; y <= to[1]; ++y)
    {
      // Cells along x are consecutive rows: one range.
      const std::int64_t row = this->dims_[0] * (y + this->dims_[1] * z);
      const std::uint32_t begin = starts[static_cast<std::size_t>(row + from[0])];
      const std::uint32_t end = starts[static_cast<std::size_t>(row + to[0] + 1)];
      for (std::uint32_t k = begin; k < end; ++k)
      {
        visit(items[k]);
      }
    }
}

double ProbeDistance::piece_distance(const Vec& x, PieceKind kind, std::uint32_t index) const
{
  switch (kind)
  {
    case PieceKind::Face:
      return this->radii_[index] - (x - this->centres_[index]).norm();
    case PieceKind::Arc: {
      const SasArc& arc = this->boundary_.arcs[index];
      const Vec v = x - arc.centre;
      const double along = v.dot(arc.axis);
      const double radial = (v - along * arc.axis).norm();
      return std::sqrt(along * along + (radial - arc.radius) * (radial - arc.radius));
    }
    case PieceKind::Vertex:
      return (x - this->boundary_.vertices[index].position).norm();
    default:
      return this->reach_;
  }
}

void ProbeDistance::vertices_within(const Vec& x, double radius,
                                    const std::function<void(std::uint32_t)>& visit) const
{
  this->for_cells(x, radius, this->vertex_start_, this->vertex_items_, [&](std::uint32_t k) {
    if ((this->boundary_.vertices[k].position - x).squaredNorm() < radius * radius)
    {
      visit(k);
    }
  });
}

double ProbeDistance::union_depth(const Vec& x, std::uint32_t* sphere) const
{
  double depth = -this->reach_;
  this->for_cells(x, this->outside_exact_, this->sphere_start_, this->sphere_items_,
                  [&](std::uint32_t i) {
                    const double d = this->radii_[i] - (x - this->centres_[i]).norm();
                    if (d > depth)
                    {
                      depth = d;
                      if (sphere)
                      {
                        *sphere = i;
                      }
                    }
                  });
  return depth;
}

ClosestPiece ProbeDistance::closest(const Vec& x, const Filter& filter, double limit) const
{
  using Mode = Filter::Mode;
  const bool filtered = filter.mode != Mode::All;
  const auto has = [&](std::uint32_t sphere) {
    return sphere == filter.atoms[0] || sphere == filter.atoms[1] ||
      (filter.mode == Mode::ConcaveCutters && sphere == filter.atoms[2]);
  };
  ClosestPiece best;
  // Spheres holding x, deepest last: the nearest exposed face point is the radial projection
  // onto the least deep one whose projection no neighbour covers.
  struct Holder
  {
    double depth;
    std::uint32_t sphere;
  };
  Holder holders[128];
  std::size_t holder_count = 0;
  double deepest = -std::numeric_limits<double>::max();
  std::uint32_t deepest_sphere = 0;
  bool inside = false;
  this->for_cells(x, this->largest_, this->sphere_start_, this->sphere_items_,
                  [&](std::uint32_t i) {
                    const double squared = (x - this->centres_[i]).squaredNorm();
                    const double r = this->radii_[i];
                    if (squared >= r * r)
                    {
                      return; // a root only for the spheres holding x
                    }
                    inside = true;
                    const double d = r - std::sqrt(squared);
                    if (d > deepest)
                    {
                      deepest = d;
                      deepest_sphere = i;
                    }
                    if (d < this->reach_ && holder_count < 128)
                    {
                      holders[holder_count++] = { d, i };
                    }
                  });
  if (!inside)
  {
    // Outside every sphere: the nearest may lie farther.
    this->for_cells(x, this->outside_exact_, this->sphere_start_, this->sphere_items_,
                    [&](std::uint32_t i) {
                      const double d = this->radii_[i] - (x - this->centres_[i]).norm();
                      if (d > deepest)
                      {
                        deepest = d;
                        deepest_sphere = i;
                      }
                    });
  }
  if (deepest == -std::numeric_limits<double>::max())
  {
    best.distance = -this->reach_; // far from every sphere
    return best;
  }
  // Probe positions themselves (on the boundary, to rounding) count as inside when a query
  // leaves pieces out: it asks how far the other pieces are.
  if (deepest <= 0 && !(filtered && deepest > -1e-9))
  {
    // Outside the union: the nearest point of the nearest sphere.
    const Vec& c = this->centres_[deepest_sphere];
    best.distance = deepest;
    best.point = c + this->radii_[deepest_sphere] * (x - c).normalized();
    best.kind = PieceKind::Face;
    best.index = deepest_sphere;
    return best;
  }
  best.distance = limit > 0 ? std::min(limit, this->reach_) : this->reach_;
  std::sort(holders, holders + holder_count, [](const Holder& a, const Holder& b) {
    return a.depth < b.depth || (a.depth == b.depth && a.sphere < b.sphere);
  });
  for (std::size_t k = 0; k < holder_count; ++k)
  {
    if (holders[k].depth >= best.distance)
    {
      break; // sorted: no nearer face follows
    }
    const std::uint32_t i = holders[k].sphere;
    if (filtered)
    {
      break; // no face cuts a torus or concave patch
    }
    const Vec offset = x - this->centres_[i];
    const double length = offset.norm();
    if (length == 0)
    {
      continue;
    }
    const Vec y = this->centres_[i] + this->radii_[i] / length * offset;
    bool covered = this->boundary_.area[i] <= 0;
    for (const std::uint32_t j : this->boundary_.neighbours[i])
    {
      const double rj = this->radii_[j];
      if ((y - this->centres_[j]).squaredNorm() < rj * rj * (1.0 - 1e-12))
      {
        covered = true;
        break;
      }
    }
    if (!covered)
    {
      best.distance = holders[k].depth;
      best.point = y;
      best.kind = PieceKind::Face;
      best.index = i;
      break;
    }
  }
  std::uint32_t last_arc = UINT32_MAX;
  this->for_cells(
    x, best.distance + this->arc_extent_, this->arc_start_, this->arc_entries_,
    [&](std::uint32_t entry) {
      // A piece whose bounding ball lies beyond the best so far is skipped cheaply.
      const double reach = best.distance + this->arc_extent_;
      if ((x - this->arc_piece_middle_[entry]).squaredNorm() >= reach * reach)
      {
        return;
      }
      const std::uint32_t k = this->arc_items_[entry];
      if (k == last_arc)
      {
        return; // the next piece of the same arc
      }
      last_arc = k;
      const SasArc& arc = this->boundary_.arcs[k];
      if (filtered)
      {
        const bool first = has(arc.first), second = has(arc.second);
        const bool pinched_pair =
          filter.mode == Mode::ConcaveCutters && first && second && arc.radius < filter.probe;
        if ((first || second) && !pinched_pair)
        {
          return;
        }
      }
      const Vec v = x - arc.centre;
      const double along = v.dot(arc.axis);
      const Vec across = v - along * arc.axis;
      const double radial = across.norm();
      const double distance =
        std::sqrt(along * along + (radial - arc.radius) * (radial - arc.radius));
      if (distance >= best.distance)
      {
        return;
      }
      double azimuth = arc.start;
      if (radial > 1e-12)
      {
        azimuth = std::atan2(across.dot(arc.e2), across.dot(arc.e1));
        double offset = std::fmod(azimuth - arc.start, two_pi);
        if (offset < 0)
        {
          offset += two_pi;
        }
        if (offset > arc.span)
        {
          return; // nearest circle point not on the exposed arc: an end vertex is nearer
        }
      }
      best.distance = distance;
      best.point = arc.point(azimuth);
      best.kind = PieceKind::Arc;
      best.index = k;
    });
  this->for_cells(x, best.distance, this->vertex_start_, this->vertex_items_, [&](std::uint32_t k) {
    const double distance = (x - this->boundary_.vertices[k].position).norm();
    const auto& spheres = this->boundary_.vertices[k].spheres;
    if (distance < best.distance &&
        !(filter.mode == Mode::ConcaveCutters ||
          (filter.mode == Mode::TorusCutters &&
           (has(spheres[0]) || has(spheres[1]) || has(spheres[2])))))
    {
      best.distance = distance;
      best.point = this->boundary_.vertices[k].position;
      best.kind = PieceKind::Vertex;
      best.index = k;
    }
  });
  return best;
}

} // namespace mesolens
