// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/mapping/geodesic_disk.h"

#include "mesolens/common/errors.h"
#include "common/detail/disjoint_sets.h"
#include "mapping/detail/edge_key.h"
#include "mapping/detail/local_surface.h"
#include "mapping/detail/surface_levels.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <unordered_map>

namespace mesolens {

namespace {
using detail::edge_key;

std::string format_length(double value)
{
  std::ostringstream text;
  text << value;
  return text.str();
}

/// The part of a local surface the disk takes (`taken` vertices: within the radius or enclosed),
/// cut along the isoline; each triangle keeps the local triangle it comes from and its place in
/// the input triangle.
struct Clipped
{
  TriangleMesh mesh;
  std::vector<double> distance;
  std::vector<double> normals;            // 3 per vertex
  std::vector<std::int64_t> origin;       // per vertex: input vertex or -1
  std::vector<std::int64_t> parent;       // per triangle: local triangle
  std::vector<std::int64_t> source;       // per triangle: input triangle
  std::vector<double> source_barycentric; // 9 per triangle

  std::int64_t add_vertex(const std::array<double, 3>& p, const std::array<double, 3>& n, double d,
                          std::int64_t from)
  {
    this->mesh.points.insert(this->mesh.points.end(), p.begin(), p.end());
    this->normals.insert(this->normals.end(), n.begin(), n.end());
    this->distance.push_back(d);
    this->origin.push_back(from);
    return std::int64_t(this->distance.size() - 1);
  }
  std::array<double, 3> normal(std::int64_t v) const
  {
    const auto i = std::size_t(3 * v);
    return { this->normals[i], this->normals[i + 1], this->normals[i + 2] };
  }
};

Clipped clip_below(const detail::LocalSurface& local, const std::vector<double>& distance,
                   const std::vector<std::uint8_t>& taken, double radius)
{
  const TriangleMesh& mesh = local.mesh;
  Clipped out;
  std::unordered_map<std::int64_t, std::int64_t> vertex_of;
  std::unordered_map<std::uint64_t, std::int64_t> cut_of;
  auto normal_of = [&local](std::int64_t v) {
    const auto i = std::size_t(3 * v);
    return std::array<double, 3>{ local.normals[i], local.normals[i + 1], local.normals[i + 2] };
  };
  auto inside_vertex = [&](std::int64_t v) {
    const auto found = vertex_of.find(v);
    if (found != vertex_of.end())
    {
      return found->second;
    }
    return vertex_of[v] = out.add_vertex(mesh.point(v), normal_of(v), distance[std::size_t(v)],
                                         local.original_vertex[std::size_t(v)]);
  };
  // Where the isoline crosses edge (inside, outside), from the inside end; 0: at that end.
  auto fraction = [&](std::int64_t inside, std::int64_t outside) {
    const double t = (radius - distance[std::size_t(inside)]) /
      (distance[std::size_t(outside)] - distance[std::size_t(inside)]);
    return t < 1e-6 ? 0.0 : t;
  };
  auto cut = [&](std::int64_t inside, std::int64_t outside, double t) {
    if (t == 0)
    {
      return inside_vertex(inside);
    }
    const std::uint64_t key = edge_key(inside, outside);
    const auto found = cut_of.find(key);
    if (found != cut_of.end())
    {
      return found->second;
    }
    const auto a = mesh.point(inside), b = mesh.point(outside);
    const auto na = normal_of(inside), nb = normal_of(outside);
    std::array<double, 3> p{}, n{};
    for (std::size_t d = 0; d < 3; ++d)
    {
      p[d] = a[d] + t * (b[d] - a[d]);
      n[d] = na[d] + t * (nb[d] - na[d]);
    }
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (double& c : n)
    {
      c /= length > 0 ? length : 1.0;
    }
    return cut_of[key] = out.add_vertex(p, n, radius, -1);
  };
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
  {
    const std::int64_t v[3] = { mesh.triangles[3 * t], mesh.triangles[3 * t + 1],
                                mesh.triangles[3 * t + 2] };
    const bool in[3] = { taken[std::size_t(v[0])] != 0, taken[std::size_t(v[1])] != 0,
                         taken[std::size_t(v[2])] != 0 };
    if (!in[0] && !in[1] && !in[2])
    {
      continue;
    }
    const double* corner_bary = &local.source_barycentric[9 * t];
    std::vector<std::pair<std::int64_t, std::array<double, 3>>> polygon;
    auto push = [&polygon](std::int64_t id, const std::array<double, 3>& bary) {
      if (polygon.empty() || polygon.back().first != id)
      {
        polygon.emplace_back(id, bary);
      }
    };
    for (int k = 0; k < 3; ++k)
    {
      const int next = (k + 1) % 3;
      if (in[k])
      {
        const double* bk = corner_bary + 3 * k;
        push(inside_vertex(v[k]), { bk[0], bk[1], bk[2] });
      }
      if (in[k] != in[next])
      {
        const int inside = in[k] ? k : next;
        const int outside = in[k] ? next : k;
        const double f = fraction(v[inside], v[outside]);
        const double* bi = corner_bary + 3 * inside;
        const double* bo = corner_bary + 3 * outside;
        push(cut(v[inside], v[outside], f),
             { bi[0] + f * (bo[0] - bi[0]), bi[1] + f * (bo[1] - bi[1]),
               bi[2] + f * (bo[2] - bi[2]) });
      }
    }
    if (polygon.size() > 1 && polygon.front().first == polygon.back().first)
    {
      polygon.pop_back();
    }
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
    {
      for (const std::size_t corner : { std::size_t(0), k, k + 1 })
      {
        out.mesh.triangles.push_back(polygon[corner].first);
        out.source_barycentric.insert(out.source_barycentric.end(), polygon[corner].second.begin(),
                                      polygon[corner].second.end());
      }
      out.parent.push_back(std::int64_t(t));
      out.source.push_back(local.source_triangle[t]);
    }
  }
  return out;
}

/// Keeps the edge-connected component of `keep_triangle`; drops unused vertices.
Clipped component_of(const Clipped& in, std::int64_t keep_triangle)
{
  const std::size_t n = in.mesh.triangle_count();
  detail::DisjointSets components(n);
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
        components.join(t, found.first->second);
      }
    }
  }
  Clipped out;
  std::vector<std::int64_t> new_index(in.distance.size(), -1);
  const std::size_t keep = components.root(std::size_t(keep_triangle));
  for (std::size_t t = 0; t < n; ++t)
  {
    if (components.root(t) != keep)
    {
      continue;
    }
    for (int k = 0; k < 3; ++k)
    {
      const std::int64_t v = in.mesh.triangles[3 * t + std::size_t(k)];
      if (new_index[std::size_t(v)] < 0)
      {
        new_index[std::size_t(v)] = out.add_vertex(
          in.mesh.point(v), in.normal(v), in.distance[std::size_t(v)], in.origin[std::size_t(v)]);
      }
      out.mesh.triangles.push_back(new_index[std::size_t(v)]);
    }
    out.parent.push_back(in.parent[t]);
    out.source.push_back(in.source[t]);
    out.source_barycentric.insert(out.source_barycentric.end(),
                                  in.source_barycentric.begin() + long(9 * t),
                                  in.source_barycentric.begin() + long(9 * t + 9));
  }
  return out;
}

/// Which vertices the disk takes: those within the radius, and those of every region farther
/// away that the disk encloses (the top of a bump the front went round; its own triangles, not a
/// patch over it). A region farther away that reaches the local surface's border or the
/// march's end lies outside; without such a region, the largest lies outside. Returns how many
/// regions were enclosed.
std::size_t disk_vertices(const detail::LocalSurface& local, const GeodesicSolver& solver,
                          const std::vector<double>& distance, double radius,
                          std::vector<std::uint8_t>& inside)
{
  const std::size_t n = distance.size();
  inside.assign(n, 0);
  detail::DisjointSets farther(n);
  for (std::size_t v = 0; v < n; ++v)
  {
    inside[v] = distance[v] <= radius;
  }
  const TriangleMesh& mesh = local.mesh;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
  {
    for (std::size_t k = 0; k < 3; ++k)
    {
      const auto a = std::size_t(mesh.triangles[3 * t + k]);
      const auto b = std::size_t(mesh.triangles[3 * t + (k + 1) % 3]);
      if (!inside[a] && !inside[b])
      {
        farther.join(a, b);
      }
    }
  }
  // Per region farther away (by root): its size and whether it reaches out.
  std::vector<std::size_t> size(n, 0);
  std::vector<std::uint8_t> reaches_out(n, 0);
  for (std::size_t v = 0; v < n; ++v)
  {
    if (!inside[v])
    {
      const std::size_t r = farther.root(v);
      ++size[r];
      reaches_out[r] |= !std::isfinite(distance[v]) || solver.on_boundary(std::uint32_t(v));
    }
  }
  bool any_out = false;
  std::size_t largest = n;
  for (std::size_t v = 0; v < n; ++v)
  {
    any_out = any_out || (size[v] > 0 && reaches_out[v]);
    if (size[v] > 0 && (largest == n || size[v] > size[largest]))
    {
      largest = v;
    }
  }
  std::vector<std::uint8_t> enclosed(n, 0);
  std::size_t regions = 0;
  for (std::size_t v = 0; v < n; ++v)
  {
    if (size[v] > 0 && !(any_out ? reaches_out[v] : v == largest))
    {
      enclosed[v] = 1;
      ++regions;
    }
  }
  for (std::size_t v = 0; v < n; ++v)
  {
    inside[v] = inside[v] || enclosed[farther.root(v)];
  }
  return regions;
}

/// Where the seed (a point of local triangle seed.triangle) lies on the disk.
SurfacePoint locate_seed(const Clipped& disk, const SurfacePoint& seed)
{
  SurfacePoint best;
  double best_outside = std::numeric_limits<double>::max();
  for (std::size_t t = 0; t < disk.mesh.triangle_count(); ++t)
  {
    if (disk.parent[t] != seed.triangle)
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

/// The clipped disk on the local surface, with its topology checked.
Clipped grow(const detail::LocalSurface& local, double radius, std::size_t& holes_closed)
{
  const GeodesicSolver solver(local.mesh);
  // Every vertex of a triangle crossing the isoline is within one edge of it.
  const GeodesicField field = solver.distances(local.seed, radius + solver.longest_edge());
  for (std::size_t i = 0; i < field.vertices.size() && field.distances[i] <= radius; ++i)
  {
    // The local surface's own border lies beyond the radius, so this is the input's boundary.
    if (solver.on_boundary(field.vertices[i]))
    {
      const std::int64_t original = local.original_vertex[field.vertices[i]];
      throw TopologyError(
        "the geodesic disk of radius " + format_length(radius) + " reaches the mesh boundary" +
        (original >= 0 ? " at vertex " + std::to_string(original) : std::string()) + " (distance " +
        format_length(field.distances[i]) +
        "); pick a point farther from the boundary or a smaller radius");
    }
  }
  const std::vector<double> distance = field.dense(local.mesh.vertex_count());
  std::vector<std::uint8_t> taken;
  holes_closed = disk_vertices(local, solver, distance, radius, taken);
  const Clipped clipped = clip_below(local, distance, taken, radius);
  const SurfacePoint seed_on_clip = locate_seed(clipped, local.seed);
  if (seed_on_clip.triangle < 0)
  {
    throw TopologyError("the geodesic disk of radius " + format_length(radius) +
                        " lost the seed's triangle while it was cut (the surface around the "
                        "seed is degenerate)");
  }
  Clipped disk = component_of(clipped, seed_on_clip.triangle);
  if (boundary_loops(disk.mesh).empty())
  {
    throw TopologyError("the geodesic disk of radius " + format_length(radius) +
                        " covers the whole closed surface component (its farthest point is " +
                        format_length(field.distances.back()) + " away); use a smaller radius");
  }
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
} // namespace

GeodesicDisk geodesic_disk(const CellSurface& surface, const SurfacePoint& seed,
                           const GeodesicDiskParams& params)
{
  if (!(params.radius > 0) || !std::isfinite(params.radius))
  {
    throw InvalidInput("the geodesic radius must be positive and finite, got " +
                       format_length(params.radius));
  }
  // Bisecting towards a radius a billionth of the coordinates' size runs out of digits (a
  // radius of 1e-73 on a mesh of 3e-3 bisected without end).
  const double scale = std::max({ surface.bounding_diagonal(), std::abs(seed.position[0]),
                                  std::abs(seed.position[1]), std::abs(seed.position[2]) });
  if (params.radius < smallest_relative_disk_radius * scale)
  {
    throw InvalidInput("the geodesic radius " + format_length(params.radius) + " is below " +
                       format_length(smallest_relative_disk_radius) + " times the mesh's size (" +
                       format_length(scale) +
                       ", its bounding diagonal or the seed's distance from the origin)");
  }
  detail::LocalSurfaceParams local_params;
  // Straight-line distance never exceeds the geodesic one; the margin covers the march's error.
  local_params.reach = 1.02 * params.radius;
  if (params.min_triangles > 0)
  {
    constexpr double pi = 3.14159265358979323846;
    // Longest-edge bisection leaves triangles of h^2 / 8 to h^2 / 4 (h their longest edge), so
    // this edge gives n to 2 n triangles in a flat disk.
    local_params.target_edge = params.radius * std::sqrt(4 * pi / double(params.min_triangles));
    // A disk of n triangles refines its surroundings a few times n; a hundred times n (at
    // least 2e5) means the mesh is too coarse and curved for the radius, better said at once
    // than after seconds of bisection.
    local_params.max_new_triangles = std::max<std::size_t>(200000, 100 * params.min_triangles);
  }
  // The finest copy of the surface with few enough triangles within reach: predicted from the
  // copies' mean triangle areas, then counted while the local surface is gathered (a coarser
  // copy if too many; the coarsest takes any number).
  std::size_t level = 0;
  if (params.max_triangles > 0 && surface.level_count() > 1)
  {
    constexpr double pi = 3.14159265358979323846;
    const double area = pi * local_params.reach * local_params.reach;
    while (level + 1 < surface.level_count() &&
           area / surface.level(level).mean_triangle_area > 0.5 * double(params.max_triangles))
    {
      ++level;
    }
  }
  detail::LocalSurface local;
  for (;; ++level)
  {
    const SurfacePoint level_seed =
      level == 0 ? seed : surface.level(level).closest_point(seed.position);
    local_params.max_region = level + 1 < surface.level_count() ? params.max_triangles : 0;
    local = detail::local_surface(surface.level(level), level_seed, local_params);
    if (!local.region_too_large)
    {
      break;
    }
  }
  const detail::SurfaceLevel& copy = surface.level(level);
  if (local.seed.triangle < 0)
  {
    throw InvalidInput("the seed does not lie on the surface around it");
  }
  std::size_t holes = 0;
  Clipped disk = grow(local, params.radius, holes);
  GeodesicDisk result;
  result.seed = locate_seed(disk, local.seed);
  result.mesh = std::move(disk.mesh);
  result.distance = std::move(disk.distance);
  result.normals = std::move(disk.normals);
  // The disk's vertex origins are vertices of the copy it was grown on.
  result.original_vertex.resize(disk.origin.size(), -1);
  result.nearby_triangle.resize(disk.origin.size(), -1);
  for (std::size_t i = 0; i < disk.origin.size(); ++i)
  {
    const std::int64_t v = disk.origin[i];
    if (v >= 0)
    {
      result.original_vertex[i] = copy.input_vertex[std::size_t(v)];
      result.nearby_triangle[i] = copy.anchor_triangle[std::size_t(v)];
    }
  }
  result.source_triangle = std::move(disk.source);
  result.surface_level = level;
  result.source_barycentric = std::move(disk.source_barycentric);
  result.refinement_levels = local.bisection_depth;
  result.holes_closed = holes;
  return result;
}

SurfacePlacement smooth_placement(const GeodesicDisk& disk, const CellSurface& surface)
{
  struct Sources
  {
    std::vector<std::int64_t> triangle;
    std::vector<double> barycentric;
    std::vector<std::int64_t> corners;         // the disk's triangles
    std::vector<std::int64_t> nearby_triangle; // per disk vertex
    std::size_t level = 0;
  };
  Sources copy{ disk.source_triangle, disk.source_barycentric, disk.mesh.triangles,
                disk.nearby_triangle, disk.surface_level };
  if (disk.surface_level > 0)
  {
    // Each vertex's own closest input triangle: lookups then start a step or two away.
    for (std::size_t v = 0; v < copy.nearby_triangle.size(); ++v)
    {
      if (copy.nearby_triangle[v] >= 0)
      {
        const SurfacePoint found =
          detail::walk_to_closest(surface.mesh(), surface.adjacency(), copy.nearby_triangle[v],
                                  disk.mesh.point(std::int64_t(v)));
        copy.nearby_triangle[v] = found.triangle >= 0 ? found.triangle : copy.nearby_triangle[v];
      }
    }
  }
  auto sources = std::make_shared<const Sources>(std::move(copy));
  const CellSurface* cell = &surface;
  return [sources, cell](std::int64_t triangle, const std::array<double, 3>& barycentric,
                         SurfaceFrame& frame) {
    const auto t = std::size_t(triangle);
    const std::int64_t source = sources->triangle[t];
    std::array<double, 3> in_source{ 0, 0, 0 };
    const double* corners = &sources->barycentric[9 * t];
    for (std::size_t k = 0; k < 3; ++k)
    {
      for (std::size_t d = 0; d < 3; ++d)
      {
        in_source[d] += barycentric[k] * corners[3 * k + d];
      }
    }
    if (sources->level == 0)
    {
      const SmoothPoint point = cell->smooth().evaluate(source, in_source);
      frame.position = point.position;
      frame.normal = point.normal;
      return;
    }
    // Grown on a coarser copy: its smooth point, then the input's point along the copy's normal
    // from it, found by walking the input from the corner nearest in the disk.
    const SmoothPoint coarse = cell->level(sources->level).smooth->evaluate(source, in_source);
    const std::array<double, 3>& near = coarse.position;
    std::int64_t start = -1;
    double weight = -1;
    for (std::size_t k = 0; k < 3; ++k)
    {
      const std::int64_t near_corner =
        sources->nearby_triangle[std::size_t(sources->corners[3 * t + k])];
      if (near_corner >= 0 && barycentric[k] > weight)
      {
        weight = barycentric[k];
        start = near_corner;
      }
    }
    // Along the copy's normal onto the input: continuous, unlike the closest point.
    SurfacePoint on_input;
    if (start >= 0)
    {
      on_input =
        detail::walk_along_line(cell->mesh(), cell->adjacency(), start, near, coarse.normal);
    }
    if (on_input.triangle < 0 && start >= 0)
    {
      on_input = detail::walk_to_closest(cell->mesh(), cell->adjacency(), start, near);
    }
    if (on_input.triangle < 0)
    {
      on_input = cell->closest_point(near);
    }
    const SmoothPoint point = cell->smooth().evaluate(on_input.triangle, on_input.barycentric);
    frame.position = point.position;
    frame.normal = point.normal;
  };
}

} // namespace mesolens
