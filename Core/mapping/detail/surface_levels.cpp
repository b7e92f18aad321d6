// SPDX-License-Identifier: GPL-3.0-or-later
#include "mapping/detail/surface_levels.h"

#include "mapping/detail/triangle_closest_point.h"

#include <algorithm>
#include <cmath>

namespace mesolens {
namespace detail {

namespace {
using Vec3 = std::array<double, 3>;

Vec3 minus(const Vec3& a, const Vec3& b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}
Vec3 cross(const Vec3& a, const Vec3& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}
double dot(const Vec3& a, const Vec3& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// A collapse may turn no triangle's normal by more than this (cosine of 60 degrees).
constexpr double smallest_normal_cosine = 0.5;

/// Quarters a mesh's vertices in rounds of independent edge collapses: each round takes the
/// vertices in order and collapses each one's shortest edge into it when that keeps the
/// surface a manifold of the same topology (the link condition: the edge's ends share exactly
/// the two vertices opposite it), moves no boundary vertex, and turns no triangle by more than
/// 60 degrees or makes one degenerate; the collapse then locks both ends' neighbourhoods for the
/// rest of the round, so every check sees the mesh as the round found it. Simple, O(F) per
/// round and deterministic, where a global priority queue (CGAL's or OpenMesh's decimaters)
/// takes 10 to 20 s on 2 M triangles.
class RoundDecimation
{
public:
  /// `mesh` and `input_vertex` must outlive the decimation (its vertices never move).
  RoundDecimation(const TriangleMesh& mesh, const std::vector<std::int64_t>& input_vertex)
    : Points(mesh.points)
    , InputVertex(input_vertex)
  {
    this->Triangles.reserve(mesh.triangle_count());
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    {
      this->Triangles.push_back(
        { mesh.triangles[3 * t], mesh.triangles[3 * t + 1], mesh.triangles[3 * t + 2] });
    }
  }

  /// Collapses rounds until at most `target` vertices are used or a round achieves little.
  void run(std::size_t target)
  {
    std::size_t used = this->Points.size() / 3;
    while (used > target)
    {
      const std::size_t collapsed = this->round(used - target);
      used -= collapsed;
      if (collapsed < used / 50)
      {
        break;
      }
    }
  }

  /// The decimated mesh (unused vertices dropped) and each vertex's input vertex.
  TriangleMesh result(std::vector<std::int64_t>& input_vertex) const
  {
    std::vector<std::int64_t> index(this->Points.size() / 3, -1);
    TriangleMesh out;
    input_vertex.clear();
    for (const auto& triangle : this->Triangles)
    {
      if (triangle[0] < 0)
      {
        continue;
      }
      for (const std::int64_t v : triangle)
      {
        if (index[std::size_t(v)] < 0)
        {
          index[std::size_t(v)] = std::int64_t(input_vertex.size());
          out.points.insert(out.points.end(), this->Points.begin() + 3 * v,
                            this->Points.begin() + 3 * v + 3);
          input_vertex.push_back(this->InputVertex[std::size_t(v)]);
        }
        out.triangles.push_back(index[std::size_t(v)]);
      }
    }
    return out;
  }

private:
  const std::vector<double>& Points;
  const std::vector<std::int64_t>& InputVertex;
  std::vector<std::array<std::int64_t, 3>> Triangles; // [0] = -1: removed
  // Per round: triangles around each vertex (CSR) and what is locked.
  std::vector<std::size_t> Start;
  std::vector<std::int64_t> Around;
  std::vector<std::uint8_t> Locked;
  std::vector<std::uint8_t> Boundary;

  Vec3 point(std::int64_t v) const
  {
    return { this->Points[std::size_t(3 * v)], this->Points[std::size_t(3 * v + 1)],
             this->Points[std::size_t(3 * v + 2)] };
  }

  void index_round()
  {
    const std::size_t vertices = this->Points.size() / 3;
    this->Start.assign(vertices + 1, 0);
    for (const auto& triangle : this->Triangles)
    {
      for (std::size_t k = 0; triangle[0] >= 0 && k < 3; ++k)
      {
        ++this->Start[std::size_t(triangle[k]) + 1];
      }
    }
    for (std::size_t v = 0; v < vertices; ++v)
    {
      this->Start[v + 1] += this->Start[v];
    }
    this->Around.resize(this->Start.back());
    std::vector<std::size_t> fill(this->Start.begin(), this->Start.end() - 1);
    for (std::size_t t = 0; t < this->Triangles.size(); ++t)
    {
      for (std::size_t k = 0; this->Triangles[t][0] >= 0 && k < 3; ++k)
      {
        this->Around[fill[std::size_t(this->Triangles[t][k])]++] = std::int64_t(t);
      }
    }
    this->Locked.assign(vertices, 0);
    // A vertex is on the boundary when some edge from it has one triangle: in a manifold, when
    // it has as many triangles as neighbours minus one.
    this->Boundary.assign(vertices, 0);
    std::vector<std::int64_t> ring;
    for (std::size_t v = 0; v < vertices; ++v)
    {
      this->neighbours(std::int64_t(v), ring);
      this->Boundary[v] = ring.size() != this->Start[v + 1] - this->Start[v];
    }
  }

  void neighbours(std::int64_t v, std::vector<std::int64_t>& ring) const
  {
    ring.clear();
    for (std::size_t i = this->Start[std::size_t(v)]; i < this->Start[std::size_t(v) + 1]; ++i)
    {
      for (const std::int64_t w : this->Triangles[std::size_t(this->Around[i])])
      {
        if (w != v && std::find(ring.begin(), ring.end(), w) == ring.end())
        {
          ring.push_back(w);
        }
      }
    }
  }

  /// Whether moving b onto a (collapsing b into a) keeps every other triangle around b turned
  /// by at most 60 degrees and not degenerate; a's other triangles do not change.
  bool keeps_orientation(std::int64_t a, std::int64_t b) const
  {
    const Vec3 target = this->point(a);
    for (std::size_t i = this->Start[std::size_t(b)]; i < this->Start[std::size_t(b) + 1]; ++i)
    {
      const auto& triangle = this->Triangles[std::size_t(this->Around[i])];
      if (std::find(triangle.begin(), triangle.end(), a) != triangle.end())
      {
        continue; // removed by the collapse
      }
      std::array<Vec3, 3> before, after;
      for (std::size_t k = 0; k < 3; ++k)
      {
        before[k] = this->point(triangle[k]);
        after[k] = triangle[k] == b ? target : before[k];
      }
      const Vec3 n0 = cross(minus(before[1], before[0]), minus(before[2], before[0]));
      const Vec3 n1 = cross(minus(after[1], after[0]), minus(after[2], after[0]));
      const double l0 = std::sqrt(dot(n0, n0)), l1 = std::sqrt(dot(n1, n1));
      if (!(l1 > 1e-6 * l0) || dot(n0, n1) < smallest_normal_cosine * l0 * l1)
      {
        return false;
      }
    }
    return true;
  }

  /// One round; returns how many vertices it removed (at most `wanted`).
  std::size_t round(std::size_t wanted)
  {
    this->index_round();
    const std::size_t vertices = this->Points.size() / 3;
    std::vector<std::int64_t> ring_a, ring_b;
    std::vector<std::pair<double, std::int64_t>> candidates;
    std::size_t collapsed = 0;
    for (std::size_t a = 0; a < vertices && collapsed < wanted; ++a)
    {
      if (this->Locked[a] || this->Boundary[a] || this->Start[a] == this->Start[a + 1])
      {
        continue;
      }
      this->neighbours(std::int64_t(a), ring_a);
      // Its edges to unlocked interior neighbours, shortest first: the first that may go.
      candidates.clear();
      for (const std::int64_t w : ring_a)
      {
        if (!this->Locked[std::size_t(w)] && !this->Boundary[std::size_t(w)])
        {
          const Vec3 d = minus(this->point(w), this->point(std::int64_t(a)));
          candidates.emplace_back(dot(d, d), w);
        }
      }
      std::sort(candidates.begin(), candidates.end());
      std::int64_t b = -1;
      for (const auto& candidate : candidates)
      {
        this->neighbours(candidate.second, ring_b);
        std::size_t shared = 0;
        bool opposite_keep_three = true; // the two vertices opposite the edge lose one each
        for (const std::int64_t w : ring_a)
        {
          if (std::find(ring_b.begin(), ring_b.end(), w) != ring_b.end())
          {
            ++shared;
            opposite_keep_three = opposite_keep_three &&
              this->Start[std::size_t(w) + 1] - this->Start[std::size_t(w)] > 3;
          }
        }
        // a stays where it is: every vertex of a copy is one of the input's.
        if (shared == 2 && opposite_keep_three && ring_a.size() + ring_b.size() >= 7 &&
            this->keeps_orientation(std::int64_t(a), candidate.second))
        {
          b = candidate.second;
          break;
        }
      }
      if (b < 0)
      {
        continue;
      }
      // Collapse b into a.
      for (std::size_t i = this->Start[std::size_t(b)]; i < this->Start[std::size_t(b) + 1]; ++i)
      {
        auto& triangle = this->Triangles[std::size_t(this->Around[i])];
        if (std::find(triangle.begin(), triangle.end(), std::int64_t(a)) != triangle.end())
        {
          triangle = { -1, -1, -1 };
          continue;
        }
        std::replace(triangle.begin(), triangle.end(), b, std::int64_t(a));
      }
      for (const auto* ring : { &ring_a, &ring_b })
      {
        for (const std::int64_t w : *ring)
        {
          this->Locked[std::size_t(w)] = 1;
        }
      }
      this->Locked[a] = 1;
      ++collapsed;
    }
    return collapsed;
  }
};

/// One level from `finer` (whose vertices are input vertices `input_of`), with about a quarter
/// of its vertices, all of them input vertices, and the input's normals at them: its smooth
/// surface then follows the input's closely.
std::unique_ptr<SurfaceLevel> decimate(const TriangleMesh& finer,
                                       const std::vector<std::int64_t>& input_of,
                                       const SurfaceLevel& input)
{
  RoundDecimation decimation(finer, input_of);
  decimation.run(finer.vertex_count() / 4);
  auto level = std::make_unique<SurfaceLevel>();
  TriangleMesh mesh = decimation.result(level->input_vertex);
  std::vector<double> normals;
  normals.reserve(mesh.points.size());
  for (const std::int64_t v : level->input_vertex)
  {
    level->anchor_triangle.push_back(input.anchor_triangle[std::size_t(v)]);
    const auto& n = input.smooth->vertex_normals();
    normals.insert(normals.end(), n.begin() + long(3 * v), n.begin() + long(3 * v + 3));
  }
  level->adjacency = mesh_adjacency(mesh);
  level->smooth = std::make_shared<const SmoothSurface>(std::move(mesh), std::move(normals));
  return level;
}
} // namespace

SurfacePoint SurfaceLevel::closest_point(const std::array<double, 3>& point) const
{
  return this->locator().closest_point(point);
}

const SurfaceLocator& SurfaceLevel::locator() const
{
  std::call_once(this->LocatorBuilt,
                 [this] { this->Locator = std::make_unique<SurfaceLocator>(this->mesh()); });
  return *this->Locator;
}

void SurfaceLevel::measure()
{
  const TriangleMesh& mesh = this->mesh();
  double total = 0;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
  {
    const Vec3 a = mesh.point(mesh.triangles[3 * t]);
    const Vec3 n = cross(minus(mesh.point(mesh.triangles[3 * t + 1]), a),
                         minus(mesh.point(mesh.triangles[3 * t + 2]), a));
    total += 0.5 * std::sqrt(dot(n, n));
  }
  this->mean_triangle_area = mesh.triangle_count() ? total / double(mesh.triangle_count()) : 0;
}

std::vector<std::unique_ptr<SurfaceLevel>> coarser_levels(const SurfaceLevel& input,
                                                          std::size_t smallest)
{
  std::vector<std::unique_ptr<SurfaceLevel>> levels;
  const SurfaceLevel* finer = &input;
  while (finer->mesh().vertex_count() > smallest)
  {
    const std::size_t before = finer->mesh().vertex_count();
    auto level = decimate(finer->mesh(), finer->input_vertex, input);
    if (level->mesh().vertex_count() > before * 3 / 4)
    {
      break; // collapses stopped (locked borders, thin features): no useful level
    }
    level->measure();
    level->locator(); // built now: clicks then find their seed on it at once
    levels.push_back(std::move(level));
    finer = levels.back().get();
  }
  return levels;
}

SurfacePoint walk_to_closest(const TriangleMesh& mesh, const MeshAdjacency& adjacency,
                             std::int64_t start, const std::array<double, 3>& point, int max_steps)
{
  auto closest_on = [&](std::int64_t t) {
    return closest_on_triangle(point, mesh.point(mesh.triangles[3 * std::size_t(t)]),
                               mesh.point(mesh.triangles[3 * std::size_t(t) + 1]),
                               mesh.point(mesh.triangles[3 * std::size_t(t) + 2]));
  };
  std::int64_t current = start;
  TriangleClosestPoint best = closest_on(current);
  for (int step = 0; step < max_steps; ++step)
  {
    // On an edge or a corner of the current triangle, the closest point may lie beyond it.
    std::int64_t next = -1;
    TriangleClosestPoint next_point = best;
    auto consider = [&](std::int64_t t) {
      if (t < 0 || t == current)
      {
        return;
      }
      const TriangleClosestPoint candidate = closest_on(t);
      if (candidate.distance2 < next_point.distance2)
      {
        next = t;
        next_point = candidate;
      }
    };
    for (std::size_t k = 0; k < 3; ++k)
    {
      if (best.barycentric[k] > 0)
      {
        continue;
      }
      // Opposite corner k lies the edge (k + 1, k + 2): adjacency slot k + 1.
      consider(adjacency.across[3 * std::size_t(current) + (k + 1) % 3]);
      if (best.barycentric[(k + 1) % 3] <= 0 || best.barycentric[(k + 2) % 3] <= 0)
      {
        // At a corner: every triangle around it.
        const std::size_t corner = best.barycentric[(k + 1) % 3] <= 0 ? (k + 2) % 3 : (k + 1) % 3;
        const auto v = std::size_t(mesh.triangles[3 * std::size_t(current) + corner]);
        for (std::size_t i = adjacency.vertex_start[v]; i < adjacency.vertex_start[v + 1]; ++i)
        {
          consider(adjacency.vertex_triangles[i]);
        }
      }
    }
    if (next < 0)
    {
      SurfacePoint found;
      found.triangle = current;
      found.barycentric = best.barycentric;
      found.position = best.position;
      return found;
    }
    current = next;
    best = next_point;
  }
  return SurfacePoint{};
}

SurfacePoint walk_along_line(const TriangleMesh& mesh, const MeshAdjacency& adjacency,
                             std::int64_t start, const std::array<double, 3>& point,
                             const std::array<double, 3>& direction, int max_steps)
{
  std::int64_t current = start;
  std::int64_t previous = -1;
  for (int step = 0; step < max_steps && current >= 0; ++step)
  {
    const auto t = std::size_t(current);
    const Vec3 a = mesh.point(mesh.triangles[3 * t]);
    const Vec3 b = mesh.point(mesh.triangles[3 * t + 1]);
    const Vec3 c = mesh.point(mesh.triangles[3 * t + 2]);
    const Vec3 normal = cross(minus(b, a), minus(c, a));
    const double facing = dot(direction, normal);
    if (std::abs(facing) <= 1e-3 * std::sqrt(dot(direction, direction) * dot(normal, normal)))
    {
      break;
    }
    const double along = dot(minus(a, point), normal) / facing;
    const Vec3 hit{ point[0] + along * direction[0], point[1] + along * direction[1],
                    point[2] + along * direction[2] };
    // Barycentric coordinates from the sub-triangles' signed areas.
    const double area = dot(normal, normal);
    const std::array<double, 3> weights{ dot(cross(minus(b, hit), minus(c, hit)), normal) / area,
                                         dot(cross(minus(c, hit), minus(a, hit)), normal) / area,
                                         dot(cross(minus(a, hit), minus(b, hit)), normal) / area };
    std::size_t lowest = 0;
    for (std::size_t k = 1; k < 3; ++k)
    {
      lowest = weights[k] < weights[lowest] ? k : lowest;
    }
    if (weights[lowest] >= -1e-12)
    {
      SurfacePoint found;
      found.triangle = current;
      found.barycentric = weights;
      found.position = hit;
      return found;
    }
    // Beyond the edge opposite the most negative corner: edge (lowest + 1, lowest + 2).
    const std::int64_t next = adjacency.across[3 * t + (lowest + 1) % 3];
    if (next == previous)
    {
      break; // the crossing lies on the edge between the two: no progress
    }
    previous = current;
    current = next;
  }
  return SurfacePoint{};
}

} // namespace detail
} // namespace mesolens
