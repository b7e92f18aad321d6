// SPDX-License-Identifier: GPL-3.0-or-later
#include <Eigen/Dense>

#include "surface/detail/chord_refinement.h"

#include "surface/detail/balanced_loop.h"
#include "surface/detail/frozen_creases.h"
#include "common/detail/grid_cells.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

namespace mesolens {

namespace {
using Vec = Eigen::Vector3d;
/// Triangles per unit of parallel work: consecutive triangles of a contour lie close together,
/// so one focus serves a chunk's projections.
constexpr std::size_t chunk_triangles = 2048;
constexpr std::int64_t unsplit = -1;
/// Two corners' surface normals this far apart (cosine) mark a crease; a piece of a split
/// triangle and a new corner's normal, a fold.
constexpr double crease_cosine = 0.35;
constexpr double half_pi = 1.57079632679489661923;

/// An edge that may need a split: the triangle corner it starts from, its midpoint, and the
/// cube of focus it falls in.
struct Candidate
{
  std::uint64_t cube; ///< the cube as a key (grid_cell_key())
  std::size_t corner;
  Vec middle;
};

/// The new vertices of one chunk and the edges (lower end, upper end) they split. (A cache line
/// each: neighbouring chunks are filled at once by different threads.)
struct alignas(64) ChunkSplits
{
  std::vector<ContourVertex> vertices;
  std::vector<std::pair<std::int64_t, std::int64_t>> edges;
};

/// An edge (lower end, upper end) and the vertex splitting it.
using Split = std::array<std::int64_t, 3>;

/// The split edges by their lower end (compressed rows): the vertex on each.
class SplitEdges
{
public:
  SplitEdges(const std::vector<Split>& splits, std::size_t vertex_count)
    : start_(vertex_count + 1, 0)
    , items_(splits.size())
  {
    for (const Split& split : splits)
    {
      ++this->start_[std::size_t(split[0]) + 1];
    }
    for (std::size_t v = 0; v < vertex_count; ++v)
    {
      this->start_[v + 1] += this->start_[v];
    }
    std::vector<std::size_t> cursor(this->start_.begin(), this->start_.end() - 1);
    for (const Split& split : splits)
    {
      this->items_[cursor[std::size_t(split[0])]++] = { split[1], split[2] };
    }
  }

  /// The vertex splitting edge (a, b), or `unsplit`.
  std::int64_t find(std::int64_t a, std::int64_t b) const
  {
    const std::size_t lower = std::size_t(std::min(a, b));
    const std::int64_t upper = std::max(a, b);
    for (std::size_t k = this->start_[lower]; k < this->start_[lower + 1]; ++k)
    {
      if (this->items_[k].first == upper)
      {
        return this->items_[k].second;
      }
    }
    return unsplit;
  }

private:
  std::vector<std::size_t> start_;
  std::vector<std::pair<std::int64_t, std::int64_t>> items_; ///< (upper end, vertex)
};

/// Triangle (t0, t1, t2) cut along its split edges (m[k] on edge t_k t_k+1, or `unsplit`),
/// appended to `out` counter-clockwise as it was.
void cut_triangle(const std::array<std::int64_t, 3>& t, const std::array<std::int64_t, 3>& m,
                  const std::vector<ContourVertex>& vertices, std::vector<std::int64_t>& out)
{
  const auto emit = [&out](std::int64_t a, std::int64_t b, std::int64_t c) {
    out.insert(out.end(), { a, b, c });
  };
  const int marked = (m[0] != unsplit) + (m[1] != unsplit) + (m[2] != unsplit);
  if (marked == 0)
  {
    emit(t[0], t[1], t[2]);
  }
  else if (marked == 3)
  {
    emit(t[0], m[0], m[2]);
    emit(t[1], m[1], m[0]);
    emit(t[2], m[2], m[1]);
    emit(m[0], m[1], m[2]);
  }
  else if (marked == 1)
  {
    const int s = m[0] != unsplit ? 0 : (m[1] != unsplit ? 1 : 2);
    emit(t[s], m[s], t[(s + 2) % 3]);
    emit(m[s], t[(s + 1) % 3], t[(s + 2) % 3]);
  }
  else
  {
    // Unsplit edge (v2, v0); the corner at v1 is cut off, the quad left by its shorter diagonal.
    const int u = m[0] == unsplit ? 0 : (m[1] == unsplit ? 1 : 2);
    const std::int64_t v2 = t[u], v0 = t[(u + 1) % 3], v1 = t[(u + 2) % 3];
    const std::int64_t m01 = m[(u + 1) % 3], m12 = m[(u + 2) % 3];
    emit(m01, v1, m12);
    const auto at = [&](std::int64_t v) -> const Vec& { return vertices[std::size_t(v)].position; };
    if ((at(v0) - at(m12)).squaredNorm() <= (at(v2) - at(m01)).squaredNorm())
    {
      emit(v0, m01, m12);
      emit(v0, m12, v2);
    }
    else
    {
      emit(v0, m01, v2);
      emit(m01, m12, v2);
    }
  }
}

/// Whether a triangle whose corners are `a`, `b`, `c` with `normal` (their edges' cross
/// product) is a sliver, narrower than a tenth of its longest edge.
bool sliver(const Vec& a, const Vec& b, const Vec& c, const Vec& normal)
{
  const double longest =
    std::max({ (b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm() });
  return normal.norm() < 0.1 * longest;
}

/// Whether triangle (a, b, c) lies across the surface: a corner's surface normal more than
/// about 70 degrees from the triangle's. Slivers (narrower than a tenth of their longest edge)
/// only when they face away from a corner's normal: three nearly aligned points of a smooth
/// surface span a plane of almost any tilt.
bool lies_across(const ContourVertex& a, const ContourVertex& b, const ContourVertex& c)
{
  const Vec normal = (b.position - a.position).cross(c.position - a.position);
  const double least =
    sliver(a.position, b.position, c.position, normal) ? 0.0 : crease_cosine * normal.norm();
  return a.normal.dot(normal) < least || b.normal.dot(normal) < least ||
    c.normal.dot(normal) < least;
}

/// Whether triangle (a, b, c) spans a crease (two corners' normals far apart, their pieces not
/// smoothly joined) or lies across the surface.
bool at_a_crease(const ContourVertex& a, const ContourVertex& b, const ContourVertex& c,
                 const LocalSurfaceProjection& surface)
{
  const auto apart = [&](const ContourVertex& u, const ContourVertex& v) {
    return u.normal.dot(v.normal) < crease_cosine && !surface.smoothly_joined(u, v);
  };
  return lies_across(a, b, c) || apart(a, b) || apart(b, c) || apart(c, a);
}

/// Whether the pieces `children` (3 corners each) of triangle `t` face as it does (a sliver,
/// as the surface at its corners), none at a crease: splits that fold the mesh over a crease
/// fail.
bool children_face_outwards(const std::array<std::int64_t, 3>& t,
                            const std::vector<std::int64_t>& children,
                            const std::vector<ContourVertex>& vertices,
                            const LocalSurfaceProjection& surface)
{
  const auto at = [&](std::int64_t v) -> const ContourVertex& { return vertices[std::size_t(v)]; };
  Vec parent = (at(t[1]).position - at(t[0]).position).cross(at(t[2]).position - at(t[0]).position);
  if (sliver(at(t[0]).position, at(t[1]).position, at(t[2]).position, parent))
  {
    // Three nearly aligned points span a plane of almost any tilt.
    parent = at(t[0]).normal + at(t[1]).normal + at(t[2]).normal;
  }
  for (std::size_t k = 0; k < children.size(); k += 3)
  {
    const ContourVertex &a = at(children[k]), &b = at(children[k + 1]), &c = at(children[k + 2]);
    const Vec normal = (b.position - a.position).cross(c.position - a.position);
    if (!(normal.norm() > 0) || normal.dot(parent) <= 0 || at_a_crease(a, b, c, surface))
    {
      return false;
    }
  }
  return true;
}

/// Per triangle, whether it spans or lies across a crease: it stays as it is, as a split may fold
/// the mesh through the crease.
std::vector<char> crease_triangles(const ContourMesh& mesh, const LocalSurfaceProjection& surface,
                                   const ParallelFor& parallel_for)
{
  const std::size_t triangle_count = mesh.triangles.size() / 3;
  std::vector<char> crease(triangle_count, 0);
  run_parallel(parallel_for, triangle_count, [&](std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t)
    {
      const std::int64_t* corner = &mesh.triangles[3 * t];
      const auto at = [&](int k) -> const ContourVertex& {
        return mesh.vertices[std::size_t(corner[k])];
      };
      crease[t] = at_a_crease(at(0), at(1), at(2), surface) ? 1 : 0;
    }
  });
  return crease;
}

/// Per active triangle (by its place in the round's list), the splits proposed on its edges
/// (`unsplit` where none), and per proposed split whether it stays: split k's vertex is
/// vertex_count + k until the kept ones are renumbered.
struct ProposedMiddles
{
  std::vector<std::array<std::int64_t, 3>> of_triangle;
  std::vector<char> kept;
  std::size_t vertex_count = 0;

  /// The kept splits on active triangle k's edges.
  std::array<std::int64_t, 3> kept_of(std::size_t k) const
  {
    std::array<std::int64_t, 3> middles = this->of_triangle[k];
    for (std::int64_t& m : middles)
    {
      m = m != unsplit && this->kept[std::size_t(m) - this->vertex_count] ? m : unsplit;
    }
    return middles;
  }
};

/// Whether a triangle with these splits on its edges stays whole.
bool none_split(const std::array<std::int64_t, 3>& middles)
{
  return middles[0] == unsplit && middles[1] == unsplit && middles[2] == unsplit;
}

/// A refinement from round to round (refine_chords()): the mesh, the crease triangles that stay,
/// and the triangles to look at, which each round takes in chunks of chunk_triangles.
class ChordRefinement
{
public:
  ChordRefinement(ContourMesh& mesh, const SurfaceProjection& projection, double tolerance,
                  double focus_size, const ParallelFor& parallel_for)
    : mesh_(mesh)
    , projection_(projection)
    , tolerance_(tolerance)
    , focus_size_(focus_size)
    , parallel_for_(parallel_for)
    , surface_(projection())
    , frozen_(mesh, crease_triangles(mesh, *surface_, parallel_for), focus_size)
    , active_(mesh.triangles.size() / 3)
  {
    std::iota(this->active_.begin(), this->active_.end(), std::size_t(0));
  }

  bool has_active() const
  {
    return !this->active_.empty();
  }

  /// One round: splits proposed where edges stray from the surface, those that would fold the
  /// mesh dropped, the triangles cut along the others. False when none was made (the mesh is
  /// as it was, and no later round would make one).
  bool split_round()
  {
    this->vertex_count_ = this->mesh_.vertices.size();
    this->triangle_count_ = this->mesh_.triangles.size() / 3;
    this->chunks_ = (this->active_.size() + chunk_triangles - 1) / chunk_triangles;
    std::vector<ChunkSplits> splits = this->propose_splits();
    const std::vector<Split> proposed = this->append_split_vertices(splits);
    if (proposed.empty())
    {
      return false;
    }
    ProposedMiddles middles = this->proposed_middles(proposed);
    this->drop_folding_splits(middles);
    const std::vector<std::int64_t> renumbered = this->renumber_kept_vertices(middles.kept);
    if (this->mesh_.vertices.size() == this->vertex_count_)
    {
      return false;
    }
    this->cut_triangles(middles, renumbered);
    this->first_new_ = this->vertex_count_;
    return true;
  }

private:
  std::size_t chunk_end(std::size_t chunk) const
  {
    return std::min(this->active_.size(), (chunk + 1) * chunk_triangles);
  }
  /// Edge `corner` of the mesh's triangles: from that corner to the next one counter-clockwise.
  std::pair<std::int64_t, std::int64_t> edge_of(std::size_t corner) const
  {
    return { this->mesh_.triangles[corner],
             this->mesh_.triangles[corner - corner % 3 + (corner + 1) % 3] };
  }

  /// What a chunk's work reuses from chunk to chunk.
  struct ChunkState
  {
    std::unique_ptr<LocalSurfaceProjection> local;
    std::vector<Candidate> candidates;
  };
  std::vector<ChunkSplits> propose_splits() const;
  void list_candidates(std::size_t chunk, ChunkState& state) const;
  void project_candidates(ChunkState& state, ChunkSplits& out) const;
  std::vector<Split> append_split_vertices(std::vector<ChunkSplits>& splits);
  ProposedMiddles proposed_middles(const std::vector<Split>& proposed) const;
  void check_cut(std::size_t k, const ProposedMiddles& middles, std::vector<std::int64_t>& children,
                 std::vector<std::int64_t>& dropped) const;
  void drop_folding_splits(ProposedMiddles& middles) const;
  std::vector<std::int64_t> renumber_kept_vertices(const std::vector<char>& kept);
  void cut_triangles(const ProposedMiddles& middles, const std::vector<std::int64_t>& renumbered);

  ContourMesh& mesh_;
  const SurfaceProjection& projection_;
  const double tolerance_;
  const double focus_size_;
  const ParallelFor& parallel_for_;
  /// A projection of the refinement's own, for the crease and fold tests (smoothly_joined()).
  const std::unique_ptr<LocalSurfaceProjection> surface_;
  /// Crease triangles, found once: they stay, and the pieces of triangles cut beside them must
  /// not pass through them (nor span or lie across a crease themselves).
  const FrozenCreases frozen_;
  /// The triangles to look at, in increasing order: every one at first, then those the last
  /// round cut, which hold every edge with a new end (the only edges left to look at).
  std::vector<std::size_t> active_;
  std::size_t first_new_ = 0; ///< vertices from here on came from the last round
  /// The mesh's vertices, triangles, and chunks of active triangles as the round found them.
  std::size_t vertex_count_ = 0, triangle_count_ = 0, chunks_ = 0;
};

/// Per chunk, the edges that stray from the surface, split at their middles' projections.
/// Chunks differ widely in cost (most edges need no projection): taken one at a time.
std::vector<ChunkSplits> ChordRefinement::propose_splits() const
{
  std::vector<ChunkSplits> splits(this->chunks_);
  run_balanced<ChunkState>(this->parallel_for_, this->chunks_,
                           [&](std::size_t chunk, ChunkState& state) {
                             this->list_candidates(chunk, state);
                             if (!state.candidates.empty())
                             {
                               this->project_candidates(state, splits[chunk]);
                             }
                           });
  return splits;
}

/// The chunk's edges that may need a split (into state.candidates): each edge once, from the
/// side where it runs upwards; not those made before the last round (both ends older: looked at
/// then) nor those of triangles at a crease (they stay); and not those the surface's pieces at
/// their ends show to follow it within the tolerance.
void ChordRefinement::list_candidates(std::size_t chunk, ChunkState& state) const
{
  const double tolerance = this->tolerance_;
  std::unique_ptr<LocalSurfaceProjection>& local = state.local;
  std::vector<Candidate>& candidates = state.candidates;
  candidates.clear();
  for (std::size_t k = chunk * chunk_triangles; k < this->chunk_end(chunk); ++k)
  {
    for (std::size_t corner = 3 * this->active_[k]; corner < 3 * this->active_[k] + 3; ++corner)
    {
      const auto [a, b] = this->edge_of(corner);
      if (a > b || std::size_t(b) < this->first_new_ || this->frozen_.frozen_edge(a, b))
      {
        continue;
      }
      const ContourVertex& from = this->mesh_.vertices[std::size_t(a)];
      const ContourVertex& to = this->mesh_.vertices[std::size_t(b)];
      const Vec middle = 0.5 * (from.position + to.position);
      if (!local)
      {
        local = this->projection_();
      }
      const double gap = local->piece_gap(from, to, middle);
      if (std::isnan(gap))
      {
        // Kept when length * bend / 8 < tolerance / 2. The bend (angle between the
        // normals) lies between their chord and pi / 2 times it: most edges are settled
        // without the arc cosine. Up to twice that bend, kept when the midpoint lies within
        // the tolerance of the nearer end's piece: a third piece between the ends would
        // bend the edge more. (On 3wip at 0.11 Å this spares a third of the projections,
        // and 0.07 % more of the edges end beyond the tolerance.)
        const double length = (to.position - from.position).norm();
        const double largest_bend = 4.0 * tolerance / length;
        const double chord = (from.normal - to.normal).norm();
        if (chord < 2.0 * largest_bend)
        {
          const double bend = half_pi * chord < largest_bend
            ? 0.0
            : std::acos(std::clamp(from.normal.dot(to.normal), -1.0, 1.0));
          if (bend < largest_bend ||
              (bend < 2.0 * largest_bend && local->end_pieces_gap(from, to, middle) <= tolerance))
          {
            continue;
          }
        }
      }
      else if (gap <= tolerance)
      {
        continue;
      }
      candidates.push_back({ 0, corner, middle });
    }
  }
}

/// The candidates' middles projected onto the surface, each split kept (into `out`) when its
/// vertex lies beyond the tolerance, nearer than half the edge, facing as both ends do. Grouped
/// by cube of focus_size, each group projected under one focus: the ball of its midpoints, a
/// little wider for the projections (points that leave it are answered from the whole surface,
/// as exactly).
void ChordRefinement::project_candidates(ChunkState& state, ChunkSplits& out) const
{
  const double focus_size = this->focus_size_;
  LocalSurfaceProjection& local = *state.local;
  std::vector<Candidate>& candidates = state.candidates;
  for (Candidate& candidate : candidates)
  {
    candidate.cube = grid_cell_key(
      grid_cell({ candidate.middle[0], candidate.middle[1], candidate.middle[2] }, focus_size));
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) {
    return x.cube < y.cube || (x.cube == y.cube && x.corner < y.corner);
  });
  for (std::size_t first = 0; first < candidates.size();)
  {
    std::size_t last = first;
    Vec low = candidates[first].middle, high = low;
    while (last < candidates.size() && candidates[last].cube == candidates[first].cube)
    {
      low = low.cwiseMin(candidates[last].middle);
      high = high.cwiseMax(candidates[last].middle);
      ++last;
    }
    local.focus(0.5 * (low + high), 0.5 * (high - low).norm() + 0.1 * focus_size);
    for (std::size_t k = first; k < last; ++k)
    {
      const Vec& middle = candidates[k].middle;
      const auto [a, b] = this->edge_of(candidates[k].corner);
      const ContourVertex& from = this->mesh_.vertices[std::size_t(a)];
      const ContourVertex& to = this->mesh_.vertices[std::size_t(b)];
      ContourVertex vertex;
      if (!local.project_between(middle, from, to, vertex))
      {
        continue;
      }
      const double deviation = (vertex.position - middle).norm();
      const double half = 0.5 * (to.position - from.position).norm();
      if (deviation > this->tolerance_ && deviation < half && vertex.normal.dot(from.normal) > 0 &&
          vertex.normal.dot(to.normal) > 0)
      {
        out.vertices.push_back(vertex);
        out.edges.emplace_back(a, b);
      }
    }
    first = last;
  }
}

/// The proposed splits, their vertices appended to the mesh for now (chunk by chunk): split k
/// on edge (lower end, upper end) with vertex vertex_count + k. None (and the mesh as it was)
/// when no chunk proposed one.
std::vector<Split> ChordRefinement::append_split_vertices(std::vector<ChunkSplits>& splits)
{
  const std::size_t chunks = this->chunks_;
  const std::size_t vertex_count = this->vertex_count_;
  std::vector<std::size_t> first_split(chunks + 1, 0);
  for (std::size_t chunk = 0; chunk < chunks; ++chunk)
  {
    first_split[chunk + 1] = first_split[chunk] + splits[chunk].edges.size();
  }
  if (first_split[chunks] == 0)
  {
    return {};
  }
  std::vector<Split> proposed(first_split[chunks]);
  this->mesh_.vertices.resize(vertex_count + proposed.size());
  run_parallel(this->parallel_for_, chunks, [&](std::size_t begin, std::size_t end) {
    for (std::size_t chunk = begin; chunk < end; ++chunk)
    {
      ChunkSplits& own = splits[chunk];
      for (std::size_t k = 0; k < own.edges.size(); ++k)
      {
        const std::size_t at = first_split[chunk] + k;
        proposed[at] = { own.edges[k].first, own.edges[k].second, std::int64_t(vertex_count + at) };
        this->mesh_.vertices[vertex_count + at] = own.vertices[k];
      }
      own = {};
    }
  });
  return proposed;
}

/// The splits proposed on each active triangle's edges, looked up once; all kept for now.
ProposedMiddles ChordRefinement::proposed_middles(const std::vector<Split>& proposed) const
{
  ProposedMiddles middles;
  middles.vertex_count = this->vertex_count_;
  middles.kept.assign(proposed.size(), 1);
  middles.of_triangle.resize(this->active_.size());
  const SplitEdges proposed_edges(proposed, this->vertex_count_);
  run_parallel(this->parallel_for_, this->active_.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k)
    {
      const std::int64_t* corner = &this->mesh_.triangles[3 * this->active_[k]];
      for (std::size_t e = 0; e < 3; ++e)
      {
        middles.of_triangle[k][e] = proposed_edges.find(corner[e], corner[(e + 1) % 3]);
      }
    }
  });
  return middles;
}

/// Whether active triangle k, cut along its kept splits, folds or passes through a triangle
/// that stays at a crease: then those splits go (into `dropped`). (Those never have a split:
/// their edges are not looked at.)
void ChordRefinement::check_cut(std::size_t k, const ProposedMiddles& middles,
                                std::vector<std::int64_t>& children,
                                std::vector<std::int64_t>& dropped) const
{
  const std::size_t t = this->active_[k];
  const auto kept = middles.kept_of(k);
  const std::array<std::int64_t, 3> corners = { this->mesh_.triangles[3 * t],
                                                this->mesh_.triangles[3 * t + 1],
                                                this->mesh_.triangles[3 * t + 2] };
  children.clear();
  cut_triangle(corners, kept, this->mesh_.vertices, children);
  if (!children_face_outwards(corners, children, this->mesh_.vertices, *this->surface_) ||
      this->frozen_.meets(children, this->mesh_.vertices))
  {
    for (const std::int64_t m : kept)
    {
      if (m != unsplit)
      {
        dropped.push_back(m);
      }
    }
  }
}

/// Drops the splits whose triangles' pieces would fold the mesh, with every split of those
/// triangles: every cut triangle checked once (noting the splits' triangles), then again
/// those beside dropped splits until none drops.
void ChordRefinement::drop_folding_splits(ProposedMiddles& middles) const
{
  const std::size_t vertex_count = this->vertex_count_;
  // Per split, the places in `active` of the two triangles it cuts: first the one where its
  // edge runs from the lower end to the upper, then the other (the triangles are oriented
  // alike, so they run it in opposite directions, and each slot is written once).
  std::vector<std::array<std::size_t, 2>> cut_by(middles.kept.size(), { SIZE_MAX, SIZE_MAX });
  std::vector<std::vector<std::int64_t>> dropped(this->chunks_);
  run_parallel(this->parallel_for_, this->chunks_, [&](std::size_t begin, std::size_t end) {
    std::vector<std::int64_t> children;
    for (std::size_t chunk = begin; chunk < end; ++chunk)
    {
      for (std::size_t k = chunk * chunk_triangles; k < this->chunk_end(chunk); ++k)
      {
        const auto kept = middles.kept_of(k);
        if (none_split(kept))
        {
          continue;
        }
        const std::int64_t* corner = &this->mesh_.triangles[3 * this->active_[k]];
        for (std::size_t e = 0; e < 3; ++e)
        {
          if (kept[e] != unsplit)
          {
            const std::size_t slot = corner[e] < corner[(e + 1) % 3] ? 0 : 1;
            cut_by[std::size_t(kept[e]) - vertex_count][slot] = k;
          }
        }
        this->check_cut(k, middles, children, dropped[chunk]);
      }
    }
  });
  std::vector<std::int64_t> newly, children;
  for (const auto& chunk : dropped)
  {
    newly.insert(newly.end(), chunk.begin(), chunk.end());
  }
  while (!newly.empty())
  {
    std::vector<std::size_t> again;
    for (const std::int64_t m : newly)
    {
      const std::size_t k = std::size_t(m) - vertex_count;
      if (middles.kept[k])
      {
        middles.kept[k] = 0;
        for (const std::size_t place : cut_by[k])
        {
          if (place != SIZE_MAX)
          {
            again.push_back(place);
          }
        }
      }
    }
    std::sort(again.begin(), again.end());
    again.erase(std::unique(again.begin(), again.end()), again.end());
    newly.clear();
    for (const std::size_t place : again)
    {
      this->check_cut(place, middles, children, newly);
    }
  }
}

/// The kept split vertices renumbered in order after the mesh's, the others removed; per
/// proposed split its vertex's new index (`unsplit` when dropped).
std::vector<std::int64_t> ChordRefinement::renumber_kept_vertices(const std::vector<char>& kept)
{
  std::vector<ContourVertex>& vertices = this->mesh_.vertices;
  std::vector<std::int64_t> renumbered(kept.size(), unsplit);
  std::size_t next = this->vertex_count_;
  for (std::size_t k = 0; k < kept.size(); ++k)
  {
    if (kept[k])
    {
      vertices[next] = vertices[this->vertex_count_ + k];
      renumbered[k] = std::int64_t(next++);
    }
  }
  vertices.resize(next);
  return renumbered;
}

/// Cuts the active triangles along their kept splits. Each cut triangle's first piece takes its
/// place, the others follow the mesh's triangles chunk by chunk (so that consecutive triangles
/// stay close together); all of them are the next round's active triangles, the cut ones (which
/// keep their indices, below every added one) first: in increasing order again.
void ChordRefinement::cut_triangles(const ProposedMiddles& middles,
                                    const std::vector<std::int64_t>& renumbered)
{
  const std::size_t chunks = this->chunks_;
  const std::size_t triangle_count = this->triangle_count_;
  ContourMesh& mesh = this->mesh_;
  std::vector<std::size_t>& active = this->active_;
  std::vector<std::vector<std::int64_t>> added(chunks);
  std::vector<std::vector<std::size_t>> cut(chunks);
  run_parallel(this->parallel_for_, chunks, [&](std::size_t begin, std::size_t end) {
    std::vector<std::int64_t> pieces;
    for (std::size_t chunk = begin; chunk < end; ++chunk)
    {
      for (std::size_t k = chunk * chunk_triangles; k < this->chunk_end(chunk); ++k)
      {
        const std::size_t t = active[k];
        std::array<std::int64_t, 3> kept = middles.kept_of(k);
        if (none_split(kept))
        {
          continue;
        }
        for (std::int64_t& m : kept)
        {
          m = m == unsplit ? unsplit : renumbered[std::size_t(m) - this->vertex_count_];
        }
        std::int64_t* corner = &mesh.triangles[3 * t];
        const std::array<std::int64_t, 3> corners = { corner[0], corner[1], corner[2] };
        pieces.clear();
        cut_triangle(corners, kept, mesh.vertices, pieces);
        std::copy(pieces.begin(), pieces.begin() + 3, corner);
        added[chunk].insert(added[chunk].end(), pieces.begin() + 3, pieces.end());
        cut[chunk].push_back(t);
      }
    }
  });
  std::vector<std::size_t> offset(chunks + 1, mesh.triangles.size()), first_cut(chunks + 1, 0);
  for (std::size_t chunk = 0; chunk < chunks; ++chunk)
  {
    offset[chunk + 1] = offset[chunk] + added[chunk].size();
    first_cut[chunk + 1] = first_cut[chunk] + cut[chunk].size();
  }
  mesh.triangles.resize(offset[chunks]);
  active.resize(first_cut[chunks] + (offset[chunks] - 3 * triangle_count) / 3);
  run_parallel(this->parallel_for_, chunks, [&](std::size_t begin, std::size_t end) {
    for (std::size_t chunk = begin; chunk < end; ++chunk)
    {
      std::copy(added[chunk].begin(), added[chunk].end(),
                mesh.triangles.begin() + std::ptrdiff_t(offset[chunk]));
      std::copy(cut[chunk].begin(), cut[chunk].end(),
                active.begin() + std::ptrdiff_t(first_cut[chunk]));
      const std::size_t first_added = first_cut[chunks] + (offset[chunk] - 3 * triangle_count) / 3;
      for (std::size_t k = 0; k < added[chunk].size() / 3; ++k)
      {
        active[first_added + k] = offset[chunk] / 3 + k;
      }
      added[chunk] = {};
      cut[chunk] = {};
    }
  });
}
} // namespace

void refine_chords(ContourMesh& mesh, const SurfaceProjection& projection, double tolerance,
                   double focus_size, int max_rounds, const ParallelFor& parallel_for)
{
  ChordRefinement refinement(mesh, projection, tolerance, focus_size, parallel_for);
  for (int round = 0; round < max_rounds && refinement.has_active(); ++round)
  {
    if (!refinement.split_round())
    {
      break;
    }
  }
}

} // namespace mesolens
