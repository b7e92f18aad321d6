// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/mapping/cell_surface.h"

#include "mesolens/common/errors.h"
#include "mesolens/mesh/surface_locator.h"
#include "mapping/detail/edge_key.h"
#include "mapping/detail/surface_levels.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace mesolens {

MeshAdjacency mesh_adjacency(const TriangleMesh& mesh)
{
  const std::size_t triangles = mesh.triangle_count();
  MeshAdjacency adjacency;
  adjacency.across.assign(3 * triangles, -1);
  // Directed edges sorted by their undirected key pair up the two triangles of each edge.
  struct Side
  {
    std::uint64_t key;
    std::int64_t slot; // 3 * triangle + corner
  };
  std::vector<Side> sides(3 * triangles);
  for (std::size_t t = 0; t < triangles; ++t)
  {
    for (std::size_t k = 0; k < 3; ++k)
    {
      sides[3 * t + k] = { detail::edge_key(mesh.triangles[3 * t + k],
                                            mesh.triangles[3 * t + (k + 1) % 3]),
                           std::int64_t(3 * t + k) };
    }
  }
  std::sort(sides.begin(), sides.end(), [](const Side& x, const Side& y) {
    return x.key != y.key ? x.key < y.key : x.slot < y.slot;
  });
  for (std::size_t i = 0; i + 1 < sides.size(); ++i)
  {
    if (sides[i].key == sides[i + 1].key)
    {
      adjacency.across[std::size_t(sides[i].slot)] = sides[i + 1].slot / 3;
      adjacency.across[std::size_t(sides[i + 1].slot)] = sides[i].slot / 3;
      ++i;
    }
  }
  const std::size_t vertices = mesh.vertex_count();
  adjacency.vertex_start.assign(vertices + 1, 0);
  for (const std::int64_t v : mesh.triangles)
  {
    ++adjacency.vertex_start[std::size_t(v) + 1];
  }
  std::partial_sum(adjacency.vertex_start.begin(), adjacency.vertex_start.end(),
                   adjacency.vertex_start.begin());
  adjacency.vertex_triangles.resize(mesh.triangles.size());
  std::vector<std::size_t> fill(adjacency.vertex_start.begin(), adjacency.vertex_start.end() - 1);
  for (std::size_t t = 0; t < triangles; ++t)
  {
    for (std::size_t k = 0; k < 3; ++k)
    {
      adjacency.vertex_triangles[fill[std::size_t(mesh.triangles[3 * t + k])]++] = std::int64_t(t);
    }
  }
  return adjacency;
}

struct CellSurface::Impl
{
  std::vector<std::unique_ptr<detail::SurfaceLevel>> Levels; // [0]: the input
  double Diagonal = 0;
};

CellSurface::CellSurface(TriangleMesh mesh)
  : Internal(std::make_unique<Impl>())
{
  require_manifold(mesh, "the surface mesh");
  Impl& impl = *this->Internal;
  std::array<double, 3> low{ mesh.points[0], mesh.points[1], mesh.points[2] };
  std::array<double, 3> high = low;
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
  {
    low[i % 3] = std::min(low[i % 3], mesh.points[i]);
    high[i % 3] = std::max(high[i % 3], mesh.points[i]);
  }
  impl.Diagonal =
    std::sqrt((high[0] - low[0]) * (high[0] - low[0]) + (high[1] - low[1]) * (high[1] - low[1]) +
              (high[2] - low[2]) * (high[2] - low[2]));
  auto input = std::make_unique<detail::SurfaceLevel>();
  input->adjacency = mesh_adjacency(mesh);
  input->input_vertex.resize(mesh.vertex_count());
  std::iota(input->input_vertex.begin(), input->input_vertex.end(), std::int64_t(0));
  input->anchor_triangle.resize(mesh.vertex_count());
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
  {
    // A vertex no triangle uses (a mesh may have some) has none: -1.
    const std::size_t first = std::size_t(input->adjacency.vertex_start[v]);
    input->anchor_triangle[v] = first < std::size_t(input->adjacency.vertex_start[v + 1])
      ? input->adjacency.vertex_triangles[first]
      : -1;
  }
  input->smooth = std::make_shared<const SmoothSurface>(std::move(mesh));
  input->measure();
  impl.Levels.push_back(std::move(input));
  if (this->mesh().triangle_count() > coarse_copies_above)
  {
    // Copies down to a few thousand vertices: every disk then has a copy within reach.
    for (auto& level : detail::coarser_levels(*impl.Levels.front(), coarse_copies_above / 8))
    {
      impl.Levels.push_back(std::move(level));
    }
  }
}

std::size_t CellSurface::level_count() const
{
  return this->Internal->Levels.size();
}

const detail::SurfaceLevel& CellSurface::level(std::size_t index) const
{
  return *this->Internal->Levels.at(index);
}

CellSurface::~CellSurface() = default;

const TriangleMesh& CellSurface::mesh() const
{
  return this->smooth().mesh();
}

const SmoothSurface& CellSurface::smooth() const
{
  return *this->Internal->Levels.front()->smooth;
}

const MeshAdjacency& CellSurface::adjacency() const
{
  return this->Internal->Levels.front()->adjacency;
}

double CellSurface::bounding_diagonal() const
{
  return this->Internal->Diagonal;
}

SurfacePoint CellSurface::closest_point(const std::array<double, 3>& point, double* distance) const
{
  return this->Internal->Levels.front()->locator().closest_point(point, distance);
}

} // namespace mesolens
