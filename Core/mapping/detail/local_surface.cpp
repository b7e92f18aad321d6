// SPDX-License-Identifier: GPL-3.0-or-later
#include "mapping/detail/local_surface.h"

#include "mesolens/common/errors.h"
#include "mapping/detail/edge_key.h"
#include "mapping/detail/triangle_closest_point.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace mesolens {
namespace detail {

namespace {
using Vec3 = std::array<double, 3>;
using Barycentric = std::array<double, 3>;

Vec3 minus(const Vec3& a, const Vec3& b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}
double dot(const Vec3& a, const Vec3& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c)
{
  return std::sqrt(closest_on_triangle(p, a, b, c).distance2);
}

/// How far the smooth patch over corners p (normals n) can stray from the flat triangle: every
/// control point of a PN triangle lies within half the largest |(p_j - p_i) . n_i| of it.
double patch_bulge(const std::array<Vec3, 3>& p, const std::array<Vec3, 3>& n)
{
  double largest = 0;
  for (std::size_t i = 0; i < 3; ++i)
  {
    for (std::size_t j = 0; j < 3; ++j)
    {
      if (i != j)
      {
        largest = std::max(largest, std::abs(dot(minus(p[j], p[i]), n[i])));
      }
    }
  }
  return 0.5 * largest;
}

/// Whether the smooth patch over corners p (normals n) may come within `reach` of `centre`:
/// the flat triangle does, within `bulge_factor` times the patch's bulge bound.
bool patch_within(const std::array<Vec3, 3>& p, const std::array<Vec3, 3>& n, const Vec3& centre,
                  double reach, double bulge_factor)
{
  return point_triangle_distance(centre, p[0], p[1], p[2]) <=
    reach + bulge_factor * patch_bulge(p, n);
}

/// Whether input triangle t (with its smooth patch) comes within `reach` of `centre`.
bool input_triangle_within(const SurfaceLevel& surface, std::int64_t t, const Vec3& centre,
                           double reach)
{
  const TriangleMesh& mesh = surface.mesh();
  const std::vector<double>& normals = surface.smooth->vertex_normals();
  std::array<Vec3, 3> p, n;
  for (std::size_t k = 0; k < 3; ++k)
  {
    const auto v = std::size_t(mesh.triangles[3 * std::size_t(t) + k]);
    p[k] = mesh.point(std::int64_t(v));
    n[k] = { normals[3 * v], normals[3 * v + 1], normals[3 * v + 2] };
  }
  return patch_within(p, n, centre, reach, 1.0);
}

/// Input triangles within reach, edge-connected to the seed's, in the order a breadth-first
/// walk meets them; stops once it has more than `limit`.
std::vector<std::int64_t> gather(const SurfaceLevel& surface, const SurfacePoint& seed,
                                 double reach, std::size_t limit,
                                 std::unordered_map<std::int64_t, bool>& seen)
{
  const MeshAdjacency& adjacency = surface.adjacency;
  std::vector<std::int64_t> region{ seed.triangle };
  seen[seed.triangle] = true;
  for (std::size_t i = 0; i < region.size() && region.size() <= limit; ++i)
  {
    for (std::size_t k = 0; k < 3; ++k)
    {
      const std::int64_t next = adjacency.across[3 * std::size_t(region[i]) + k];
      if (next < 0 || !seen.emplace(next, false).second)
      {
        continue;
      }
      if (input_triangle_within(surface, next, seed.position, reach))
      {
        seen[next] = true;
        region.push_back(next);
      }
    }
  }
  return region;
}

/// Adds every triangle around the region's vertices whose region triangles form more than one
/// fan (they would make the region non-manifold there), until there are none.
void complete_fans(const SurfaceLevel& surface, std::vector<std::int64_t>& region,
                   std::unordered_map<std::int64_t, bool>& seen)
{
  const TriangleMesh& mesh = surface.mesh();
  const MeshAdjacency& adjacency = surface.adjacency;
  auto in_region = [&seen](std::int64_t t) {
    const auto found = seen.find(t);
    return found != seen.end() && found->second;
  };
  for (bool changed = true; changed;)
  {
    changed = false;
    std::unordered_map<std::int64_t, int> border_edges;
    for (const std::int64_t t : region)
    {
      for (std::size_t k = 0; k < 3; ++k)
      {
        const std::int64_t other = adjacency.across[3 * std::size_t(t) + k];
        if (other < 0 || !in_region(other))
        {
          ++border_edges[mesh.triangles[3 * std::size_t(t) + k]];
          ++border_edges[mesh.triangles[3 * std::size_t(t) + (k + 1) % 3]];
        }
      }
    }
    std::vector<std::int64_t> pinched;
    for (const auto& [vertex, count] : border_edges)
    {
      if (count > 2)
      {
        pinched.push_back(vertex);
      }
    }
    std::sort(pinched.begin(), pinched.end()); // the hash map's order is not the input's
    for (const std::int64_t v : pinched)
    {
      for (std::size_t i = adjacency.vertex_start[std::size_t(v)];
           i < adjacency.vertex_start[std::size_t(v) + 1]; ++i)
      {
        const std::int64_t t = adjacency.vertex_triangles[i];
        if (!in_region(t))
        {
          seen[t] = true;
          region.push_back(t);
          changed = true;
        }
      }
    }
  }
}

/// The local mesh while it is refined: triangles live in slots; a bisected triangle keeps its
/// slot for one half and appends the other.
class Refinement
{
public:
  Refinement(const SurfaceLevel& surface, const Vec3& centre, double reach, double target_edge,
             std::size_t max_triangles)
    : Surface(surface)
    , Centre(centre)
    , Reach(reach)
    , TargetEdge2(target_edge * target_edge)
    , MaxTriangles(max_triangles)
  {
  }

  /// Stop (SolverFailure) when bisection has added more than `count` triangles; 0: no limit.
  void limit_refinement(std::size_t count)
  {
    this->InputCount = this->Corners.size();
    this->RefinedLimit = count > 0 ? this->InputCount + count : 0;
  }

  LocalSurface Out;
  std::vector<std::array<std::int64_t, 3>> Corners;
  std::vector<std::array<Barycentric, 3>> Bary;
  std::vector<int> Depth;

  void add_input_triangles(const std::vector<std::int64_t>& triangles)
  {
    const TriangleMesh& mesh = this->Surface.mesh();
    const std::vector<double>& normals = this->Surface.smooth->vertex_normals();
    std::unordered_map<std::int64_t, std::int64_t> local_of;
    for (const std::int64_t t : triangles)
    {
      std::array<std::int64_t, 3> corners{};
      for (std::size_t k = 0; k < 3; ++k)
      {
        const std::int64_t v = mesh.triangles[3 * std::size_t(t) + k];
        const auto found = local_of.emplace(v, std::int64_t(this->Out.original_vertex.size()));
        if (found.second)
        {
          const auto p = mesh.point(v);
          this->Out.mesh.points.insert(this->Out.mesh.points.end(), p.begin(), p.end());
          this->Out.normals.insert(this->Out.normals.end(), normals.begin() + long(3 * v),
                                   normals.begin() + long(3 * v + 3));
          this->Out.original_vertex.push_back(v);
        }
        corners[k] = found.first->second;
      }
      this->push_triangle(corners, t, { Barycentric{ 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } }, 0);
    }
  }

  void refine_all()
  {
    if (this->TargetEdge2 <= 0)
    {
      return;
    }
    std::vector<std::size_t> work;
    for (std::size_t t = 0; t < this->Corners.size(); ++t)
    {
      work.push_back(t);
    }
    // Depth-first over the work list keeps it short; the order is fixed, so the mesh is too.
    while (!work.empty())
    {
      const std::size_t t = work.back();
      work.pop_back();
      if (!this->needs_refinement(t))
      {
        continue;
      }
      this->Touched.clear();
      this->bisect(t);
      work.insert(work.end(), this->Touched.rbegin(), this->Touched.rend());
    }
  }

private:
  const SurfaceLevel& Surface;
  Vec3 Centre;
  double Reach;
  double TargetEdge2;
  std::size_t MaxTriangles;
  std::size_t InputCount = 0;   ///< triangles before bisection (limit_refinement)
  std::size_t RefinedLimit = 0; ///< InputCount + the bisections allowed; 0: none
  std::vector<std::int64_t> Source;
  std::unordered_map<std::uint64_t, std::array<std::int64_t, 2>> EdgeTriangles;
  std::vector<std::size_t> Touched;

  Vec3 point(std::int64_t v) const
  {
    return this->Out.mesh.point(v);
  }
  Vec3 normal(std::int64_t v) const
  {
    const auto i = std::size_t(3 * v);
    return { this->Out.normals[i], this->Out.normals[i + 1], this->Out.normals[i + 2] };
  }

  void push_triangle(const std::array<std::int64_t, 3>& corners, std::int64_t source,
                     const std::array<Barycentric, 3>& bary, int depth)
  {
    const std::size_t slot = this->Corners.size();
    this->Corners.push_back(corners);
    this->Source.push_back(source);
    this->Bary.push_back(bary);
    this->Depth.push_back(depth);
    for (std::size_t k = 0; k < 3; ++k)
    {
      this->attach(edge_key(corners[k], corners[(k + 1) % 3]), slot);
    }
  }

  void attach(std::uint64_t key, std::size_t slot)
  {
    auto found = this->EdgeTriangles.emplace(key, std::array<std::int64_t, 2>{ -1, -1 });
    auto& pair = found.first->second;
    (pair[0] < 0 ? pair[0] : pair[1]) = std::int64_t(slot);
  }

  void detach(std::uint64_t key, std::size_t slot)
  {
    auto& pair = this->EdgeTriangles.at(key);
    if (pair[0] == std::int64_t(slot))
    {
      pair[0] = pair[1];
    }
    pair[1] = -1;
    if (pair[0] < 0)
    {
      this->EdgeTriangles.erase(key);
    }
  }

  /// The corner k whose edge (k, k+1) is longest; ties go to the smaller edge key so that the
  /// longest-edge paths are strictly ordered and refinement terminates.
  std::size_t longest_edge(std::size_t t, double* length2 = nullptr) const
  {
    std::size_t best = 0;
    double best_length = -1;
    std::uint64_t best_key = 0;
    for (std::size_t k = 0; k < 3; ++k)
    {
      const std::int64_t a = this->Corners[t][k], b = this->Corners[t][(k + 1) % 3];
      const Vec3 d = minus(this->point(a), this->point(b));
      const double l = dot(d, d);
      const std::uint64_t key = edge_key(a, b);
      if (l > best_length || (l == best_length && key < best_key))
      {
        best = k;
        best_length = l;
        best_key = key;
      }
    }
    if (length2)
    {
      *length2 = best_length;
    }
    return best;
  }

  bool needs_refinement(std::size_t t) const
  {
    double length2 = 0;
    this->longest_edge(t, &length2);
    if (length2 <= this->TargetEdge2)
    {
      return false;
    }
    std::array<Vec3, 3> p, n;
    for (std::size_t k = 0; k < 3; ++k)
    {
      p[k] = this->point(this->Corners[t][k]);
      n[k] = this->normal(this->Corners[t][k]);
    }
    // 1.5 times the bulge bound: a piece of a patch bulges less than the bound its corners give,
    // but not by a known factor.
    return patch_within(p, n, this->Centre, this->Reach, 1.5);
  }

  std::int64_t other_triangle(std::uint64_t key, std::size_t t) const
  {
    const auto& pair = this->EdgeTriangles.at(key);
    return pair[0] == std::int64_t(t) ? pair[1] : pair[0];
  }

  /// Bisects t along its longest edge after making that edge the longest of the triangle
  /// across it (Rivara's longest-edge propagation path), so the mesh stays conforming.
  void bisect(std::size_t t)
  {
    std::vector<std::size_t> path{ t };
    while (!path.empty())
    {
      const std::size_t current = path.back();
      const std::size_t k = this->longest_edge(current);
      const std::int64_t a = this->Corners[current][k];
      const std::int64_t b = this->Corners[current][(k + 1) % 3];
      const std::uint64_t key = edge_key(a, b);
      const std::int64_t neighbour = this->other_triangle(key, current);
      if (neighbour >= 0)
      {
        const std::size_t nk = this->longest_edge(std::size_t(neighbour));
        if (edge_key(this->Corners[std::size_t(neighbour)][nk],
                     this->Corners[std::size_t(neighbour)][(nk + 1) % 3]) != key)
        {
          path.push_back(std::size_t(neighbour));
          continue;
        }
      }
      this->split_edge(current, k, neighbour);
      // Checked at every split: one propagation path may itself run long.
      this->require_within_limits();
      path.pop_back();
    }
  }

  void require_within_limits() const
  {
    if (this->Corners.size() > this->MaxTriangles)
    {
      throw SolverFailure("refining the surface around the seed needs more than " +
                          std::to_string(this->MaxTriangles) + " triangles");
    }
    if (this->RefinedLimit > 0 && this->Corners.size() > this->RefinedLimit)
    {
      throw SolverFailure(
        "refining the surface around the seed needs more than " +
        std::to_string(this->RefinedLimit - this->InputCount) +
        " new triangles: the mesh is too coarse and curved there for a disk this small; "
        "subdivide the mesh or choose a larger radius");
    }
  }

  /// Splits edge (corner k, k+1) of triangle t, and of `neighbour` across it (-1: none), at the
  /// smooth surface's point halfway along it (in t's input triangle).
  void split_edge(std::size_t t, std::size_t k, std::int64_t neighbour)
  {
    const std::int64_t a = this->Corners[t][k];
    const std::int64_t b = this->Corners[t][(k + 1) % 3];
    Barycentric middle{};
    for (std::size_t d = 0; d < 3; ++d)
    {
      middle[d] = 0.5 * (this->Bary[t][k][d] + this->Bary[t][(k + 1) % 3][d]);
    }
    const SmoothPoint on_surface = this->Surface.smooth->evaluate(this->Source[t], middle);
    const auto m = std::int64_t(this->Out.original_vertex.size());
    this->Out.mesh.points.insert(this->Out.mesh.points.end(), on_surface.position.begin(),
                                 on_surface.position.end());
    this->Out.normals.insert(this->Out.normals.end(), on_surface.normal.begin(),
                             on_surface.normal.end());
    this->Out.original_vertex.push_back(-1);
    this->split_triangle(t, a, b, m);
    if (neighbour >= 0)
    {
      this->split_triangle(std::size_t(neighbour), a, b, m);
    }
  }

  /// Replaces triangle t, which has edge {a, b}, by its two halves at vertex m.
  void split_triangle(std::size_t t, std::int64_t a, std::int64_t b, std::int64_t m)
  {
    const auto corners = this->Corners[t];
    const auto bary = this->Bary[t];
    std::size_t i = 0; // corner i -> i+1 runs along the edge, in the triangle's orientation
    while (!(corners[i] == a && corners[(i + 1) % 3] == b) &&
           !(corners[i] == b && corners[(i + 1) % 3] == a))
    {
      ++i;
    }
    const std::size_t j = (i + 1) % 3, c = (i + 2) % 3;
    Barycentric middle{};
    for (std::size_t d = 0; d < 3; ++d)
    {
      middle[d] = 0.5 * (bary[i][d] + bary[j][d]);
    }
    for (std::size_t k = 0; k < 3; ++k)
    {
      this->detach(edge_key(corners[k], corners[(k + 1) % 3]), t);
    }
    const int depth = this->Depth[t] + 1;
    // First half (corners i, m, c) in slot t, second (m, j, c) appended.
    this->Corners[t] = { corners[i], m, corners[c] };
    this->Bary[t] = { bary[i], middle, bary[c] };
    this->Depth[t] = depth;
    for (std::size_t k = 0; k < 3; ++k)
    {
      this->attach(edge_key(this->Corners[t][k], this->Corners[t][(k + 1) % 3]), t);
    }
    const std::size_t second = this->Corners.size();
    this->push_triangle({ m, corners[j], corners[c] }, this->Source[t],
                        { middle, bary[j], bary[c] }, depth);
    this->Touched.push_back(t);
    this->Touched.push_back(second);
  }

public:
  void finish()
  {
    for (std::size_t t = 0; t < this->Corners.size(); ++t)
    {
      this->Out.mesh.triangles.insert(this->Out.mesh.triangles.end(), this->Corners[t].begin(),
                                      this->Corners[t].end());
      this->Out.source_triangle.push_back(this->Source[t]);
      for (const Barycentric& corner : this->Bary[t])
      {
        this->Out.source_barycentric.insert(this->Out.source_barycentric.end(), corner.begin(),
                                            corner.end());
      }
      this->Out.bisection_depth = std::max(this->Out.bisection_depth, this->Depth[t]);
    }
  }
};

/// Where the input seed lies on the local mesh: the piece of its triangle that holds it.
SurfacePoint locate_seed(const LocalSurface& local, const SurfacePoint& seed)
{
  SurfacePoint best;
  double best_outside = std::numeric_limits<double>::max();
  for (std::size_t t = 0; t < local.source_triangle.size(); ++t)
  {
    if (local.source_triangle[t] != seed.triangle)
    {
      continue;
    }
    // Solve seed = c0 + l1 (c1 - c0) + l2 (c2 - c0) in the barycentric plane (components 1, 2).
    const double* c = &local.source_barycentric[9 * t];
    const double x1 = c[4] - c[1], y1 = c[5] - c[2];
    const double x2 = c[7] - c[1], y2 = c[8] - c[2];
    const double px = seed.barycentric[1] - c[1], py = seed.barycentric[2] - c[2];
    const double determinant = x1 * y2 - x2 * y1;
    if (determinant == 0)
    {
      continue;
    }
    const double l1 = (px * y2 - x2 * py) / determinant;
    const double l2 = (x1 * py - px * y1) / determinant;
    const double l0 = 1 - l1 - l2;
    const double outside = std::max({ 0.0, -l0, -l1, -l2 });
    if (outside < best_outside)
    {
      best_outside = outside;
      best.triangle = std::int64_t(t);
      best.barycentric = { l0, l1, l2 };
    }
  }
  if (best.triangle >= 0)
  {
    best.position = { 0, 0, 0 };
    for (std::size_t k = 0; k < 3; ++k)
    {
      const auto p = local.mesh.point(local.mesh.triangles[3 * std::size_t(best.triangle) + k]);
      for (std::size_t d = 0; d < 3; ++d)
      {
        best.position[d] += best.barycentric[k] * p[d];
      }
    }
  }
  return best;
}
} // namespace

LocalSurface local_surface(const SurfaceLevel& surface, const SurfacePoint& seed,
                           const LocalSurfaceParams& params)
{
  if (seed.triangle < 0 || std::size_t(seed.triangle) >= surface.mesh().triangle_count())
  {
    throw InvalidInput("the seed does not lie on a triangle of the surface");
  }
  if (!(params.reach > 0) || !std::isfinite(params.reach))
  {
    throw InvalidInput("the reach around the seed must be positive and finite");
  }
  const bool region_limited = params.max_region > 0 && params.max_region < params.max_triangles;
  const std::size_t limit = region_limited ? params.max_region : params.max_triangles;
  std::unordered_map<std::int64_t, bool> seen;
  std::vector<std::int64_t> region = gather(surface, seed, params.reach, limit, seen);
  if (region.size() > limit)
  {
    if (region_limited)
    {
      LocalSurface too_large;
      too_large.region_too_large = true;
      return too_large;
    }
    throw SolverFailure("more than " + std::to_string(params.max_triangles) +
                        " triangles of the surface lie within " + std::to_string(params.reach) +
                        " of the seed");
  }
  complete_fans(surface, region, seen);
  Refinement refinement(surface, seed.position, params.reach, params.target_edge,
                        params.max_triangles);
  refinement.add_input_triangles(region);
  refinement.limit_refinement(params.max_new_triangles);
  refinement.refine_all();
  refinement.finish();
  LocalSurface local = std::move(refinement.Out);
  local.seed = locate_seed(local, seed);
  return local;
}

} // namespace detail
} // namespace mesolens
