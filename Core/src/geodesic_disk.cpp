// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/geodesic_disk.h"

#include "mesolens/errors.h"
#include "mesh_subdivision.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <sstream>
#include <unordered_map>

namespace mesolens {

namespace {
std::uint64_t edge_key(std::int64_t a, std::int64_t b)
{
  return (std::uint64_t(std::min(a, b)) << 32) | std::uint64_t(std::max(a, b));
}

std::string format_length(double value)
{
  std::ostringstream text;
  text << value;
  return text.str();
}

/// The part of `mesh` where distance <= radius, cut along the isoline; triangles carry the
/// index of the mesh triangle they come from.
struct Clipped
{
  TriangleMesh mesh;
  std::vector<double> distance;
  std::vector<std::int64_t> origin;          // per vertex: mesh vertex or -1
  std::vector<std::int64_t> source_triangle; // per triangle
};

Clipped clip_below(const TriangleMesh& mesh, const std::vector<double>& distance, double radius)
{
  Clipped out;
  std::unordered_map<std::int64_t, std::int64_t> vertex_of;
  std::unordered_map<std::uint64_t, std::int64_t> cut_of;
  auto add_vertex = [&out](const std::array<double, 3>& p, double d, std::int64_t origin) {
    out.mesh.points.insert(out.mesh.points.end(), { p[0], p[1], p[2] });
    out.distance.push_back(d);
    out.origin.push_back(origin);
    return std::int64_t(out.distance.size() - 1);
  };
  auto inside_vertex = [&](std::int64_t v) {
    const auto found = vertex_of.find(v);
    if (found != vertex_of.end())
    {
      return found->second;
    }
    return vertex_of[v] = add_vertex(mesh.point(v), distance[std::size_t(v)], v);
  };
  auto cut = [&](std::int64_t inside, std::int64_t outside) {
    const double t = (radius - distance[std::size_t(inside)]) /
      (distance[std::size_t(outside)] - distance[std::size_t(inside)]);
    if (t < 1e-6)
    {
      return inside_vertex(inside); // the isoline passes through the inside vertex
    }
    const std::uint64_t key = edge_key(inside, outside);
    const auto found = cut_of.find(key);
    if (found != cut_of.end())
    {
      return found->second;
    }
    const auto a = mesh.point(inside);
    const auto b = mesh.point(outside);
    const std::array<double, 3> p{ a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]),
                                   a[2] + t * (b[2] - a[2]) };
    return cut_of[key] = add_vertex(p, radius, -1);
  };
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
  {
    const std::int64_t v[3] = { mesh.triangles[3 * t], mesh.triangles[3 * t + 1],
                                mesh.triangles[3 * t + 2] };
    const bool in[3] = { distance[std::size_t(v[0])] <= radius,
                         distance[std::size_t(v[1])] <= radius,
                         distance[std::size_t(v[2])] <= radius };
    if (!in[0] && !in[1] && !in[2])
    {
      continue;
    }
    std::vector<std::int64_t> polygon;
    for (int k = 0; k < 3; ++k)
    {
      const int next = (k + 1) % 3;
      if (in[k])
      {
        polygon.push_back(inside_vertex(v[k]));
      }
      if (in[k] != in[next])
      {
        polygon.push_back(in[k] ? cut(v[k], v[next]) : cut(v[next], v[k]));
      }
    }
    polygon.erase(std::unique(polygon.begin(), polygon.end()), polygon.end());
    if (polygon.size() > 1 && polygon.front() == polygon.back())
    {
      polygon.pop_back();
    }
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
    {
      out.mesh.triangles.insert(out.mesh.triangles.end(),
                                { polygon[0], polygon[k], polygon[k + 1] });
      out.source_triangle.push_back(std::int64_t(t));
    }
  }
  return out;
}

/// Keeps the edge-connected component of `keep_triangle`; drops unused vertices.
Clipped component_of(const Clipped& in, std::int64_t keep_triangle)
{
  const std::size_t n = in.mesh.triangle_count();
  std::vector<std::size_t> parent(n);
  std::iota(parent.begin(), parent.end(), std::size_t(0));
  std::function<std::size_t(std::size_t)> root = [&](std::size_t x) {
    while (parent[x] != x)
    {
      x = parent[x] = parent[parent[x]];
    }
    return x;
  };
  std::unordered_map<std::uint64_t, std::size_t> first_triangle;
  for (std::size_t t = 0; t < n; ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      const auto key = edge_key(in.mesh.triangles[3 * t + std::size_t(k)],
                                in.mesh.triangles[3 * t + std::size_t((k + 1) % 3)]);
      const auto found = first_triangle.emplace(key, t);
      if (!found.second)
      {
        parent[root(t)] = root(found.first->second);
      }
    }
  }
  Clipped out;
  std::vector<std::int64_t> new_index(in.distance.size(), -1);
  const std::size_t keep = root(std::size_t(keep_triangle));
  for (std::size_t t = 0; t < n; ++t)
  {
    if (root(t) != keep)
    {
      continue;
    }
    for (int k = 0; k < 3; ++k)
    {
      const std::int64_t v = in.mesh.triangles[3 * t + std::size_t(k)];
      if (new_index[std::size_t(v)] < 0)
      {
        new_index[std::size_t(v)] = std::int64_t(out.distance.size());
        const auto p = in.mesh.point(v);
        out.mesh.points.insert(out.mesh.points.end(), { p[0], p[1], p[2] });
        out.distance.push_back(in.distance[std::size_t(v)]);
        out.origin.push_back(in.origin[std::size_t(v)]);
      }
      out.mesh.triangles.push_back(new_index[std::size_t(v)]);
    }
    out.source_triangle.push_back(in.source_triangle[t]);
  }
  return out;
}

double loop_length(const TriangleMesh& mesh, const std::vector<std::int64_t>& loop)
{
  double length = 0;
  for (std::size_t i = 0; i < loop.size(); ++i)
  {
    const auto a = mesh.point(loop[i]);
    const auto b = mesh.point(loop[(i + 1) % loop.size()]);
    length += std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                        (a[2] - b[2]) * (a[2] - b[2]));
  }
  return length;
}

/// Closes the small boundary loops (shorter than a quarter of the longest one), left where the
/// front passed on both sides of a bump, with a fan around their centroid. Longer loops are a
/// sign that the disk wraps a handle and are left for the topology check to report.
std::size_t close_inner_holes(Clipped& disk)
{
  std::vector<std::vector<std::int64_t>> loops = boundary_loops(disk.mesh);
  if (loops.size() <= 1)
  {
    return 0;
  }
  std::size_t outer = 0;
  for (std::size_t i = 1; i < loops.size(); ++i)
  {
    if (loop_length(disk.mesh, loops[i]) > loop_length(disk.mesh, loops[outer]))
    {
      outer = i;
    }
  }
  const double outer_length = loop_length(disk.mesh, loops[outer]);
  std::size_t closed = 0;
  for (std::size_t i = 0; i < loops.size(); ++i)
  {
    if (i == outer || loop_length(disk.mesh, loops[i]) > 0.25 * outer_length)
    {
      continue;
    }
    std::array<double, 3> centre{ 0, 0, 0 };
    double distance = 0;
    for (const std::int64_t v : loops[i])
    {
      const auto p = disk.mesh.point(v);
      for (int d = 0; d < 3; ++d)
      {
        centre[std::size_t(d)] += p[std::size_t(d)] / double(loops[i].size());
      }
      distance += disk.distance[std::size_t(v)] / double(loops[i].size());
    }
    disk.mesh.points.insert(disk.mesh.points.end(), { centre[0], centre[1], centre[2] });
    disk.distance.push_back(distance);
    disk.origin.push_back(-1);
    const std::int64_t c = std::int64_t(disk.distance.size() - 1);
    for (std::size_t k = 0; k < loops[i].size(); ++k)
    {
      // The loop runs along the hole in the triangles' orientation; the fan goes the other way.
      disk.mesh.triangles.insert(disk.mesh.triangles.end(),
                                 { loops[i][(k + 1) % loops[i].size()], loops[i][k], c });
      disk.source_triangle.push_back(-1);
    }
    ++closed;
  }
  return closed;
}

/// Where the seed (inside mesh triangle `seed_triangle`) lies on the disk.
SurfacePoint locate_seed(const Clipped& disk, const SurfacePoint& seed)
{
  SurfacePoint best;
  double best_outside = std::numeric_limits<double>::max();
  for (std::size_t t = 0; t < disk.mesh.triangle_count(); ++t)
  {
    if (disk.source_triangle[t] != seed.triangle)
    {
      continue;
    }
    // Barycentric coordinates of the seed in this piece (same plane as the source triangle).
    const auto a = disk.mesh.point(disk.mesh.triangles[3 * t]);
    const auto b = disk.mesh.point(disk.mesh.triangles[3 * t + 1]);
    const auto c = disk.mesh.point(disk.mesh.triangles[3 * t + 2]);
    const std::array<double, 3> v0{ b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    const std::array<double, 3> v1{ c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    const std::array<double, 3> v2{ seed.position[0] - a[0], seed.position[1] - a[1],
                                    seed.position[2] - a[2] };
    auto dot = [](const std::array<double, 3>& x, const std::array<double, 3>& y) {
      return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
    };
    const double d00 = dot(v0, v0), d01 = dot(v0, v1), d11 = dot(v1, v1), d20 = dot(v2, v0),
                 d21 = dot(v2, v1);
    const double denominator = d00 * d11 - d01 * d01;
    if (denominator <= 0)
    {
      continue;
    }
    const double b1 = (d11 * d20 - d01 * d21) / denominator;
    const double b2 = (d00 * d21 - d01 * d20) / denominator;
    const double b0 = 1 - b1 - b2;
    const double outside = std::max({ 0.0, -b0, -b1, -b2 });
    if (outside < best_outside)
    {
      best_outside = outside;
      best.triangle = std::int64_t(t);
      best.barycentric = { b0, b1, b2 };
      best.position = seed.position;
    }
  }
  return best;
}

/// One attempt: the clipped disk on `solver`'s mesh, with its topology checked.
Clipped grow(const GeodesicSolver& solver, const SurfacePoint& seed, double radius,
             std::size_t& holes_closed)
{
  const TriangleMesh& mesh = solver.mesh();
  // Every vertex of a triangle crossing the isoline is within one edge of it.
  const GeodesicField field = solver.distances(seed, radius + solver.longest_edge());
  for (std::size_t i = 0; i < field.vertices.size() && field.distances[i] <= radius; ++i)
  {
    if (solver.on_boundary(field.vertices[i]))
    {
      throw TopologyError("the geodesic disk of radius " + format_length(radius) +
                          " reaches the mesh boundary at vertex " +
                          std::to_string(field.vertices[i]) + " (distance " +
                          format_length(field.distances[i]) +
                          "); pick a point farther from "
                          "the boundary or a smaller radius");
    }
  }
  const Clipped clipped = clip_below(mesh, field.dense(mesh.vertex_count()), radius);
  Clipped disk = clipped;
  const SurfacePoint seed_on_clip = locate_seed(clipped, seed);
  if (seed_on_clip.triangle < 0)
  {
    throw TopologyError("the seed's triangle was lost while cutting the geodesic disk");
  }
  disk = component_of(clipped, seed_on_clip.triangle);
  if (boundary_loops(disk.mesh).empty())
  {
    throw TopologyError("the geodesic disk of radius " + format_length(radius) +
                        " covers the whole closed surface component (its farthest point is " +
                        format_length(field.distances.back()) + " away); use a smaller radius");
  }
  holes_closed = close_inner_holes(disk);
  const MeshReport report = mesh_report(disk.mesh.view());
  if (!report.is_manifold())
  {
    throw TopologyError("the geodesic disk of radius " + format_length(radius) +
                        " is not a manifold: " + report.describe_defects());
  }
  if (report.euler_characteristic != 1 || report.boundary_loops != 1)
  {
    throw TopologyError("the geodesic disk of radius " + format_length(radius) +
                        " wraps a handle of the surface (Euler characteristic " +
                        std::to_string(report.euler_characteristic) + ", " +
                        std::to_string(report.boundary_loops) +
                        " boundary loops; a disk has 1 and 1); use a smaller radius");
  }
  return disk;
}

/// The triangles of `mesh` that come within `reach` of the seed (by geodesic distance), as a
/// separate mesh; `origin` maps its vertices to the input's origin ids.
TriangleMesh region_around(const GeodesicSolver& solver, const SurfacePoint& seed, double reach,
                           const std::vector<std::int64_t>& origin_in,
                           std::vector<std::int64_t>& origin_out)
{
  const TriangleMesh& mesh = solver.mesh();
  const std::vector<double> d =
    solver.distances(seed, reach + solver.longest_edge()).dense(mesh.vertex_count());
  TriangleMesh region;
  std::vector<std::int64_t> new_index(mesh.vertex_count(), -1);
  origin_out.clear();
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
  {
    const std::int64_t* v = &mesh.triangles[3 * t];
    if (std::min({ d[std::size_t(v[0])], d[std::size_t(v[1])], d[std::size_t(v[2])] }) > reach)
    {
      continue;
    }
    for (int k = 0; k < 3; ++k)
    {
      std::int64_t& id = new_index[std::size_t(v[k])];
      if (id < 0)
      {
        id = std::int64_t(origin_out.size());
        const auto p = mesh.point(v[k]);
        region.points.insert(region.points.end(), { p[0], p[1], p[2] });
        origin_out.push_back(origin_in[std::size_t(v[k])]);
      }
      region.triangles.push_back(id);
    }
  }
  return region;
}
} // namespace

GeodesicDisk geodesic_disk(const GeodesicSolver& solver, const SurfacePoint& seed,
                           const GeodesicDiskParams& params)
{
  if (!(params.radius > 0) || !std::isfinite(params.radius))
  {
    throw InvalidInput("the geodesic radius must be positive and finite, got " +
                       format_length(params.radius));
  }
  if (params.max_refinement_levels < 0 || params.max_refinement_levels > 8)
  {
    throw InvalidInput("max_refinement_levels must lie in [0, 8]");
  }
  const GeodesicSolver* current = &solver;
  std::unique_ptr<GeodesicSolver> refined;
  SurfacePoint current_seed = seed;
  std::vector<std::int64_t> origin(solver.mesh().vertex_count());
  std::iota(origin.begin(), origin.end(), std::int64_t(0));
  GeodesicDisk result;
  for (int level = 0;; ++level)
  {
    std::size_t holes = 0;
    Clipped disk = grow(*current, current_seed, params.radius, holes);
    const bool enough =
      params.min_triangles == 0 || disk.mesh.triangle_count() >= params.min_triangles;
    if (enough || level >= params.max_refinement_levels)
    {
      result.seed = locate_seed(disk, current_seed);
      result.mesh = std::move(disk.mesh);
      result.distance = std::move(disk.distance);
      result.original_vertex.resize(disk.origin.size());
      for (std::size_t v = 0; v < disk.origin.size(); ++v)
      {
        result.original_vertex[v] = disk.origin[v] < 0 ? -1 : origin[std::size_t(disk.origin[v])];
      }
      result.refinement_levels = level;
      result.holes_closed = holes;
      return result;
    }
    // Too coarse for a faithful parameterization: Loop-subdivide the surroundings, grow again.
    std::vector<std::int64_t> region_origin;
    TriangleMesh region = region_around(
      *current, current_seed, params.radius + 3 * current->longest_edge(), origin, region_origin);
    TriangleMesh finer = detail::loop_subdivide(region, region_origin);
    origin = std::move(region_origin);
    refined = std::make_unique<GeodesicSolver>(std::move(finer));
    current = refined.get();
    current_seed = current->closest_point(seed.position);
  }
}

} // namespace mesolens
