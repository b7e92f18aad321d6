// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/mesh/triangle_mesh.h"

#include "mesolens/common/errors.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>

namespace mesolens {

TriangleMeshView TriangleMesh::view() const
{
  TriangleMeshView view;
  view.points = this->points;
  view.triangles = this->triangles.data();
  view.triangle_count = this->triangle_count();
  return view;
}

void require_manifold(const TriangleMesh& mesh, const char* what)
{
  if (mesh.triangle_count() == 0)
  {
    throw InvalidInput(std::string(what) + " has no triangles");
  }
  for (const double value : mesh.points)
  {
    if (!std::isfinite(value))
    {
      throw InvalidInput(std::string(what) + " has a non-finite vertex coordinate");
    }
  }
  const MeshReport report = mesh_report(mesh.view());
  if (!report.is_manifold() || report.inconsistently_oriented_edges > 0)
  {
    throw TopologyError(std::string(what) +
                        " is not a clean 2-manifold: " + report.describe_defects());
  }
}

std::vector<std::vector<std::int64_t>> boundary_loops(const TriangleMesh& mesh)
{
  // Directed edges; an edge whose reverse is absent lies on the boundary.
  std::vector<std::pair<std::int64_t, std::int64_t>> directed;
  directed.reserve(mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
  {
    for (std::size_t k = 0; k < 3; ++k)
    {
      directed.emplace_back(mesh.triangles[3 * t + k], mesh.triangles[3 * t + (k + 1) % 3]);
    }
  }
  std::sort(directed.begin(), directed.end());
  std::map<std::int64_t, std::int64_t> next; // ordered: loops start at their smallest vertex
  for (const auto& [a, b] : directed)
  {
    if (!std::binary_search(directed.begin(), directed.end(), std::make_pair(b, a)))
    {
      next[a] = b;
    }
  }
  std::vector<std::vector<std::int64_t>> loops;
  std::set<std::int64_t> visited;
  for (const auto& entry : next)
  {
    if (visited.count(entry.first))
    {
      continue;
    }
    std::vector<std::int64_t> loop;
    for (std::int64_t v = entry.first; !visited.count(v);)
    {
      visited.insert(v);
      loop.push_back(v);
      const auto found = next.find(v);
      if (found == next.end())
      {
        break;
      }
      v = found->second;
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

std::array<double, 3> triangle_normal(const TriangleMesh& mesh, std::int64_t triangle)
{
  const std::size_t t = 3 * static_cast<std::size_t>(triangle);
  const auto a = mesh.point(mesh.triangles[t]);
  const auto b = mesh.point(mesh.triangles[t + 1]);
  const auto c = mesh.point(mesh.triangles[t + 2]);
  const std::array<double, 3> u{ b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const std::array<double, 3> v{ c[0] - a[0], c[1] - a[1], c[2] - a[2] };
  std::array<double, 3> n{ u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                           u[0] * v[1] - u[1] * v[0] };
  const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (length > 0)
  {
    for (double& x : n)
    {
      x /= length;
    }
  }
  return n;
}

std::vector<double> vertex_normals(const TriangleMesh& mesh)
{
  std::vector<double> normals(mesh.points.size(), 0.0);
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
  {
    const auto a = mesh.point(mesh.triangles[3 * t]);
    const auto b = mesh.point(mesh.triangles[3 * t + 1]);
    const auto c = mesh.point(mesh.triangles[3 * t + 2]);
    const std::array<double, 3> u{ b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    const std::array<double, 3> v{ c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    // The cross product is twice the area times the normal: area weighting for free.
    const std::array<double, 3> n{ u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                                   u[0] * v[1] - u[1] * v[0] };
    for (int k = 0; k < 3; ++k)
    {
      const std::size_t vertex = static_cast<std::size_t>(mesh.triangles[3 * t + std::size_t(k)]);
      for (int d = 0; d < 3; ++d)
      {
        normals[3 * vertex + std::size_t(d)] += n[std::size_t(d)];
      }
    }
  }
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
  {
    const double length =
      std::sqrt(normals[3 * v] * normals[3 * v] + normals[3 * v + 1] * normals[3 * v + 1] +
                normals[3 * v + 2] * normals[3 * v + 2]);
    if (length > 0)
    {
      for (int d = 0; d < 3; ++d)
      {
        normals[3 * v + std::size_t(d)] /= length;
      }
    }
  }
  return normals;
}

} // namespace mesolens
