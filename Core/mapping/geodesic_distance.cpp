// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/mapping/geodesic_distance.h"

#include "mesolens/common/errors.h"

#include "mesolens/mesh/surface_locator.h"
#include "mapping/detail/edge_key.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <numeric>
#include <queue>

namespace mesolens {

namespace {
constexpr double infinity = std::numeric_limits<double>::infinity();
constexpr int max_unfolding_steps = 10;

struct Vec2
{
  double x;
  double y;
};

double norm(const Vec2& v)
{
  return std::hypot(v.x, v.y);
}

double cross(const Vec2& a, const Vec2& b)
{
  return a.x * b.y - a.y * b.x;
}

double distance3(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                   (a[2] - b[2]) * (a[2] - b[2]));
}

/// The point at distance rp from p and rq from q, on the side of line pq away from `away`.
/// False when the two circles do not meet.
bool circle_intersection(const Vec2& p, double rp, const Vec2& q, double rq, const Vec2& away,
                         Vec2& out)
{
  const Vec2 pq{ q.x - p.x, q.y - p.y };
  const double d = norm(pq);
  if (d <= 0)
  {
    return false;
  }
  const double a = (rp * rp - rq * rq + d * d) / (2 * d);
  double h2 = rp * rp - a * a;
  if (h2 < 0)
  {
    if (h2 < -1e-12 * std::max(rp * rp, 1e-300))
    {
      return false;
    }
    h2 = 0;
  }
  const double h = std::sqrt(h2);
  const Vec2 base{ p.x + a * pq.x / d, p.y + a * pq.y / d };
  const Vec2 normal{ -pq.y / d, pq.x / d };
  const double away_side = cross(pq, Vec2{ away.x - p.x, away.y - p.y });
  const double sign = away_side > 0 ? -1.0 : 1.0;
  out = Vec2{ base.x + sign * h * normal.x, base.y + sign * h * normal.y };
  return true;
}

/// One update of `target` (at the origin of a local plane) from two vertices at p and q.
struct Stencil
{
  std::uint32_t target;
  std::uint32_t p;
  std::uint32_t q;
  float px, py, qx, qy;
};
} // namespace

std::vector<double> GeodesicField::dense(std::size_t vertex_count) const
{
  std::vector<double> all(vertex_count, infinity);
  for (std::size_t i = 0; i < this->vertices.size(); ++i)
  {
    if (this->vertices[i] < vertex_count)
    {
      all[this->vertices[i]] = this->distances[i];
    }
  }
  return all;
}

struct GeodesicSolver::Impl
{
  TriangleMesh Mesh;
  std::vector<Stencil> Stencils;
  std::vector<std::uint32_t> DependentStart; // CSR: stencils in which a vertex is p or q
  std::vector<std::uint32_t> Dependents;
  std::vector<std::uint8_t> Boundary; // per vertex: on a boundary edge
  double LongestEdge = 0;

  mutable std::once_flag LocatorBuilt;
  mutable std::unique_ptr<SurfaceLocator> Locator;

  // Work arrays reused between marches; only touched entries are reset.
  mutable std::vector<double> Distance;
  mutable std::vector<std::uint8_t> Final;
  mutable std::vector<std::uint32_t> Touched;

  std::array<double, 3> point(std::uint32_t v) const
  {
    return this->Mesh.point(v);
  }

  /// Triangle across edge (a, b) from `triangle`, or -1 on a boundary.
  std::int64_t across(const std::vector<std::pair<std::uint64_t, std::uint32_t>>& edges,
                      std::uint32_t a, std::uint32_t b, std::uint32_t triangle) const
  {
    const std::uint64_t key = detail::edge_key(a, b);
    auto it = std::lower_bound(edges.begin(), edges.end(), std::make_pair(key, std::uint32_t(0)));
    for (; it != edges.end() && it->first == key; ++it)
    {
      if (it->second != triangle)
      {
        return it->second;
      }
    }
    return -1;
  }

  std::uint32_t third_vertex(std::uint32_t triangle, std::uint32_t a, std::uint32_t b) const
  {
    for (int k = 0; k < 3; ++k)
    {
      const auto v =
        static_cast<std::uint32_t>(this->Mesh.triangles[3 * triangle + std::size_t(k)]);
      if (v != a && v != b)
      {
        return v;
      }
    }
    return a;
  }

  void add_stencil(std::uint32_t c, std::uint32_t p, const Vec2& pp, std::uint32_t q,
                   const Vec2& qq)
  {
    this->Stencils.push_back({ c, p, q, float(pp.x), float(pp.y), float(qq.x), float(qq.y) });
  }

  /// Stencils of corner c of `triangle` (neighbours p, q), splitting an obtuse angle by
  /// unfolding the strip of triangles across the opposite edge.
  void build_corner(std::uint32_t triangle, std::uint32_t c, std::uint32_t p, std::uint32_t q,
                    const std::vector<std::pair<std::uint64_t, std::uint32_t>>& edges)
  {
    const auto C = this->point(c);
    const auto P = this->point(p);
    const auto Q = this->point(q);
    const double cp = distance3(C, P);
    const double cq = distance3(C, Q);
    const double pq = distance3(P, Q);
    const double cos_angle = std::clamp((cp * cp + cq * cq - pq * pq) / (2 * cp * cq), -1.0, 1.0);
    const double angle = std::acos(cos_angle);
    const Vec2 p2{ cp, 0 };
    const Vec2 q2{ cq * cos_angle, cq * std::sin(angle) };
    if (cos_angle >= 0)
    {
      this->add_stencil(c, p, p2, q, q2);
      return;
    }
    // Obtuse: walk the strip across the edge facing c until a vertex lies inside the angle.
    std::uint32_t e1 = p;
    std::uint32_t e2 = q;
    Vec2 e1_2d = p2;
    Vec2 e2_2d = q2;
    std::uint32_t current = triangle;
    for (int step = 0; step < max_unfolding_steps; ++step)
    {
      const std::int64_t next = this->across(edges, e1, e2, current);
      if (next < 0)
      {
        break;
      }
      const std::uint32_t d = this->third_vertex(std::uint32_t(next), e1, e2);
      if (d == c)
      {
        break;
      }
      const auto D = this->point(d);
      Vec2 d2{};
      if (!circle_intersection(e1_2d, distance3(D, this->point(e1)), e2_2d,
                               distance3(D, this->point(e2)), Vec2{ 0, 0 }, d2))
      {
        break;
      }
      const double d_angle = std::atan2(d2.y, d2.x);
      if (d_angle > 0 && d_angle < angle)
      {
        this->add_stencil(c, p, p2, d, d2);
        this->add_stencil(c, d, d2, q, q2);
        return;
      }
      if (d_angle <= 0)
      {
        e1 = d; // D is on p's side: the angle continues through edge (d, e2)
        e1_2d = d2;
      }
      else
      {
        e2 = d;
        e2_2d = d2;
      }
      current = std::uint32_t(next);
    }
    this->add_stencil(c, p, p2, q, q2);
  }

  void build()
  {
    const std::size_t triangles = this->Mesh.triangle_count();
    std::vector<std::pair<std::uint64_t, std::uint32_t>> edges;
    edges.reserve(3 * triangles);
    for (std::uint32_t t = 0; t < triangles; ++t)
    {
      for (int k = 0; k < 3; ++k)
      {
        const auto a = std::uint32_t(this->Mesh.triangles[3 * t + std::size_t(k)]);
        const auto b = std::uint32_t(this->Mesh.triangles[3 * t + std::size_t((k + 1) % 3)]);
        edges.emplace_back(detail::edge_key(a, b), t);
        this->LongestEdge = std::max(this->LongestEdge, distance3(this->point(a), this->point(b)));
      }
    }
    std::sort(edges.begin(), edges.end());
    this->Boundary.assign(this->Mesh.vertex_count(), 0);
    for (std::size_t i = 0; i < edges.size();)
    {
      std::size_t j = i;
      while (j < edges.size() && edges[j].first == edges[i].first)
      {
        ++j;
      }
      if (j - i == 1)
      {
        this->Boundary[edges[i].first >> 32] = 1;
        this->Boundary[edges[i].first & 0xffffffffu] = 1;
      }
      i = j;
    }
    this->Stencils.reserve(3 * triangles + triangles / 2);
    for (std::uint32_t t = 0; t < triangles; ++t)
    {
      const auto v0 = std::uint32_t(this->Mesh.triangles[3 * t]);
      const auto v1 = std::uint32_t(this->Mesh.triangles[3 * t + 1]);
      const auto v2 = std::uint32_t(this->Mesh.triangles[3 * t + 2]);
      this->build_corner(t, v0, v1, v2, edges);
      this->build_corner(t, v1, v2, v0, edges);
      this->build_corner(t, v2, v0, v1, edges);
    }
    const std::size_t vertices = this->Mesh.vertex_count();
    this->DependentStart.assign(vertices + 1, 0);
    for (const Stencil& s : this->Stencils)
    {
      ++this->DependentStart[s.p + 1];
      ++this->DependentStart[s.q + 1];
    }
    std::partial_sum(this->DependentStart.begin(), this->DependentStart.end(),
                     this->DependentStart.begin());
    this->Dependents.resize(this->DependentStart.back());
    std::vector<std::uint32_t> fill(this->DependentStart.begin(), this->DependentStart.end() - 1);
    for (std::uint32_t s = 0; s < this->Stencils.size(); ++s)
    {
      this->Dependents[fill[this->Stencils[s].p]++] = s;
      this->Dependents[fill[this->Stencils[s].q]++] = s;
    }
    this->Distance.assign(vertices, infinity);
    this->Final.assign(vertices, 0);
  }

  /// The distance the stencil gives its target from the final distances of p and q.
  double update(const Stencil& s) const
  {
    const double tp = this->Final[s.p] ? this->Distance[s.p] : infinity;
    const double tq = this->Final[s.q] ? this->Distance[s.q] : infinity;
    const Vec2 p{ s.px, s.py };
    const Vec2 q{ s.qx, s.qy };
    const double along_edges = std::min(tp + norm(p), tq + norm(q));
    if (!std::isfinite(tp) || !std::isfinite(tq))
    {
      return along_edges;
    }
    // Virtual point source seen through the strip: at distance tp from p and tq from q, on the
    // far side of pq. Valid when the straight line from it to the target crosses segment pq.
    Vec2 source{};
    if (!circle_intersection(p, tp, q, tq, Vec2{ 0, 0 }, source))
    {
      return along_edges;
    }
    const Vec2 pq{ q.x - p.x, q.y - p.y };
    const double denominator = cross(pq, Vec2{ -source.x, -source.y });
    if (std::abs(denominator) <= 0)
    {
      return along_edges;
    }
    // Intersection of the line source -> origin with line p + s (q - p).
    const double along =
      cross(Vec2{ source.x - p.x, source.y - p.y }, Vec2{ -source.x, -source.y }) / denominator;
    if (along < -1e-9 || along > 1 + 1e-9)
    {
      return along_edges;
    }
    return std::min(norm(source), along_edges);
  }
};

GeodesicSolver::GeodesicSolver(TriangleMesh mesh)
  : Internal(std::make_unique<Impl>())
{
  require_manifold(mesh, "the surface mesh");
  if (mesh.vertex_count() >= std::numeric_limits<std::uint32_t>::max() ||
      mesh.triangle_count() >= std::numeric_limits<std::uint32_t>::max())
  {
    throw InvalidInput("geodesic distances support at most 2^32 - 1 vertices and triangles");
  }
  this->Internal->Mesh = std::move(mesh);
  this->Internal->build();
}

GeodesicSolver::~GeodesicSolver() = default;

const TriangleMesh& GeodesicSolver::mesh() const
{
  return this->Internal->Mesh;
}

double GeodesicSolver::longest_edge() const
{
  return this->Internal->LongestEdge;
}

bool GeodesicSolver::on_boundary(std::uint32_t vertex) const
{
  return vertex < this->Internal->Boundary.size() && this->Internal->Boundary[vertex] != 0;
}

SurfacePoint GeodesicSolver::closest_point(const std::array<double, 3>& point,
                                           double* distance) const
{
  Impl& impl = *this->Internal;
  std::call_once(impl.LocatorBuilt,
                 [&impl] { impl.Locator = std::make_unique<SurfaceLocator>(impl.Mesh); });
  return impl.Locator->closest_point(point, distance);
}

GeodesicField GeodesicSolver::distances(const SurfacePoint& seed, double stop_distance) const
{
  Impl& impl = *this->Internal;
  const TriangleMesh& mesh = impl.Mesh;
  if (seed.triangle < 0 || std::size_t(seed.triangle) >= mesh.triangle_count())
  {
    throw InvalidInput("the seed does not lie on a triangle of the mesh");
  }
  if (!(stop_distance > 0) || !std::isfinite(stop_distance))
  {
    throw InvalidInput("the geodesic radius must be positive and finite");
  }
  // The seed's position from its barycentric coordinates.
  std::array<double, 3> origin{ 0, 0, 0 };
  for (int k = 0; k < 3; ++k)
  {
    const auto v = mesh.point(mesh.triangles[3 * std::size_t(seed.triangle) + std::size_t(k)]);
    for (int d = 0; d < 3; ++d)
    {
      origin[std::size_t(d)] += seed.barycentric[std::size_t(k)] * v[std::size_t(d)];
    }
  }
  using Entry = std::pair<double, std::uint32_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> trial;
  auto touch = [&](std::uint32_t v, double d) {
    if (d < impl.Distance[v])
    {
      if (!std::isfinite(impl.Distance[v]))
      {
        impl.Touched.push_back(v);
      }
      impl.Distance[v] = d;
      trial.emplace(d, v);
    }
  };
  for (int k = 0; k < 3; ++k)
  {
    const auto v = std::uint32_t(mesh.triangles[3 * std::size_t(seed.triangle) + std::size_t(k)]);
    touch(v, distance3(origin, mesh.point(v)));
  }
  GeodesicField field;
  while (!trial.empty())
  {
    const auto [d, v] = trial.top();
    trial.pop();
    if (impl.Final[v] || d > impl.Distance[v])
    {
      continue;
    }
    if (d > stop_distance)
    {
      break;
    }
    impl.Final[v] = 1;
    field.vertices.push_back(v);
    field.distances.push_back(d);
    for (std::uint32_t k = impl.DependentStart[v]; k < impl.DependentStart[v + 1]; ++k)
    {
      const Stencil& s = impl.Stencils[impl.Dependents[k]];
      if (!impl.Final[s.target])
      {
        touch(s.target, impl.update(s));
      }
    }
  }
  for (const std::uint32_t v : impl.Touched)
  {
    impl.Distance[v] = infinity;
    impl.Final[v] = 0;
  }
  impl.Touched.clear();
  return field;
}

} // namespace mesolens
