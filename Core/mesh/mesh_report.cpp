// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/mesh/mesh_report.h"

#include "common/detail/disjoint_sets.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <unordered_map>

namespace mesolens {

namespace {
using detail::DisjointSets;

/// One directed use of an undirected edge by a triangle.
struct EdgeUse
{
  std::int64_t low;
  std::int64_t high;
  std::size_t triangle;
  bool forward; // the triangle walks low -> high
};

double triangle_area(const double* p, const double* q, const double* r)
{
  const std::array<double, 3> u{ q[0] - p[0], q[1] - p[1], q[2] - p[2] };
  const std::array<double, 3> v{ r[0] - p[0], r[1] - p[1], r[2] - p[2] };
  const std::array<double, 3> c{ u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                                 u[0] * v[1] - u[1] * v[0] };
  return 0.5 * std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
}

bool finite_point(const double* p)
{
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

/// Per triangle, whether its indices lie in range and its corners are finite (the others are
/// counted, marked degenerate and left out of the topology); and the mean length of the valid
/// triangles' edges, the length scale of the relative area test.
struct ValidTriangles
{
  std::vector<bool> valid;
  double mean_edge = 0;
};

ValidTriangles check_indices(const TriangleMeshView& mesh, MeshReport& report)
{
  ValidTriangles result;
  std::vector<bool>& valid = result.valid;
  valid.assign(mesh.triangle_count, true);
  double edge_length_sum = 0;
  std::size_t edge_length_count = 0;
  for (std::size_t t = 0; t < mesh.triangle_count; ++t)
  {
    const std::int64_t* tri = mesh.triangles + 3 * t;
    for (int k = 0; k < 3; ++k)
    {
      if (tri[k] < 0 || std::size_t(tri[k]) >= mesh.points.size() ||
          !finite_point(mesh.points[tri[k]]))
      {
        valid[t] = false;
      }
    }
    if (!valid[t])
    {
      ++report.invalid_triangles;
      report.triangle_is_degenerate[t] = 1;
      continue;
    }
    for (int k = 0; k < 3; ++k)
    {
      const double* p = mesh.points[tri[k]];
      const double* q = mesh.points[tri[(k + 1) % 3]];
      edge_length_sum += std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                                   (p[2] - q[2]) * (p[2] - q[2]));
      ++edge_length_count;
    }
  }
  result.mean_edge = edge_length_count ? edge_length_sum / double(edge_length_count) : 0;
  return result;
}

/// What one pass over the valid triangles finds besides the degenerate ones (a repeated corner
/// or an area at most the threshold, counted and marked): the uses of their edges between
/// distinct corners, the vertices they use, and their number.
struct TriangleScan
{
  std::vector<EdgeUse> uses;
  std::vector<bool> referenced;
  std::size_t valid_triangles = 0;
};

TriangleScan scan_valid_triangles(const TriangleMeshView& mesh, const std::vector<bool>& valid,
                                  double area_threshold, MeshReport& report)
{
  TriangleScan scan;
  scan.uses.reserve(3 * mesh.triangle_count);
  scan.referenced.assign(mesh.points.size(), false);
  for (std::size_t t = 0; t < mesh.triangle_count; ++t)
  {
    if (!valid[t])
    {
      continue;
    }
    ++scan.valid_triangles;
    const std::int64_t* tri = mesh.triangles + 3 * t;
    const bool repeated = tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2];
    if (repeated ||
        triangle_area(mesh.points[tri[0]], mesh.points[tri[1]], mesh.points[tri[2]]) <=
          area_threshold)
    {
      ++report.degenerate_triangles;
      report.triangle_is_degenerate[t] = 1;
    }
    for (int k = 0; k < 3; ++k)
    {
      scan.referenced[std::size_t(tri[k])] = true;
      const std::int64_t a = tri[k];
      const std::int64_t b = tri[(k + 1) % 3];
      if (a != b)
      {
        scan.uses.push_back({ std::min(a, b), std::max(a, b), t, a < b });
      }
    }
  }
  return scan;
}

/// Sorts edge uses by edge (lower, then upper end) and then triangle, so that the uses of one
/// edge lie side by side: a counting sort by the lower end, then the few uses of each vertex by
/// (upper end, triangle).
void sort_edge_uses(std::vector<EdgeUse>& uses, std::size_t point_count)
{
  std::vector<std::size_t> start(point_count + 1, 0);
  for (const EdgeUse& use : uses)
  {
    ++start[std::size_t(use.low) + 1];
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<EdgeUse> sorted(uses.size());
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (const EdgeUse& use : uses)
  {
    sorted[fill[std::size_t(use.low)]++] = use;
  }
  for (std::size_t v = 0; v < point_count; ++v)
  {
    std::sort(sorted.begin() + long(start[v]), sorted.begin() + long(start[v + 1]),
              [](const EdgeUse& x, const EdgeUse& y) {
                return x.high != y.high ? x.high < y.high : x.triangle < y.triangle;
              });
  }
  uses = std::move(sorted);
}

/// What the edges join: triangles into components (across every edge), corners into fans
/// (across manifold edges; corner 3 t + k is vertex k of triangle t), and the boundary edges.
struct EdgeLinks
{
  DisjointSets triangles;
  DisjointSets corners;
  std::vector<std::pair<std::int64_t, std::int64_t>> boundary;
};

/// Counts the edges by how many triangles use them (boundary, manifold, non-manifold) and the
/// manifold ones used twice in one direction; joins the triangles and corners across them.
EdgeLinks link_across_edges(const TriangleMeshView& mesh, const std::vector<EdgeUse>& uses,
                            MeshReport& report)
{
  EdgeLinks links{ DisjointSets(mesh.triangle_count), DisjointSets(3 * mesh.triangle_count), {} };
  const auto corner = [&mesh](std::int64_t v, std::size_t t) {
    const std::int64_t* tri = mesh.triangles + 3 * t;
    return 3 * t + (tri[0] == v ? 0 : (tri[1] == v ? 1 : 2));
  };
  for (std::size_t i = 0; i < uses.size();)
  {
    std::size_t j = i;
    while (j < uses.size() && uses[j].low == uses[i].low && uses[j].high == uses[i].high)
    {
      ++j;
    }
    const std::size_t count = j - i;
    ++report.edges;
    if (count == 1)
    {
      ++report.boundary_edges;
      links.boundary.emplace_back(uses[i].low, uses[i].high);
    }
    else if (count == 2)
    {
      if (uses[i].forward == uses[i + 1].forward)
      {
        ++report.inconsistently_oriented_edges;
      }
      links.triangles.join(uses[i].triangle, uses[i + 1].triangle);
      links.corners.join(corner(uses[i].low, uses[i].triangle),
                         corner(uses[i].low, uses[i + 1].triangle));
      links.corners.join(corner(uses[i].high, uses[i].triangle),
                         corner(uses[i].high, uses[i + 1].triangle));
    }
    else
    {
      ++report.non_manifold_edges;
      report.vertex_is_non_manifold[std::size_t(uses[i].low)] = 1;
      report.vertex_is_non_manifold[std::size_t(uses[i].high)] = 1;
      for (std::size_t k = i + 1; k < j; ++k)
      {
        links.triangles.join(uses[i].triangle, uses[k].triangle);
      }
    }
    i = j;
  }
  return links;
}

/// Marks the vertices whose corners fall into more than one fan (two cones touching) as
/// non-manifold, and counts every non-manifold vertex.
void mark_pinched_vertices(const TriangleMeshView& mesh, const std::vector<bool>& valid,
                           DisjointSets& corners, MeshReport& report)
{
  std::vector<std::int64_t> fan_of_vertex(mesh.points.size(), -1);
  for (std::size_t t = 0; t < mesh.triangle_count; ++t)
  {
    if (!valid[t])
    {
      continue;
    }
    for (std::size_t k = 0; k < 3; ++k)
    {
      const auto v = std::size_t(mesh.triangles[3 * t + k]);
      const auto root = std::int64_t(corners.root(3 * t + k));
      if (fan_of_vertex[v] < 0)
      {
        fan_of_vertex[v] = root;
      }
      else if (fan_of_vertex[v] != root)
      {
        report.vertex_is_non_manifold[v] = 1;
      }
    }
  }
  report.non_manifold_vertices = std::size_t(std::count(
    report.vertex_is_non_manifold.begin(), report.vertex_is_non_manifold.end(), std::uint8_t(1)));
}

/// The closed boundary curves: connected components of the boundary edges' graph.
std::size_t boundary_loops(const std::vector<std::pair<std::int64_t, std::int64_t>>& boundary)
{
  std::unordered_map<std::int64_t, std::size_t> boundary_vertex;
  for (const auto& edge : boundary)
  {
    boundary_vertex.emplace(edge.first, boundary_vertex.size());
    boundary_vertex.emplace(edge.second, boundary_vertex.size());
  }
  DisjointSets boundary_sets(boundary_vertex.size());
  for (const auto& edge : boundary)
  {
    boundary_sets.join(boundary_vertex[edge.first], boundary_vertex[edge.second]);
  }
  std::size_t loops = 0;
  for (std::size_t v = 0; v < boundary_vertex.size(); ++v)
  {
    loops += boundary_sets.root(v) == v ? 1 : 0;
  }
  return loops;
}

/// The unreferenced vertices, the components, and the Euler characteristic (V - E + F over the
/// vertices the valid triangles use and those triangles).
void count_components(const TriangleMeshView& mesh, const std::vector<bool>& valid,
                      const TriangleScan& scan, DisjointSets& triangles, MeshReport& report)
{
  std::size_t referenced_count = 0;
  for (std::size_t v = 0; v < mesh.points.size(); ++v)
  {
    referenced_count += scan.referenced[v] ? 1 : 0;
  }
  report.unreferenced_vertices = mesh.points.size() - referenced_count;
  for (std::size_t t = 0; t < mesh.triangle_count; ++t)
  {
    report.components += (valid[t] && triangles.root(t) == t) ? 1 : 0;
  }
  report.euler_characteristic =
    long(referenced_count) - long(report.edges) + long(scan.valid_triangles);
}
} // namespace

bool MeshReport::is_manifold() const
{
  return this->triangles > 0 && this->non_manifold_edges == 0 && this->non_manifold_vertices == 0 &&
    this->degenerate_triangles == 0 && this->invalid_triangles == 0;
}

bool MeshReport::is_closed_manifold() const
{
  return this->is_manifold() && this->boundary_edges == 0 &&
    this->inconsistently_oriented_edges == 0;
}

std::string MeshReport::describe_defects() const
{
  std::ostringstream text;
  auto line = [&text](std::size_t count, const char* what) {
    if (count > 0)
    {
      text << count << ' ' << what << '\n';
    }
  };
  if (this->triangles == 0)
  {
    text << "no triangles\n";
  }
  line(this->invalid_triangles, "invalid triangles (index out of range or non-finite vertex)");
  line(this->degenerate_triangles, "degenerate (zero-area or repeated-vertex) triangles");
  line(this->non_manifold_edges, "non-manifold edges (shared by more than two triangles)");
  line(this->non_manifold_vertices, "non-manifold vertices");
  line(this->inconsistently_oriented_edges, "inconsistently oriented edges");
  if (this->boundary_edges > 0)
  {
    text << this->boundary_edges << " boundary edges in " << this->boundary_loops << " loops\n";
  }
  line(this->unreferenced_vertices, "unreferenced vertices");
  if (this->components > 1)
  {
    text << this->components << " separate components\n";
  }
  return text.str();
}

MeshReport mesh_report(const TriangleMeshView& mesh, double area_epsilon)
{
  MeshReport report;
  report.vertices = mesh.points.size();
  report.triangles = mesh.triangle_count;
  report.triangle_is_degenerate.assign(mesh.triangle_count, 0);
  report.vertex_is_non_manifold.assign(mesh.points.size(), 0);
  const ValidTriangles checked = check_indices(mesh, report);
  TriangleScan scan = scan_valid_triangles(
    mesh, checked.valid, area_epsilon * checked.mean_edge * checked.mean_edge, report);
  sort_edge_uses(scan.uses, mesh.points.size());
  EdgeLinks links = link_across_edges(mesh, scan.uses, report);
  mark_pinched_vertices(mesh, checked.valid, links.corners, report);
  report.boundary_loops = boundary_loops(links.boundary);
  count_components(mesh, checked.valid, scan, links.triangles, report);
  return report;
}

} // namespace mesolens
