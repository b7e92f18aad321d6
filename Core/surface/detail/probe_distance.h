// SPDX-License-Identifier: GPL-3.0-or-later
// The exact distance from a point to the boundary of a union of spheres (private to
// MesoLensCore). With the atoms inflated by a probe, that boundary is the set of the probe's
// possible centres, and the solvent-excluded surface is where the distance equals the probe
// radius: this field is what the tessellation contours and what decides where singular patches
// are cut.
#pragma once

#include "mesolens/common/parallel_for.h"
#include "surface/detail/sas_boundary.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

namespace mesolens {

/// The piece of a union's boundary nearest a point.
enum class PieceKind : std::uint8_t
{
  Face,   ///< a sphere's exposed part (index: the sphere)
  Arc,    ///< an exposed arc (index into SasBoundary::arcs)
  Vertex, ///< an exposed vertex (index into SasBoundary::vertices)
  None,   ///< nothing within reach
};

/// The spheres that carry piece `index` of `kind`: a face's own, an arc's two, a vertex's three,
/// into `spheres`; returns their count (0 for PieceKind::None).
inline int piece_spheres(const SasBoundary& boundary, PieceKind kind, std::uint32_t index,
                         std::array<std::uint32_t, 3>& spheres)
{
  switch (kind)
  {
    case PieceKind::Face:
      spheres = { index, index, index };
      return 1;
    case PieceKind::Arc:
      spheres = { boundary.arcs[index].first, boundary.arcs[index].second,
                  boundary.arcs[index].second };
      return 2;
    case PieceKind::Vertex:
      spheres = boundary.vertices[index].spheres;
      return 3;
    case PieceKind::None:
      break;
  }
  return 0;
}

struct ClosestPiece
{
  /// Signed distance to the boundary: positive inside the union, capped at the reach.
  double distance = 0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero(); ///< the nearest boundary point
  PieceKind kind = PieceKind::None;
  std::uint32_t index = 0;
};

/// Which pieces a query looks at: all; or those that may cut the torus between spheres
/// `atoms[0]` and `atoms[1]` (arcs and vertices touching neither); or those that may cut the
/// concave patch on spheres `atoms` (arcs touching none of them, and arcs between two of
/// them of radius below `probe`, where the probe passes between that pair).
struct PieceFilter
{
  enum class Mode : std::uint8_t
  {
    All,
    TorusCutters,
    ConcaveCutters,
  };
  Mode mode = Mode::All;
  std::array<std::uint32_t, 3> atoms{};
  double probe = 0;

  /// Whether a query with this filter looks at the arc, or at the vertex.
  bool admits(const SasArc& arc) const
  {
    if (this->mode == Mode::All)
    {
      return true;
    }
    const bool first = this->has_atom(arc.first), second = this->has_atom(arc.second);
    const bool pinched_pair =
      this->mode == Mode::ConcaveCutters && first && second && arc.radius < this->probe;
    return !(first || second) || pinched_pair;
  }
  /// Whether any vertex passes (concave patches' cutters are arcs alone: other probes'
  /// positions are caps on the patch's sphere).
  bool admits_vertices() const
  {
    return this->mode != Mode::ConcaveCutters;
  }
  bool admits(const SasVertex& vertex) const
  {
    const auto& spheres = vertex.spheres;
    return this->mode == Mode::All ||
      (this->mode == Mode::TorusCutters && !this->has_atom(spheres[0]) &&
       !this->has_atom(spheres[1]) && !this->has_atom(spheres[2]));
  }

private:
  bool has_atom(std::uint32_t sphere) const
  {
    return sphere == this->atoms[0] || sphere == this->atoms[1] ||
      (this->mode == Mode::ConcaveCutters && sphere == this->atoms[2]);
  }
};

/// The pieces that may be nearest to some point of a ball: gathered once, they let many queries
/// inside the ball look at a handful of pieces instead of the index.
struct LocalPieces
{
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0; ///< of the ball, Å
  double limit = 0;  ///< queries are exact up to this distance inside the union
  /// Signed distance from the centre to the boundary (capped at limit + radius; 0 when gathered
  /// for filters).
  double centre_distance = 0;
  std::vector<std::uint32_t> spheres; ///< those that may hold a point of the ball
  /// Arcs and vertices that may be nearest to a point of the ball: (distance from the centre
  /// to the exposed arc or to the vertex, index), nearest first.
  std::vector<std::pair<double, std::uint32_t>> arcs, vertices;
};

/// max over the spheres `first` .. `last` (indices into `centres`, `radii`) of R - |x - c|: the
/// signed distance to their union's boundary outside it, a lower bound of it inside; `deepest`
/// (may be null) gets the first sphere giving it. -1e300 for no sphere.
inline double union_depth(const std::uint32_t* first, const std::uint32_t* last,
                          const std::vector<Eigen::Vector3d>& centres,
                          const std::vector<double>& radii, const Eigen::Vector3d& x,
                          std::uint32_t* deepest = nullptr)
{
  double best = -1e300;
  for (const std::uint32_t* s = first; s != last; ++s)
  {
    const double d = radii[*s] - (x - centres[*s]).norm();
    if (d > best)
    {
      best = d;
      if (deepest)
      {
        *deepest = *s;
      }
    }
  }
  return best;
}

/// Distance queries against the boundary of spheres `centres` with radii `radii` (those of
/// `boundary`, built with its pieces). Queries are exact within `reach` of the boundary and
/// may run concurrently.
class ProbeDistance
{
public:
  /// `reach` > 0. Throws InvalidInput when the spheres lie so far apart that its grid of cells
  /// (a quarter of the reach wide) would need more than 1e9 of them. The tables are built on
  /// the threads of `parallel_for` (empty: the calling thread).
  ProbeDistance(const std::vector<Eigen::Vector3d>& centres, const std::vector<double>& radii,
                const SasBoundary& boundary, double reach, const ParallelFor& parallel_for = {});

  using Filter = PieceFilter;

  /// The nearest boundary piece of `x` and the signed distance to it. Outside the union the
  /// distance is exact (the nearest sphere) up to max(reach, largest radius) less the largest
  /// radius; farther out it reports that bound, nearer zero than the truth, and
  /// PieceKind::None. Inside it is exact up to the reach, beyond which it reports the reach and
  /// PieceKind::None. With a filter, the nearest of the pieces it lets through (inside the
  /// union only).
  /// `limit` (<= the reach; 0: the reach) bounds the search inside the union: pieces farther
  /// are not looked for, and the distance reported is then the limit (PieceKind::None).
  ClosestPiece closest(const Eigen::Vector3d& x, const Filter& filter = {}, double limit = 0) const;

  /// The pieces that may be nearest to a point within `radius` (> 0) of `centre`, for searches
  /// up to `limit` (<= the reach) inside the union, into `local` (its buffers are reused). With
  /// `for_filters`, every piece within the limit of the ball, as filtered queries need.
  void gather(const Eigen::Vector3d& centre, double radius, double limit, LocalPieces& local,
              bool for_filters = false) const;

  /// gather() for a ball inside the ball of `parent`, from the parent's pieces alone.
  void refine(const LocalPieces& parent, const Eigen::Vector3d& centre, double radius,
              LocalPieces& local) const;

  /// The spheres that may hold a point within `radius` of `centre` (|c - centre| < R + radius),
  /// appended to `spheres`: from the index, or from `candidates` (those of a larger ball
  /// holding this one).
  void spheres_near(const Eigen::Vector3d& centre, double radius,
                    std::vector<std::uint32_t>& spheres) const;
  void spheres_near(const std::vector<std::uint32_t>& candidates, const Eigen::Vector3d& centre,
                    double radius, std::vector<std::uint32_t>& spheres) const;

  /// closest() among the gathered pieces alone, for a point within `local.radius` of their
  /// centre (farther points are answered from the index): the same answer up to `local.limit`
  /// inside the union and outside it. Spheres that do not reach the ball give no outside
  /// distance: there it may be more negative than the exact one (the sign is right). Filters
  /// need pieces gathered for them. `limit` (0: the local limit) bounds the search as in the
  /// index's closest().
  ClosestPiece closest(const LocalPieces& local, const Eigen::Vector3d& x,
                       const Filter& filter = {}, double limit = 0) const;

  /// The signed distance from `x` to the whole sphere, circle or point that carries a piece
  /// (as closest() reports it for that piece, without checking that the nearest point lies on
  /// the piece's exposed part): cheap, for root finding once the piece is known.
  double piece_distance(const Eigen::Vector3d& x, PieceKind kind, std::uint32_t index) const;

  /// The distance from `x` to exposed arc `k` (its ends included).
  double arc_distance(std::uint32_t k, const Eigen::Vector3d& x) const;
  /// The same, with the nearest point of the exposed arc in `nearest`.
  double arc_distance(std::uint32_t k, const Eigen::Vector3d& x, Eigen::Vector3d& nearest) const;
  /// Whether the distance from `x` to exposed arc `k` is below `bound` (Å); if so, that distance
  /// in `distance` (else left as it was). Cheaper than arc_distance() for arcs beyond the bound.
  bool arc_nearer(std::uint32_t k, const Eigen::Vector3d& x, double bound, double& distance) const;

  /// Whether the point `y` of sphere `i` lies outside each of its neighbours (to a relative
  /// 1e-12 of their squared radii): on the union's boundary, where `i` is exposed at all.
  bool uncovered(std::uint32_t i, const Eigen::Vector3d& y) const;

  /// Whether the point of arc `k`'s circle at in-plane coordinates (a1, a2) (along e1, e2 from
  /// its centre) lies on the exposed arc.
  bool within_span(std::uint32_t k, double a1, double a2) const
  {
    const SasArc& arc = this->boundary_.arcs[k];
    if (arc.span >= 2.0 * 3.14159265358979323846)
    {
      return true;
    }
    // By the signs of cross products with its ends (no angles).
    const ArcEnds& ends = this->arc_ends_[k];
    const bool after_start = ends.start_cos * a2 - ends.start_sin * a1 >= 0;
    const bool before_end = a1 * ends.end_sin - a2 * ends.end_cos >= 0;
    return arc.span <= 3.14159265358979323846 ? after_start && before_end
                                              : after_start || before_end;
  }

  /// Appends to `arcs` (sorted, each once) every arc `filter` admits with an exposed point within
  /// `radius` of `x`, and perhaps a few a little farther.
  void arcs_within(const Eigen::Vector3d& x, double radius, std::vector<std::uint32_t>& arcs,
                   const Filter& filter = {}) const;

  /// Calls `visit` with each vertex within `radius` of `x`, in index order of
  /// their cells.
  void vertices_within(const Eigen::Vector3d& x, double radius,
                       const std::function<void(std::uint32_t)>& visit) const;

  /// max over spheres of (R - |x - c|): the signed distance outside the union, a lower bound of
  /// it inside. -reach when no sphere is within reach. `sphere` gets the maximising sphere.
  double union_depth(const Eigen::Vector3d& x, std::uint32_t* sphere = nullptr) const;

  /// The bytes its cell tables hold (for checks that empty space costs little).
  std::size_t table_bytes() const;

private:
  /// Items per cell, stored by rows of cells along x. A row holds spans of consecutive cells
  /// from an occupied one to an occupied one, split where more than `largest_span_gap` empty
  /// cells lie between two, so that empty space costs a few bytes per row wherever the items
  /// lie (two atoms a kilometre apart on one row need two spans, not a billion cells).
  struct CellSpan
  {
    std::int32_t first = 0, last = -1; ///< cells along x
    std::uint32_t offset = 0;          ///< where the span's cells' first items are in `starts`
  };
  struct CellTable
  {
    std::vector<std::uint32_t> row_spans; ///< per row and one past, its first span in `spans`
    std::vector<CellSpan> spans;
    std::vector<std::uint32_t> starts; ///< per span's cell and one past, its first item
    std::vector<std::uint32_t> items;
  };
  /// The arcs' table, their pieces' middles and their ends' directions.
  void index_arcs();
  /// `table` from (cell, item) pairs (sorted here).
  void build_table(std::vector<std::pair<std::int64_t, std::uint32_t>>& pairs,
                   CellTable& table) const;
  template<typename Visit>
  void for_cells(const Eigen::Vector3d& x, double radius, const CellTable& table,
                 Visit&& visit) const;
  std::int64_t cell_of(const Eigen::Vector3d& x, std::array<std::int64_t, 3>& ijk) const;
  /// The spheres holding a query point, and the deepest sphere (see the source).
  struct SphereScan;
  /// Settles a query from its spheres when it can (far from all, or outside the union): sets
  /// `best`, true.
  bool outside_union(const SphereScan& scan, const Eigen::Vector3d& x, bool filtered,
                     ClosestPiece& best) const;
  /// When the nearest boundary point of `x` is on a face (the projection onto the deepest of
  /// the spheres holding it) nearer than `best`: sets `best`, true.
  bool nearest_face(const SphereScan& scan, const Eigen::Vector3d& x, ClosestPiece& best) const;
  /// The radial projection of `x` onto sphere `i`, when no other sphere covers it.
  bool exposed_projection(std::uint32_t i, const Eigen::Vector3d& x, Eigen::Vector3d& y) const;
  /// Where a point lies about arc `k`'s circle: along its axis, in its plane (along e1 and e2
  /// from its centre), how far from the axis, and the squared distance to the circle.
  struct ArcFrame
  {
    double along, a1, a2, radial, squared;
  };
  ArcFrame arc_frame(std::uint32_t k, const Eigen::Vector3d& x) const;
  /// arc_distance() from the frame of a point about the arc's circle.
  double arc_distance_in(std::uint32_t k, const Eigen::Vector3d& x, const ArcFrame& frame) const;
  /// Vertex `k` as the nearest piece when the filter admits it and it is nearer than
  /// `best.distance`: updates `best`.
  void try_vertex(std::uint32_t k, const Eigen::Vector3d& x, const Filter& filter,
                  ClosestPiece& best) const;
  /// Whether sphere `i` may hold a point within `radius` of `centre`.
  bool sphere_reaches(std::uint32_t i, const Eigen::Vector3d& centre, double radius) const;
  /// Arc `k` as the nearest piece when nearer than `best.distance`: updates `best`.
  void try_arc(std::uint32_t k, const Eigen::Vector3d& x, ClosestPiece& best) const;

  /// Per arc: cosine and sine of its start and end azimuths, for the span test.
  struct ArcEnds
  {
    double start_cos, start_sin, end_cos, end_sin;
  };

  const std::vector<Eigen::Vector3d>& centres_;
  const std::vector<double>& radii_;
  const SasBoundary& boundary_;
  double reach_ = 0;
  double largest_ = 0;       ///< the largest radius
  double outside_exact_ = 0; ///< union_depth() is exact outside the union to this less largest_
  double cell_ = 1;
  double arc_extent_ = 0; ///< every indexed arc piece lies within this of its middle
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  std::array<std::int64_t, 3> dims_{};
  // Per cell: the spheres centred in it, the arcs whose bounding ball overlaps it, the vertices
  // in it.
  CellTable spheres_;
  CellTable arc_cells_;                           ///< items: entries, indices into the two below
  std::vector<std::uint32_t> arc_items_;          ///< per entry, the arc
  std::vector<Eigen::Vector3d> arc_piece_middle_; ///< per entry, its piece's middle
  CellTable vertices_;
  std::vector<ArcEnds> arc_ends_;
};

} // namespace mesolens
