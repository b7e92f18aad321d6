// SPDX-License-Identifier: GPL-3.0-or-later
#include <Eigen/Dense>

#include "surface/detail/surface_contour_fields.h"

#include "surface/detail/block_bins.h"
#include "surface/detail/excluded_surface.h"
#include "common/detail/grid_cells.h"
#include "surface/detail/segment_roots.h"

#include "mesolens/surface/molecular_surface.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>

namespace mesolens {

namespace {
using Vec = Eigen::Vector3d;
constexpr int side = ContourGrid::block_points;
constexpr std::size_t block_size = std::size_t(side) * side * side;
constexpr double two_pi = 6.28318530717958647692;
/// How far beyond the probe radius (Å) the general search for a vertex looks inside the union.
constexpr double general_search_depth = 0.3;
/// Boxes grow by this much (Å) before they are binned and their points found, so that a point
/// near a box's face counts in every block that holds it, whatever the rounding.
constexpr double box_slack = 1e-6;

/// Calls `visit(at, x)` for every point of `block` in the box [from, to] (Å) and in the ball
/// about `centre` of `radius` (a few more, within rounding): its index in the block and its
/// position (the same, bit for bit, from every block holding it).
template<typename Visit>
void for_points(const ContourGrid& grid, std::size_t block, const Vec& from, const Vec& to,
                const Vec& centre, double radius, Visit&& visit)
{
  std::array<int, 3> first{}, last{};
  if (!grid.points_within(block, from, to, first, last))
  {
    return;
  }
  const auto origin = grid.block_first(block);
  const double h = grid.spacing, per_spacing = 1.0 / h;
  const Vec base = grid.point(origin[0], origin[1], origin[2]);
  const Vec offset = centre - base; // the ball's centre in the block's frame (Å)
  for (int z = first[2]; z <= last[2]; ++z)
  {
    const double dz = h * z - offset[2];
    for (int y = first[1]; y <= last[1]; ++y)
    {
      const double dy = h * y - offset[1];
      const double rest = radius * radius - dz * dz - dy * dy;
      if (rest < 0)
      {
        continue;
      }
      // The row's points within the ball, a point to spare against rounding.
      const double half = std::sqrt(rest);
      const int x0 = std::max(first[0], floor_to_int((offset[0] - half) * per_spacing));
      const int x1 = std::min(last[0], ceil_to_int((offset[0] + half) * per_spacing));
      // Coordinates as grid.point() makes them, per row.
      Vec point(0.0, grid.low[1] + h * double(origin[1] + y),
                grid.low[2] + h * double(origin[2] + z));
      const std::size_t row = std::size_t(side * (y + side * z));
      for (int x = x0; x <= x1; ++x)
      {
        point[0] = grid.low[0] + h * double(origin[0] + x);
        visit(row + std::size_t(x), point);
      }
    }
  }
}

/// A ball holding an arc's points: about the middle of its chord when it spans at most half a
/// turn, else about its circle's centre.
void arc_ball(const SasArc& arc, Vec& centre, double& radius)
{
  if (arc.span <= 0.5 * two_pi)
  {
    centre = 0.5 * (arc.point(arc.start) + arc.point(arc.start + arc.span));
    radius = arc.radius * std::sin(0.5 * arc.span);
  }
  else
  {
    centre = arc.centre;
    radius = arc.radius;
  }
}

/// The box of arc `k`'s points (its ends included): per axis the ends, and the circle's
/// extremes where they fall within the span (in the circle's frame the extreme along an axis
/// lies in the direction of that axis's components on e1 and e2).
void arc_box(const ProbeDistance& distance, const SasArc& arc, std::uint32_t k, Vec& from, Vec& to)
{
  from = to = arc.point(arc.start);
  const Vec last = arc.point(arc.start + arc.span);
  from = from.cwiseMin(last);
  to = to.cwiseMax(last);
  for (int a = 0; a < 3; ++a)
  {
    const double amplitude = std::sqrt(arc.e1[a] * arc.e1[a] + arc.e2[a] * arc.e2[a]);
    if (amplitude == 0)
    {
      continue; // the circle's plane is across this axis
    }
    if (distance.within_span(k, arc.e1[a], arc.e2[a]))
    {
      to[a] = std::max(to[a], arc.centre[a] + arc.radius * amplitude);
    }
    if (distance.within_span(k, -arc.e1[a], -arc.e2[a]))
    {
      from[a] = std::min(from[a], arc.centre[a] - arc.radius * amplitude);
    }
  }
}

/// The solvent-excluded surface's field over a grid: the boundary's pieces binned to the blocks
/// they may reach.
class ExcludedSurfaceContour final : public ContourField
{
public:
  ExcludedSurfaceContour(const ExcludedSurface& surface, const std::vector<double>& radii)
    : surface_(surface)
    , radii_(radii)
  {
  }

  void prepare(const ContourGrid& grid, const ParallelFor& parallel_for) override
  {
    const double limit = this->surface_.limit;
    const SasBoundary& boundary = this->surface_.boundary;
    // An edge the surface crosses has its outside end within a spacing (the lattice's longest
    // edge) of the surface, which lies a probe radius inside the union: the nearest sphere of
    // such ends is found.
    this->outside_reach_ = std::max(0.0, grid.spacing - this->surface_.probe) + 0.1 * grid.spacing;
    const Vec slack = Vec::Constant(box_slack);
    this->spheres_ = BlockBins(
      grid, this->radii_.size(),
      [&](std::size_t i, Vec& from, Vec& to) {
        const Vec reach = Vec::Constant(this->radii_[i] + this->outside_reach(i)) + slack;
        from = this->surface_.centres[i] - reach;
        to = this->surface_.centres[i] + reach;
        return true;
      },
      parallel_for);
    this->arc_boxes_.resize(boundary.arcs.size());
    this->arc_balls_.resize(boundary.arcs.size());
    this->arcs_ = BlockBins(
      grid, boundary.arcs.size(),
      [&](std::size_t k, Vec& from, Vec& to) {
        arc_box(this->surface_.distance, boundary.arcs[k], static_cast<std::uint32_t>(k), from, to);
        from -= Vec::Constant(limit) + slack;
        to += Vec::Constant(limit) + slack;
        this->arc_boxes_[k] = { from, to };
        Vec centre;
        double radius = 0;
        arc_ball(boundary.arcs[k], centre, radius);
        this->arc_balls_[k] = { centre[0], centre[1], centre[2], radius + limit + box_slack };
        return true;
      },
      parallel_for);
    this->vertices_ = BlockBins(
      grid, boundary.vertices.size(),
      [&](std::size_t k, Vec& from, Vec& to) {
        from = boundary.vertices[k].position - Vec::Constant(limit) - slack;
        to = boundary.vertices[k].position + Vec::Constant(limit) + slack;
        return true;
      },
      parallel_for);
  }

  void blocks_to_sample(std::vector<std::size_t>& blocks) const override
  {
    // Blocks with no piece near sample nothing (see ExcludedSurfaceBlock::sample_block).
    std::vector<std::size_t> pieces;
    std::set_union(this->arcs_.occupied_blocks().begin(), this->arcs_.occupied_blocks().end(),
                   this->vertices_.occupied_blocks().begin(),
                   this->vertices_.occupied_blocks().end(), std::back_inserter(pieces));
    blocks.clear();
    std::set_union(pieces.begin(), pieces.end(), this->spheres_.occupied_blocks().begin(),
                   this->spheres_.occupied_blocks().end(), std::back_inserter(blocks));
  }

  std::unique_ptr<LocalContourField> local() const override;

  /// How far outside sphere `i` its points are visited: the exposed ones carry the union's
  /// boundary, which the nearest sphere of a point outside the union is on.
  double outside_reach(std::size_t i) const
  {
    return this->surface_.boundary.area[i] > 0 ? this->outside_reach_ : 0.0;
  }

  ExcludedSurface surface_;
  const std::vector<double>& radii_; ///< the inflated spheres'
  double outside_reach_ = 0;
  BlockBins spheres_, arcs_, vertices_;
  /// Per arc, the box and the ball (centre, radius) holding the points within the reach.
  std::vector<std::array<Vec, 2>> arc_boxes_;
  std::vector<std::array<double, 4>> arc_balls_;
};

/// One block of the solvent-excluded surface's field at a time.
class ExcludedSurfaceBlock final : public LocalContourField
{
public:
  explicit ExcludedSurfaceBlock(const ExcludedSurfaceContour& field)
    : field_(field)
    , surface_(field.surface_)
    , nearest_(block_size)
    , nearest_hint_(block_size)
    , inside_(block_size)
    , outside_(block_size)
    , outside_hint_(block_size)
  {
  }

  bool sample_block(const ContourGrid& grid, std::size_t block, double* values,
                    std::uint32_t* hints) override
  {
    const SasBoundary& boundary = this->surface_.boundary;
    const ExcludedSurfaceContour& field = this->field_;
    // Without a piece within the limit, every point lies outside the union, or inside it
    // deeper than the limit: no zero.
    bool near_pieces = !field.arcs_.items(block).empty() || !field.vertices_.items(block).empty();
    for (const std::uint32_t i : field.spheres_.items(block))
    {
      if (near_pieces)
      {
        break;
      }
      near_pieces = boundary.area[i] > 0;
    }
    if (!near_pieces)
    {
      return false;
    }
    std::fill(this->nearest_.begin(), this->nearest_.end(), this->surface_.limit);
    std::fill(this->nearest_hint_.begin(), this->nearest_hint_.end(), no_piece);
    std::fill(this->inside_.begin(), this->inside_.end(), 0);
    std::fill(this->outside_.begin(), this->outside_.end(), -std::numeric_limits<double>::max());
    std::fill(this->outside_hint_.begin(), this->outside_hint_.end(), no_piece);
    // Vertices and arcs first: where they lie nearer than a sphere, its exposure is not tested.
    this->visit_vertices(grid, block);
    this->visit_arcs(grid, block);
    this->visit_spheres(grid, block);
    const double p = this->surface_.probe;
    for (std::size_t at = 0; at < block_size; ++at)
    {
      if (this->inside_[at])
      {
        values[at] = this->nearest_[at] - p;
        hints[at] = this->nearest_hint_[at];
      }
      else if (this->outside_hint_[at] != no_piece)
      {
        values[at] = this->outside_[at] - p;
        hints[at] = this->outside_hint_[at];
      }
      else
      {
        values[at] = -field.outside_reach_ - p; // farther from every sphere
        hints[at] = no_piece;
      }
    }
    return true;
  }

  ContourVertex vertex(const Sample& outside, const Sample& inside,
                       const std::array<Sample, 4>& corners) override
  {
    // The root along the lattice edge itself: vertices kept on their edges cannot fold
    // triangles over one another, even at the surface's creases. First along the pieces nearest
    // the edge's ends (mostly one piece for both), then those nearest the tetrahedron's other
    // corners, then the others of the ends' atoms (cheap roots on one piece, each kept when
    // certified on its patch), else on the field.
    const std::pair<PieceKind, std::uint32_t> at_inside(hint_kind(inside.hint),
                                                        hint_index(inside.hint));
    const std::pair<PieceKind, std::uint32_t> at_outside(hint_kind(outside.hint),
                                                         hint_index(outside.hint));
    Vec position;
    ClosestPiece piece;
    if (this->along(outside, inside, at_inside, position, piece) ||
        (at_outside != at_inside && this->along(outside, inside, at_outside, position, piece)))
    {
      return this->surface_.vertex(position, piece);
    }
    auto& others = this->others_;
    others.clear();
    for (const Sample& corner : corners)
    {
      const std::pair<PieceKind, std::uint32_t> at_corner(hint_kind(corner.hint),
                                                          hint_index(corner.hint));
      if (at_corner != at_inside && at_corner != at_outside &&
          std::find(others.begin(), others.end(), at_corner) == others.end())
      {
        others.push_back(at_corner);
      }
    }
    for (const auto& other : others)
    {
      if (this->along(outside, inside, other, position, piece))
      {
        return this->surface_.vertex(position, piece);
      }
    }
    if (this->surface_.pieces.visit_pieces_near(
          at_inside, at_outside, [&](PieceKind kind, std::uint32_t index) {
            const std::pair<PieceKind, std::uint32_t> near(kind, index);
            return std::find(others.begin(), others.end(), near) == others.end() &&
              this->along(outside, inside, near, position, piece);
          }))
    {
      return this->surface_.vertex(position, piece);
    }
    // The general search, among the pieces near the tetrahedron (gathered once for its edges).
    // It needs the distance's sign against the probe radius and the piece at the root, so
    // pieces a little deeper than the probe radius (general_search_depth) are enough: fewer to
    // gather.
    const Vec middle = 0.25 *
      (corners[0].position + corners[1].position + corners[2].position + corners[3].position);
    if (!this->gathered_ || this->local_.centre != middle)
    {
      double radius = 0;
      for (const Sample& corner : corners)
      {
        radius = std::max(radius, (corner.position - middle).norm());
      }
      radius *= 1.0 + 1e-9;
      this->surface_.distance.gather(middle, radius, this->surface_.probe + general_search_depth,
                                     this->local_);
      this->gathered_ = true;
    }
    // Newton's method on the distance: its gradient points away from the nearest boundary
    // point (for a sphere's face, outside the union too), where there is one within the depth.
    const Vec along_edge = inside.position - outside.position;
    const auto value = [&](const Vec& x, double& slope) {
      const ClosestPiece nearest = this->surface_.distance.closest(this->local_, x);
      slope = nearest.kind == PieceKind::None || nearest.distance == 0
        ? 0.0
        : (x - nearest.point).dot(along_edge) / nearest.distance;
      return nearest.distance - this->surface_.probe;
    };
    double slope = 0;
    const double at_outside_end = value(outside.position, slope);
    const double at_inside_end = value(inside.position, slope);
    position =
      segment_root_newton(outside.position, at_outside_end, inside.position, at_inside_end, value);
    piece = this->surface_.distance.closest(this->local_, position);
    return this->surface_.vertex(position, piece);
  }

private:
  static constexpr std::uint32_t no_piece = encode_piece(PieceKind::None, 0);

  /// Whether a piece `distance` from the point `at` (its label `label`) is nearer than what the
  /// point has, within the limit: the least distance, ties to the lower label, so that every
  /// block holding a point finds the same.
  bool improves(std::size_t at, double distance, std::uint32_t label) const
  {
    return distance < this->surface_.limit &&
      (distance < this->nearest_[at] ||
       (distance == this->nearest_[at] && label < this->nearest_hint_[at]));
  }
  void take(std::size_t at, double distance, std::uint32_t label)
  {
    this->nearest_[at] = distance;
    this->nearest_hint_[at] = label;
  }
  void offer(std::size_t at, double distance, std::uint32_t label)
  {
    if (this->improves(at, distance, label))
    {
      this->take(at, distance, label);
    }
  }

  /// The block's points within the limit of each vertex near it.
  void visit_vertices(const ContourGrid& grid, std::size_t block)
  {
    const ExcludedSurfaceContour& field = this->field_;
    const double limit = this->surface_.limit;
    const Vec reach = Vec::Constant(limit + box_slack);
    for (const std::uint32_t k : field.vertices_.items(block))
    {
      const Vec& v = this->surface_.boundary.vertices[k].position;
      const std::uint32_t label = encode_piece(PieceKind::Vertex, k);
      for_points(grid, block, v - reach, v + reach, v, reach[0], [&](std::size_t at, const Vec& x) {
        const double squared = (x - v).squaredNorm();
        if (squared < limit * limit)
        {
          this->offer(at, std::sqrt(squared), label);
        }
      });
    }
  }

  /// The block's points within the limit of each exposed arc near it: those whose nearest point
  /// of the circle lies within the span (else an end vertex is nearer); on the axis every point
  /// of the circle is as near. The span is looked at last: most points have a nearer piece.
  void visit_arcs(const ContourGrid& grid, std::size_t block)
  {
    const ExcludedSurfaceContour& field = this->field_;
    const double limit = this->surface_.limit;
    for (const std::uint32_t k : field.arcs_.items(block))
    {
      const SasArc& arc = this->surface_.boundary.arcs[k];
      const std::uint32_t label = encode_piece(PieceKind::Arc, k);
      const auto& box = field.arc_boxes_[k];
      const auto& ball = field.arc_balls_[k];
      const Vec ball_centre(ball[0], ball[1], ball[2]);
      for_points(
        grid, block, box[0], box[1], ball_centre, ball[3], [&](std::size_t at, const Vec& x) {
          const Vec v = x - arc.centre;
          const double along = v.dot(arc.axis);
          if (std::abs(along) > this->nearest_[at])
          {
            return;
          }
          const double a1 = v.dot(arc.e1), a2 = v.dot(arc.e2);
          const double radial = std::sqrt(a1 * a1 + a2 * a2);
          const double squared = along * along + (radial - arc.radius) * (radial - arc.radius);
          if (!(squared < limit * limit))
          {
            return;
          }
          const double distance = std::sqrt(squared);
          if (this->improves(at, distance, label) &&
              (radial <= 1e-12 || this->surface_.distance.within_span(k, a1, a2)))
          {
            this->take(at, distance, label);
          }
        });
    }
  }

  /// Each sphere near the block marks the points inside it; an exposed one offers its face where
  /// the point's radial projection onto it is exposed (shallower spheres' projections lie inside
  /// the deepest one), and outside it gives the nearest sphere of points outside the union (ties
  /// to the lower index).
  void visit_spheres(const ContourGrid& grid, std::size_t block)
  {
    const ExcludedSurfaceContour& field = this->field_;
    for (const std::uint32_t i : field.spheres_.items(block))
    {
      const Vec& c = this->surface_.centres[i];
      const double r = field.radii_[i], outer = r + field.outside_reach(i);
      const bool exposed = this->surface_.boundary.area[i] > 0;
      const std::uint32_t label = encode_piece(PieceKind::Face, i);
      const Vec box = Vec::Constant(outer + box_slack);
      for_points(grid, block, c - box, c + box, c, box[0], [&](std::size_t at, const Vec& x) {
        const Vec offset = x - c;
        const double squared = offset.squaredNorm();
        if (squared < r * r)
        {
          this->inside_[at] = 1;
          const double gap = std::sqrt(squared);
          const double depth = r - gap;
          if (exposed && gap > 0 && this->improves(at, depth, label) &&
              this->surface_.distance.uncovered(i, c + (r / gap) * offset))
          {
            this->take(at, depth, label);
          }
        }
        else if (exposed && squared < outer * outer)
        {
          const double depth = r - std::sqrt(squared);
          if (depth > this->outside_[at] ||
              (depth == this->outside_[at] && label < this->outside_hint_[at]))
          {
            this->outside_[at] = depth;
            this->outside_hint_[at] = label;
          }
        }
      });
    }
  }

  /// Where the edge passes from the solvent side of the sphere, circle or point carrying `piece`
  /// to its other side (the last time, for a circle), certified on the piece's patch. The
  /// carrier's solvent side is inside the probe's sphere at a vertex, within the probe radius
  /// of an arc's circle, outside a face's atom; an end need not lie on that side, as the piece
  /// need not be the nearest there.
  bool along(const Sample& outside, const Sample& inside,
             const std::pair<PieceKind, std::uint32_t>& piece, Vec& position,
             ClosestPiece& nearest) const
  {
    // Plain variables, not a structured binding: lambdas below capture them (C++17).
    const PieceKind kind = piece.first;
    const std::uint32_t index = piece.second;
    if (kind == PieceKind::None)
    {
      return false;
    }
    const double p = this->surface_.probe;
    const Vec& a = outside.position;
    const Vec& b = inside.position;
    if (kind == PieceKind::Arc)
    {
      // Newton from the last of a few samples within the probe radius of the circle.
      const ProbeDistance& distance = this->surface_.distance;
      const auto along_piece = [&](const Vec& x) { return distance.arc_distance(index, x) - p; };
      const double at_inside = along_piece(b);
      if (!(at_inside > 0))
      {
        return false;
      }
      constexpr int samples = 4;
      Vec from = a;
      double at_from = along_piece(a);
      for (int s = samples - 1; s > 0 && !(at_from <= 0); --s)
      {
        const Vec x = a + (double(s) / samples) * (b - a);
        const double at_x = along_piece(x);
        if (at_x <= 0)
        {
          from = x;
          at_from = at_x;
        }
      }
      if (!(at_from <= 0))
      {
        return false;
      }
      position = segment_root_newton(from, at_from, b, at_inside, [&](const Vec& x, double& slope) {
        Vec nearest_point;
        const double gap = distance.arc_distance(index, x, nearest_point);
        slope = gap > 0 ? (x - nearest_point).dot(b - from) / gap : 0.0;
        return gap - p;
      });
    }
    else
    {
      // Spheres in closed form: the probe's at a vertex (left), the atom's for a face
      // (entered).
      const bool face = kind == PieceKind::Face;
      const Vec& centre =
        face ? this->surface_.centres[index] : this->surface_.boundary.vertices[index].position;
      const double radius = face ? this->surface_.atom_radii[index] : p;
      double entry = 0, exit = 0;
      if (!line_sphere(a, b, centre, radius, entry, exit))
      {
        return false;
      }
      const double t = face ? entry : exit;
      if (!(t >= 0 && t <= 1))
      {
        return false;
      }
      position = on_segment(a, b, t);
    }
    return this->surface_.pieces.certify(position, kind, index, nearest);
  }

  const ExcludedSurfaceContour& field_;
  const ExcludedSurface& surface_;
  // Per point of the block: the nearest piece within the limit (distance, label), whether it
  // lies inside the union, and the nearest sphere's depth and label where it does not.
  std::vector<double> nearest_;
  std::vector<std::uint32_t> nearest_hint_;
  std::vector<std::uint8_t> inside_;
  std::vector<double> outside_;
  std::vector<std::uint32_t> outside_hint_;
  std::vector<std::pair<PieceKind, std::uint32_t>> others_;
  LocalPieces local_; ///< the pieces near the cell of the last general search
  bool gathered_ = false;
};

std::unique_ptr<LocalContourField> ExcludedSurfaceContour::local() const
{
  return std::make_unique<ExcludedSurfaceBlock>(*this);
}

/// The union of spheres' field over a grid: the spheres binned to the blocks they reach.
class UnionSurfaceContour final : public ContourField
{
public:
  UnionSurfaceContour(const std::vector<Vec>& centres, const std::vector<double>& radii)
    : centres_(centres)
    , radii_(radii)
  {
  }

  void prepare(const ContourGrid& grid, const ParallelFor& parallel_for) override
  {
    this->spacing_ = grid.spacing;
    this->spheres_ = BlockBins(
      grid, this->radii_.size(),
      [&](std::size_t i, Vec& from, Vec& to) {
        const Vec reach = Vec::Constant(this->radii_[i] + box_slack);
        from = this->centres_[i] - reach;
        to = this->centres_[i] + reach;
        return true;
      },
      parallel_for);
  }

  void blocks_to_sample(std::vector<std::size_t>& blocks) const override
  {
    blocks = this->spheres_.occupied_blocks();
  }

  std::unique_ptr<LocalContourField> local() const override;

  const std::vector<Vec>& centres_;
  const std::vector<double>& radii_;
  double spacing_ = 1;
  BlockBins spheres_;
};

class UnionSurfaceBlock final : public LocalContourField
{
public:
  explicit UnionSurfaceBlock(const UnionSurfaceContour& field)
    : field_(field)
  {
  }

  bool sample_block(const ContourGrid& grid, std::size_t block, double* values,
                    std::uint32_t* hints) override
  {
    const UnionSurfaceContour& field = this->field_;
    const BlockBins::Items spheres = field.spheres_.items(block);
    this->first_ = spheres.begin();
    this->last_ = spheres.end();
    if (this->first_ == this->last_)
    {
      return false;
    }
    // Points no sphere's box holds lie outside every sphere: a spacing out stands for them.
    std::fill(values, values + block_size, -field.spacing_);
    std::fill(hints, hints + block_size, 0u);
    for (const std::uint32_t* s = this->first_; s != this->last_; ++s)
    {
      const Vec& c = field.centres_[*s];
      const double r = field.radii_[*s];
      const Vec box = Vec::Constant(r + box_slack);
      for_points(grid, block, c - box, c + box, c, box[0], [&](std::size_t at, const Vec& x) {
        const double depth = r - (x - c).norm();
        if (depth > values[at])
        {
          values[at] = depth;
          hints[at] = *s;
        }
      });
    }
    return true;
  }

  ContourVertex vertex(const Sample& outside, const Sample& inside,
                       const std::array<Sample, 4>& /*corners*/) override
  {
    ContourVertex vertex;
    vertex.position = segment_root(outside.position, outside.value, inside.position, inside.value,
                                   [&](const Vec& x) { return this->depth(x); });
    std::uint32_t sphere = 0;
    this->depth(vertex.position, &sphere);
    vertex.normal = (vertex.position - this->field_.centres_[sphere]).normalized();
    vertex.atom = static_cast<std::int32_t>(sphere);
    vertex.piece = sphere;
    vertex.patch = static_cast<std::uint8_t>(SurfacePatch::Convex);
    return vertex;
  }

private:
  double depth(const Vec& x, std::uint32_t* deepest = nullptr) const
  {
    return union_depth(this->first_, this->last_, this->field_.centres_, this->field_.radii_, x,
                       deepest);
  }

  const UnionSurfaceContour& field_;
  const std::uint32_t* first_ = nullptr; ///< the spheres of the block last sampled
  const std::uint32_t* last_ = nullptr;
};

std::unique_ptr<LocalContourField> UnionSurfaceContour::local() const
{
  return std::make_unique<UnionSurfaceBlock>(*this);
}
} // namespace

std::unique_ptr<ContourField> excluded_surface_field(
  const ProbeDistance& distance, const SesPieceProjection& pieces, const SasBoundary& boundary,
  const std::vector<Vec>& centres, const std::vector<double>& radii,
  const std::vector<double>& atom_radii, double probe, double limit)
{
  return std::make_unique<ExcludedSurfaceContour>(
    ExcludedSurface{ distance, pieces, boundary, centres, atom_radii, probe, limit }, radii);
}

std::unique_ptr<ContourField> union_surface_field(const std::vector<Vec>& centres,
                                                  const std::vector<double>& radii)
{
  return std::make_unique<UnionSurfaceContour>(centres, radii);
}

} // namespace mesolens
