// SPDX-License-Identifier: GPL-3.0-or-later
#include <Eigen/Dense>

#include "surface/detail/probe_distance.h"

#include "mesolens/common/errors.h"

#include "surface/detail/balanced_loop.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

namespace mesolens {

namespace {
using Vec = Eigen::Vector3d;
constexpr double two_pi = 6.28318530717958647692;
/// The most rows of cells the index may have (three tables of 4 bytes per row: 120 MB).
constexpr double largest_row_count = 1e7;
/// Empty cells a row's span may bridge (4 bytes each) before the row is split in two spans
/// (12 bytes and a step more for queries crossing the gap).
constexpr std::int64_t largest_span_gap = 16;

/// Sorts pieces by distance; lists refined from a parent's come nearly sorted, where insertion
/// is linear.
void sort_nearly_sorted(std::vector<std::pair<double, std::uint32_t>>& pieces)
{
  for (std::size_t k = 1; k < pieces.size(); ++k)
  {
    const auto piece = pieces[k];
    std::size_t j = k;
    for (; j > 0 && piece < pieces[j - 1]; --j)
    {
      pieces[j] = pieces[j - 1];
    }
    pieces[j] = piece;
  }
}

constexpr std::size_t max_holders = 128; // spheres holding one point: far fewer in practice

/// How far from a ball's centre its points' nearest pieces may lie: a point lies within
/// centre_distance + radius of the boundary (1-Lipschitz), and searches stop at the limit.
double local_bound(const LocalPieces& local)
{
  return std::min(local.centre_distance + local.radius, local.limit) + local.radius;
}
} // namespace

ProbeDistance::ProbeDistance(const std::vector<Vec>& centres, const std::vector<double>& radii,
                             const SasBoundary& boundary, double reach,
                             const ParallelFor& parallel_for)
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
  // Cells a quarter of the larger of the reach and the largest radius wide, visited out to the
  // radius each query needs.
  this->largest_ = largest;
  this->outside_exact_ = std::max(largest, reach);
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
  // Three tables of 4 bytes per row of cells along x: atoms spread so far apart (over about
  // 5000 Å along both y and z) that they would take over 120 MB are refused rather than exhaust
  // the memory.
  const double rows = double(this->dims_[1]) * double(this->dims_[2]);
  if (rows > largest_row_count || double(this->dims_[0]) > 1e9)
  {
    std::ostringstream message;
    message.precision(3);
    message << "the spheres span " << high[0] - low[0] << " x " << high[1] - low[1] << " x "
            << high[2] - low[2] << " Å: too far apart for one surface (its search grid would "
            << "need " << rows << " rows of " << double(this->dims_[0]) << " cells, more than "
            << largest_row_count << " rows or 1e9 cells); surround groups of atoms that lie "
            << "close together separately";
    throw InvalidInput(message.str());
  }
  // The three tables are independent: built side by side, the arcs' (the largest) first.
  const auto index_points = [this](std::size_t count, const auto& point_of, CellTable& table) {
    std::array<std::int64_t, 3> ijk{};
    std::vector<std::pair<std::int64_t, std::uint32_t>> pairs;
    pairs.reserve(count);
    for (std::size_t k = 0; k < count; ++k)
    {
      pairs.emplace_back(this->cell_of(point_of(k), ijk), static_cast<std::uint32_t>(k));
    }
    this->build_table(pairs, table);
  };
  run_balanced<char>(parallel_for, 3, [&](std::size_t table, char&) {
    if (table == 0)
    {
      this->index_arcs();
    }
    else if (table == 1)
    {
      index_points(
        boundary.vertices.size(),
        [&](std::size_t k) -> const Vec& { return boundary.vertices[k].position; },
        this->vertices_);
    }
    else
    {
      index_points(
        centres.size(), [&](std::size_t i) -> const Vec& { return centres[i]; }, this->spheres_);
    }
  });
}

void ProbeDistance::index_arcs()
{
  const SasBoundary& boundary = this->boundary_;
  std::array<std::int64_t, 3> ijk{};
  std::vector<std::pair<std::int64_t, std::uint32_t>> pairs;
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
  this->arc_ends_.reserve(boundary.arcs.size());
  for (const SasArc& arc : boundary.arcs)
  {
    const double end = arc.start + arc.span;
    this->arc_ends_.push_back(
      { std::cos(arc.start), std::sin(arc.start), std::cos(end), std::sin(end) });
  }
  // Entries point at (arc, piece middle) pairs, in cell order.
  std::vector<std::pair<std::int64_t, std::uint32_t>> entries(pairs.size());
  for (std::size_t e = 0; e < pairs.size(); ++e)
  {
    entries[e] = { pairs[e].first, static_cast<std::uint32_t>(e) };
  }
  this->build_table(entries, this->arc_cells_);
  auto& arc_entries = this->arc_cells_.items;
  this->arc_items_.resize(pairs.size());
  this->arc_piece_middle_.resize(pairs.size());
  for (std::size_t e = 0; e < arc_entries.size(); ++e)
  {
    const std::uint32_t original = arc_entries[e];
    this->arc_items_[e] = pairs[original].second;
    this->arc_piece_middle_[e] = middles[original];
    arc_entries[e] = static_cast<std::uint32_t>(e);
  }
}

std::int64_t ProbeDistance::cell_of(const Vec& x, std::array<std::int64_t, 3>& ijk) const
{
  for (int a = 0; a < 3; ++a)
  {
    // Clamped as a double first: a point far out (or not finite) has no integer cell.
    const double cell = std::floor((x[a] - this->origin_[a]) / this->cell_);
    const double last = double(this->dims_[a] - 1);
    ijk[a] = cell >= 0 ? static_cast<std::int64_t>(std::min(cell, last)) : 0;
  }
  return ijk[0] + this->dims_[0] * (ijk[1] + this->dims_[1] * ijk[2]);
}

void ProbeDistance::build_table(std::vector<std::pair<std::int64_t, std::uint32_t>>& pairs,
                                CellTable& table) const
{
  std::sort(pairs.begin(), pairs.end());
  const std::size_t rows = static_cast<std::size_t>(this->dims_[1] * this->dims_[2]);
  table.row_spans.assign(rows + 1, 0);
  table.spans.clear();
  table.starts.clear();
  table.items.resize(pairs.size());
  const std::int64_t width = this->dims_[0];
  std::size_t next_row = 0; // rows before it have their first span set
  for (std::size_t k = 0; k < pairs.size();)
  {
    // One span's pairs: cells of one row with gaps of at most largest_span_gap between them,
    // and each cell's first item (the next cell's first closes it).
    const std::int64_t row = pairs[k].first / width;
    std::size_t end = k + 1;
    while (end < pairs.size() && pairs[end].first / width == row &&
           pairs[end].first - pairs[end - 1].first <= largest_span_gap + 1)
    {
      ++end;
    }
    for (; next_row <= static_cast<std::size_t>(row); ++next_row)
    {
      table.row_spans[next_row] = static_cast<std::uint32_t>(table.spans.size());
    }
    const auto first = static_cast<std::int32_t>(pairs[k].first % width);
    const auto last = static_cast<std::int32_t>(pairs[end - 1].first % width);
    table.spans.push_back({ first, last, static_cast<std::uint32_t>(table.starts.size()) });
    std::size_t item = k;
    for (std::int32_t x = first; x <= last + 1; ++x)
    {
      while (item < end && pairs[item].first % width < x)
      {
        ++item;
      }
      table.starts.push_back(static_cast<std::uint32_t>(item));
    }
    k = end;
  }
  for (; next_row <= rows; ++next_row)
  {
    table.row_spans[next_row] = static_cast<std::uint32_t>(table.spans.size());
  }
  for (std::size_t k = 0; k < pairs.size(); ++k)
  {
    table.items[k] = pairs[k].second;
  }
}

template<typename Visit>
void ProbeDistance::for_cells(const Vec& x, double radius, const CellTable& table,
                              Visit&& visit) const
{
  std::array<std::int64_t, 3> from{}, to{};
  this->cell_of(x - Vec::Constant(radius), from);
  this->cell_of(x + Vec::Constant(radius), to);
  for (std::int64_t z = from[2]; z <= to[2]; ++z)
    for (std::int64_t y = from[1]; y <= to[1]; ++y)
    {
      // Cells along x are consecutive in a span: one range of items per span met.
      const std::size_t row = static_cast<std::size_t>(y + this->dims_[1] * z);
      for (std::uint32_t s = table.row_spans[row]; s < table.row_spans[row + 1]; ++s)
      {
        const CellSpan& span = table.spans[s];
        const std::int64_t first = std::max<std::int64_t>(from[0], span.first);
        const std::int64_t last = std::min<std::int64_t>(to[0], span.last);
        if (first > last)
        {
          continue;
        }
        const std::uint32_t* starts = table.starts.data() + span.offset;
        const std::uint32_t end = starts[last - span.first + 1];
        for (std::uint32_t k = starts[first - span.first]; k < end; ++k)
        {
          visit(table.items[k]);
        }
      }
    }
}

std::size_t ProbeDistance::table_bytes() const
{
  std::size_t bytes = 0;
  for (const CellTable* table : { &this->arc_cells_, &this->vertices_, &this->spheres_ })
  {
    bytes += sizeof(std::uint32_t) *
        (table->row_spans.size() + table->starts.size() + table->items.size()) +
      sizeof(CellSpan) * table->spans.size();
  }
  return bytes;
}

double ProbeDistance::piece_distance(const Vec& x, PieceKind kind, std::uint32_t index) const
{
  switch (kind)
  {
    case PieceKind::Face:
      return this->radii_[index] - (x - this->centres_[index]).norm();
    case PieceKind::Arc:
      return std::sqrt(this->arc_frame(index, x).squared);
    case PieceKind::Vertex:
      return (x - this->boundary_.vertices[index].position).norm();
    default:
      return this->reach_;
  }
}

void ProbeDistance::vertices_within(const Vec& x, double radius,
                                    const std::function<void(std::uint32_t)>& visit) const
{
  this->for_cells(x, radius, this->vertices_, [&](std::uint32_t k) {
    if ((this->boundary_.vertices[k].position - x).squaredNorm() < radius * radius)
    {
      visit(k);
    }
  });
}

void ProbeDistance::arcs_within(const Vec& x, double radius, std::vector<std::uint32_t>& arcs,
                                const Filter& filter) const
{
  const std::size_t first = arcs.size();
  const double reach = radius + this->arc_extent_;
  const bool filtered = filter.mode != Filter::Mode::All;
  this->for_cells(x, reach, this->arc_cells_, [&](std::uint32_t entry) {
    if ((x - this->arc_piece_middle_[entry]).squaredNorm() < reach * reach &&
        (!filtered || filter.admits(this->boundary_.arcs[this->arc_items_[entry]])))
    {
      arcs.push_back(this->arc_items_[entry]);
    }
  });
  std::sort(arcs.begin() + std::ptrdiff_t(first), arcs.end());
  arcs.erase(std::unique(arcs.begin() + std::ptrdiff_t(first), arcs.end()), arcs.end());
}

double ProbeDistance::union_depth(const Vec& x, std::uint32_t* sphere) const
{
  double depth = -this->reach_;
  this->for_cells(x, this->outside_exact_, this->spheres_, [&](std::uint32_t i) {
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

bool ProbeDistance::exposed_projection(std::uint32_t i, const Vec& x, Vec& y) const
{
  const Vec offset = x - this->centres_[i];
  const double length = offset.norm();
  if (length == 0 || this->boundary_.area[i] <= 0)
  {
    return false;
  }
  y = this->centres_[i] + this->radii_[i] / length * offset;
  return this->uncovered(i, y);
}

bool ProbeDistance::uncovered(std::uint32_t i, const Vec& y) const
{
  for (const std::uint32_t j : this->boundary_.neighbours[i])
  {
    const double rj = this->radii_[j];
    if ((y - this->centres_[j]).squaredNorm() < rj * rj * (1.0 - 1e-12))
    {
      return false;
    }
  }
  return true;
}

/// The spheres holding a query point (as deep as they hold it), and the deepest sphere of those
/// looked at (ties: the lowest index).
struct ProbeDistance::SphereScan
{
  struct Holder
  {
    double depth; ///< R - |x - c| > 0
    std::uint32_t sphere;
  };
  Holder holders[max_holders];
  std::size_t holder_count = 0;
  double deepest = -std::numeric_limits<double>::max();
  std::uint32_t deepest_sphere = 0;

  void consider(std::uint32_t sphere, double depth)
  {
    if (depth > this->deepest || (depth == this->deepest && sphere < this->deepest_sphere))
    {
      this->deepest = depth;
      this->deepest_sphere = sphere;
    }
  }
  void hold(std::uint32_t sphere, double depth)
  {
    this->consider(sphere, depth);
    if (depth > 0 && this->holder_count < max_holders)
    {
      this->holders[this->holder_count++] = { depth, sphere };
    }
  }
};

bool ProbeDistance::outside_union(const SphereScan& scan, const Vec& x, bool filtered,
                                  ClosestPiece& best) const
{
  if (scan.deepest == -std::numeric_limits<double>::max())
  {
    best.distance = -this->reach_; // far from every sphere
    return true;
  }
  // Probe positions themselves (on the boundary, to rounding) count as inside when a query
  // leaves pieces out: it asks how far the other pieces are.
  if (scan.deepest <= 0 && !(filtered && scan.deepest > -1e-9))
  {
    // Outside the union: the nearest point of the nearest sphere.
    const Vec& c = this->centres_[scan.deepest_sphere];
    best.distance = scan.deepest;
    best.point = c + this->radii_[scan.deepest_sphere] * (x - c).normalized();
    best.kind = PieceKind::Face;
    best.index = scan.deepest_sphere;
    return true;
  }
  return false;
}

bool ProbeDistance::nearest_face(const SphereScan& scan, const Vec& x, ClosestPiece& best) const
{
  // Every sphere holding x lies inside the union, so the boundary is at least as far as that
  // sphere's surface: the distance is at least the deepest holder's depth, a shallower holder's
  // projection lies inside the deepest one, and the deepest's projection, when exposed, is the
  // nearest boundary point. Holders as deep (to rounding) are tried too: the lowest index wins.
  const double deepest = scan.deepest;
  if (deepest >= best.distance)
  {
    return false;
  }
  std::uint32_t chosen = UINT32_MAX;
  Vec chosen_point;
  for (std::size_t k = 0; k < scan.holder_count; ++k)
  {
    const SphereScan::Holder& holder = scan.holders[k];
    Vec y;
    if (holder.depth >= deepest - 1e-12 && holder.sphere < chosen &&
        this->exposed_projection(holder.sphere, x, y))
    {
      chosen = holder.sphere;
      chosen_point = y;
    }
  }
  if (chosen == UINT32_MAX)
  {
    return false;
  }
  best.distance = deepest;
  best.point = chosen_point;
  best.kind = PieceKind::Face;
  best.index = chosen;
  return true;
}

ProbeDistance::ArcFrame ProbeDistance::arc_frame(std::uint32_t k, const Vec& x) const
{
  const SasArc& arc = this->boundary_.arcs[k];
  const Vec v = x - arc.centre;
  ArcFrame frame;
  frame.along = v.dot(arc.axis);
  frame.a1 = v.dot(arc.e1);
  frame.a2 = v.dot(arc.e2);
  frame.radial = std::sqrt(frame.a1 * frame.a1 + frame.a2 * frame.a2);
  frame.squared =
    frame.along * frame.along + (frame.radial - arc.radius) * (frame.radial - arc.radius);
  return frame;
}

double ProbeDistance::arc_distance(std::uint32_t k, const Vec& x, Vec& nearest) const
{
  const ArcFrame frame = this->arc_frame(k, x);
  const SasArc& arc = this->boundary_.arcs[k];
  if (frame.radial <= 1e-12)
  {
    nearest = arc.point(arc.start); // on the axis: every point of the circle is as near
    return std::sqrt(frame.squared);
  }
  if (this->within_span(k, frame.a1, frame.a2))
  {
    nearest = arc.centre + arc.radius / frame.radial * (frame.a1 * arc.e1 + frame.a2 * arc.e2);
    return std::sqrt(frame.squared);
  }
  const ArcEnds& ends = this->arc_ends_[k];
  const Vec start = arc.centre + arc.radius * (ends.start_cos * arc.e1 + ends.start_sin * arc.e2);
  const Vec end = arc.centre + arc.radius * (ends.end_cos * arc.e1 + ends.end_sin * arc.e2);
  const double to_start = (x - start).squaredNorm(), to_end = (x - end).squaredNorm();
  nearest = to_start <= to_end ? start : end;
  return std::sqrt(std::min(to_start, to_end));
}

double ProbeDistance::arc_distance(std::uint32_t k, const Vec& x) const
{
  return this->arc_distance_in(k, x, this->arc_frame(k, x));
}

bool ProbeDistance::arc_nearer(std::uint32_t k, const Vec& x, double bound, double& distance) const
{
  // The circle is no farther than the arc: its distance settles most arcs.
  const ArcFrame frame = this->arc_frame(k, x);
  if (!(frame.squared < bound * bound))
  {
    return false;
  }
  distance = this->arc_distance_in(k, x, frame);
  return distance < bound;
}

double ProbeDistance::arc_distance_in(std::uint32_t k, const Vec& x, const ArcFrame& frame) const
{
  // As the overload with the nearest point, without making it (the searches' hot path).
  if (frame.radial <= 1e-12 || this->within_span(k, frame.a1, frame.a2))
  {
    return std::sqrt(frame.squared);
  }
  const SasArc& arc = this->boundary_.arcs[k];
  const ArcEnds& ends = this->arc_ends_[k];
  const Vec start = arc.centre + arc.radius * (ends.start_cos * arc.e1 + ends.start_sin * arc.e2);
  const Vec end = arc.centre + arc.radius * (ends.end_cos * arc.e1 + ends.end_sin * arc.e2);
  return std::sqrt(std::min((x - start).squaredNorm(), (x - end).squaredNorm()));
}

void ProbeDistance::try_arc(std::uint32_t k, const Vec& x, ClosestPiece& best) const
{
  const ArcFrame frame = this->arc_frame(k, x);
  if (frame.squared >= best.distance * best.distance)
  {
    return;
  }
  const SasArc& arc = this->boundary_.arcs[k];
  Vec point;
  if (frame.radial > 1e-12)
  {
    if (!this->within_span(k, frame.a1, frame.a2))
    {
      return; // nearest circle point not on the exposed arc: an end vertex is nearer
    }
    point = arc.centre + arc.radius / frame.radial * (frame.a1 * arc.e1 + frame.a2 * arc.e2);
  }
  else
  {
    point = arc.point(arc.start); // on the axis: every circle point is as near
  }
  best.distance = std::sqrt(frame.squared);
  best.point = point;
  best.kind = PieceKind::Arc;
  best.index = k;
}

void ProbeDistance::try_vertex(std::uint32_t k, const Vec& x, const Filter& filter,
                               ClosestPiece& best) const
{
  const SasVertex& vertex = this->boundary_.vertices[k];
  const double distance = (x - vertex.position).norm();
  if (distance < best.distance && filter.admits(vertex))
  {
    best.distance = distance;
    best.point = vertex.position;
    best.kind = PieceKind::Vertex;
    best.index = k;
  }
}

bool ProbeDistance::sphere_reaches(std::uint32_t i, const Vec& centre, double radius) const
{
  const double reach = this->radii_[i] + radius;
  return (centre - this->centres_[i]).squaredNorm() < reach * reach;
}

void ProbeDistance::spheres_near(const Vec& centre, double radius,
                                 std::vector<std::uint32_t>& spheres) const
{
  this->for_cells(centre, this->largest_ + radius, this->spheres_, [&](std::uint32_t i) {
    if (this->sphere_reaches(i, centre, radius))
    {
      spheres.push_back(i);
    }
  });
}

void ProbeDistance::spheres_near(const std::vector<std::uint32_t>& candidates, const Vec& centre,
                                 double radius, std::vector<std::uint32_t>& spheres) const
{
  for (const std::uint32_t i : candidates)
  {
    if (this->sphere_reaches(i, centre, radius))
    {
      spheres.push_back(i);
    }
  }
}

void ProbeDistance::gather(const Vec& centre, double radius, double limit, LocalPieces& local,
                           bool for_filters) const
{
  local.centre = centre;
  local.radius = radius;
  local.limit = limit;
  local.spheres.clear();
  local.arcs.clear();
  local.vertices.clear();
  // Filtered queries need every piece within the limit, whatever the nearest: no bound from
  // the centre's distance (left 0).
  local.centre_distance =
    for_filters ? 0.0 : this->closest(centre, {}, std::min(limit + radius, this->reach_)).distance;
  this->spheres_near(centre, radius, local.spheres);
  // Filtered queries skip the nearest pieces: every piece within the limit counts for them.
  const double bound = for_filters ? limit + radius : local_bound(local);
  if (bound <= 0)
  {
    return; // the ball lies outside the union: spheres alone matter
  }
  std::uint32_t last_arc = UINT32_MAX;
  this->for_cells(centre, bound + this->arc_extent_, this->arc_cells_, [&](std::uint32_t entry) {
    const double reach = bound + this->arc_extent_;
    const std::uint32_t k = this->arc_items_[entry];
    if (k != last_arc && (centre - this->arc_piece_middle_[entry]).squaredNorm() < reach * reach)
    {
      last_arc = k;
      local.arcs.push_back({ 0.0, k });
    }
  });
  std::sort(local.arcs.begin(), local.arcs.end(),
            [](const auto& a, const auto& b) { return a.second < b.second; });
  local.arcs.erase(std::unique(local.arcs.begin(), local.arcs.end(),
                               [](const auto& a, const auto& b) { return a.second == b.second; }),
                   local.arcs.end());
  std::size_t kept = 0;
  for (const auto& arc : local.arcs)
  {
    double d = 0;
    if (this->arc_nearer(arc.second, centre, bound, d))
    {
      local.arcs[kept++] = { d, arc.second };
    }
  }
  local.arcs.resize(kept);
  std::sort(local.arcs.begin(), local.arcs.end());
  this->vertices_within(centre, bound, [&](std::uint32_t k) {
    local.vertices.push_back({ (this->boundary_.vertices[k].position - centre).norm(), k });
  });
  std::sort(local.vertices.begin(), local.vertices.end());
}

void ProbeDistance::refine(const LocalPieces& parent, const Vec& centre, double radius,
                           LocalPieces& local) const
{
  local.centre = centre;
  local.radius = radius;
  local.limit = parent.limit;
  local.centre_distance = this->closest(parent, centre).distance;
  local.spheres.clear();
  this->spheres_near(parent.spheres, centre, radius, local.spheres);
  local.arcs.clear();
  local.vertices.clear();
  const double bound = local_bound(local);
  if (bound <= 0)
  {
    return;
  }
  // Pieces within the bound of this centre lie within bound + offset of the parent's, and the
  // parent's lists are sorted by that distance.
  const double offset = (centre - parent.centre).norm();
  for (const auto& arc : parent.arcs)
  {
    if (arc.first >= bound + offset)
    {
      break;
    }
    double d = 0;
    if (this->arc_nearer(arc.second, centre, bound, d))
    {
      local.arcs.push_back({ d, arc.second });
    }
  }
  sort_nearly_sorted(local.arcs);
  for (const auto& vertex : parent.vertices)
  {
    if (vertex.first >= bound + offset)
    {
      break;
    }
    const double d = (this->boundary_.vertices[vertex.second].position - centre).norm();
    if (d < bound)
    {
      local.vertices.push_back({ d, vertex.second });
    }
  }
  sort_nearly_sorted(local.vertices);
}

ClosestPiece ProbeDistance::closest(const LocalPieces& local, const Vec& x, const Filter& filter,
                                    double limit) const
{
  limit = limit > 0 ? std::min(limit, local.limit) : local.limit;
  if ((x - local.centre).squaredNorm() > local.radius * local.radius)
  {
    return this->closest(x, filter, limit); // outside the ball: the index decides
  }
  const bool filtered = filter.mode != Filter::Mode::All;
  ClosestPiece best;
  // Depths by square roots only for the spheres holding x, unless none does.
  SphereScan scan;
  for (const std::uint32_t i : local.spheres)
  {
    const double squared = (x - this->centres_[i]).squaredNorm();
    const double r = this->radii_[i];
    if (squared < r * r)
    {
      scan.hold(i, r - std::sqrt(squared));
    }
  }
  if (scan.holder_count == 0)
  {
    for (const std::uint32_t i : local.spheres)
    {
      scan.consider(i, this->radii_[i] - (x - this->centres_[i]).norm());
    }
  }
  if (this->outside_union(scan, x, filtered, best))
  {
    return best;
  }
  best.distance = limit;
  if (!filtered && this->nearest_face(scan, x, best))
  {
    return best;
  }
  // Sorted by distance from the centre, which bounds each piece's from below: stop where the
  // bound passes the best. Vertices first: a point's distance is one root, and the nearest
  // vertex bounds the arcs' distances (every arc ends at vertices or closes on itself) so
  // that fewer arcs need their frame.
  const double offset = (x - local.centre).norm();
  for (const auto& vertex : local.vertices)
  {
    if (vertex.first - offset >= best.distance)
    {
      break;
    }
    this->try_vertex(vertex.second, x, filter, best);
  }
  for (const auto& arc : local.arcs)
  {
    if (arc.first - offset >= best.distance)
    {
      break;
    }
    if (filter.admits(this->boundary_.arcs[arc.second]))
    {
      this->try_arc(arc.second, x, best);
    }
  }
  return best;
}

ClosestPiece ProbeDistance::closest(const Vec& x, const Filter& filter, double limit) const
{
  const bool filtered = filter.mode != Filter::Mode::All;
  ClosestPiece best;
  // Spheres holding x: only the deepest can carry the nearest face point (see nearest_face).
  SphereScan scan;
  this->for_cells(x, this->largest_, this->spheres_, [&](std::uint32_t i) {
    const double squared = (x - this->centres_[i]).squaredNorm();
    const double r = this->radii_[i];
    if (squared < r * r)
    {
      scan.hold(i, r - std::sqrt(squared)); // a root only for those holding x
    }
  });
  if (scan.deepest == -std::numeric_limits<double>::max())
  {
    // Outside every sphere: the nearest may lie farther.
    this->for_cells(x, this->outside_exact_, this->spheres_, [&](std::uint32_t i) {
      scan.consider(i, this->radii_[i] - (x - this->centres_[i]).norm());
    });
    // Spheres beyond the search are at least this far below zero: when none nearer was found,
    // the distance is reported as that bound (nearer zero than the truth may be), so that a
    // ball around x is never judged farther from the surface than it is.
    const double unseen = this->largest_ - this->outside_exact_;
    if (scan.deepest < unseen)
    {
      best.distance = unseen;
      return best;
    }
  }
  if (this->outside_union(scan, x, filtered, best))
  {
    return best;
  }
  best.distance = limit > 0 ? std::min(limit, this->reach_) : this->reach_;
  // No face cuts a torus or concave patch.
  if (!filtered && this->nearest_face(scan, x, best))
  {
    return best;
  }
  std::uint32_t last_arc = UINT32_MAX;
  this->for_cells(x, best.distance + this->arc_extent_, this->arc_cells_, [&](std::uint32_t entry) {
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
    if (filter.admits(this->boundary_.arcs[k]))
    {
      this->try_arc(k, x, best);
    }
  });
  this->for_cells(x, best.distance, this->vertices_,
                  [&](std::uint32_t k) { this->try_vertex(k, x, filter, best); });
  return best;
}

} // namespace mesolens
