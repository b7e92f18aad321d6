// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: the membrane mapping's surface chain on arbitrary triangle meshes: the cell
// surface (mesolens::CellSurface), the geodesic disk around a picked point
// (mesolens::geodesic_disk) and its parameterization (mesolens::harmonic_parameterization).
// Meshes start as a height-field grid (a disk), a UV sphere or a torus (genus 1) of a size the
// input picks, then the input moves vertices onto others or by a hair, throws them far away,
// flips, drops or repeats triangles and bends indices. Every input must give a disk that is a
// topological disk with a finite parameterization, or a mesolens::Error.
#include "fuzz_input.h"

#include "mesolens/common/errors.h"
#include "mesolens/mapping/cell_surface.h"
#include "mesolens/mapping/geodesic_disk.h"
#include "mesolens/mapping/harmonic_parameterization.h"
#include "mesolens/mesh/mesh_report.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>

namespace {

using mesolens_fuzz::require;

void add_quad(mesolens::TriangleMesh& mesh, std::int64_t a, std::int64_t b, std::int64_t c,
              std::int64_t d)
{
  mesh.triangles.insert(mesh.triangles.end(), { a, b, c, a, c, d });
}

mesolens::TriangleMesh base_mesh(mesolens_fuzz::FuzzInput& input)
{
  const std::uint8_t shape = input.byte();
  const int n = 3 + input.byte() % 10, m = 3 + input.byte() % 10;
  mesolens::TriangleMesh mesh;
  const auto index = [m](int i, int j) { return std::int64_t(i) * m + j; };
  switch (shape % 3)
  {
    case 0: // a grid, lifted by a smooth bump
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < m; ++j)
          mesh.points.insert(mesh.points.end(),
                             { double(i), double(j), std::sin(0.5 * i) * std::cos(0.4 * j) });
      for (int i = 0; i + 1 < n; ++i)
        for (int j = 0; j + 1 < m; ++j)
          add_quad(mesh, index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1));
      break;
    case 1: // a torus of n x m quads
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < m; ++j)
        {
          const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / m;
          mesh.points.insert(
            mesh.points.end(),
            { (3 + std::cos(v)) * std::cos(u), (3 + std::cos(v)) * std::sin(u), std::sin(v) });
        }
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < m; ++j)
          add_quad(mesh, index(i, j), index((i + 1) % n, j), index((i + 1) % n, (j + 1) % m),
                   index(i, (j + 1) % m));
      break;
    default: // a UV sphere: n rings of m vertices between two poles
    {
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < m; ++j)
        {
          const double theta = M_PI * (i + 1) / (n + 1), phi = 2 * M_PI * j / m;
          mesh.points.insert(
            mesh.points.end(),
            { std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta) });
        }
      const std::int64_t north = n * m, south = north + 1;
      mesh.points.insert(mesh.points.end(), { 0, 0, 1, 0, 0, -1 });
      for (int j = 0; j < m; ++j)
      {
        const int next = (j + 1) % m;
        mesh.triangles.insert(mesh.triangles.end(), { north, index(0, j), index(0, next) });
        mesh.triangles.insert(mesh.triangles.end(), { south, index(n - 1, next), index(n - 1, j) });
        for (int i = 0; i + 1 < n; ++i)
          add_quad(mesh, index(i, j), index(i + 1, j), index(i + 1, next), index(i, next));
      }
    }
  }
  const double scale = input.ranged(1e-3, 1e3); // any unit
  for (double& x : mesh.points)
    x *= scale;
  return mesh;
}

void damage(mesolens::TriangleMesh& mesh, mesolens_fuzz::FuzzInput& input)
{
  const std::size_t operations = input.byte() % 8;
  for (std::size_t k = 0; k < operations && !input.empty(); ++k)
  {
    const std::uint8_t what = input.byte();
    const std::size_t v = input.byte() % mesh.vertex_count();
    const std::size_t w = input.byte() % mesh.vertex_count();
    const std::size_t t = input.byte() % std::max<std::size_t>(mesh.triangle_count(), 1);
    switch (what % 7)
    {
      case 0: // onto another vertex
        std::copy_n(&mesh.points[3 * w], 3, &mesh.points[3 * v]);
        break;
      case 1: // by a hair
        mesh.points[3 * v + what % 3] += input.ranged(-1e-9, 1e-9);
        break;
      case 2: // far away, or to any number at all
        mesh.points[3 * v + what % 3] = input.ranged(-1e6, 1e6);
        break;
      case 3: // flipped
        if (mesh.triangle_count())
          std::swap(mesh.triangles[3 * t], mesh.triangles[3 * t + 1]);
        break;
      case 4: // dropped
        if (mesh.triangle_count())
          mesh.triangles.erase(mesh.triangles.begin() + std::ptrdiff_t(3 * t),
                               mesh.triangles.begin() + std::ptrdiff_t(3 * t + 3));
        break;
      case 5: // repeated
        if (mesh.triangle_count())
          for (int c = 0; c < 3; ++c)
            mesh.triangles.push_back(mesh.triangles[3 * t + c]);
        break;
      default: // an index bent
        if (mesh.triangle_count())
          mesh.triangles[3 * t + what % 3] = std::int64_t(w) - (what & 8 ? 1000 : 0);
    }
  }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  mesolens_fuzz::FuzzInput input(data, size);
  mesolens::TriangleMesh mesh = base_mesh(input);
  damage(mesh, input);
  mesolens::GeodesicDiskParams params;
  const double radius_fraction = input.ranged(0.0, 0.8); // of the bounding box's diagonal
  params.min_triangles = input.byte() * 2;
  params.max_triangles = input.byte() * 4;
  // Any point: the seed is the surface point nearest to it.
  const double pick[3] = { input.ranged(-5, 5), input.ranged(-5, 5), input.ranged(-5, 5) };
  try
  {
    const mesolens::CellSurface surface(mesh);
    params.radius = radius_fraction * surface.bounding_diagonal();
    const mesolens::SurfacePoint seed = surface.closest_point({ pick[0], pick[1], pick[2] });
    const mesolens::GeodesicDisk disk = mesolens::geodesic_disk(surface, seed, params);
    const mesolens::MeshReport report = mesolens::mesh_report(disk.mesh.view());
    require(report.is_manifold() && report.boundary_loops == 1 && report.euler_characteristic == 1);
    require(disk.distance.size() == disk.mesh.vertex_count());
    for (const double x : disk.mesh.points)
      require(std::isfinite(x));
    const mesolens::DiskParameterization map =
      mesolens::harmonic_parameterization(disk.mesh, params.radius);
    require(map.uv.size() == 2 * disk.mesh.vertex_count());
    for (const double x : map.uv)
      require(std::isfinite(x));
  }
  catch (const mesolens::Error&)
  {
  }
  return 0;
}
