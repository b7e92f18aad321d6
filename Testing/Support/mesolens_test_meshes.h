// SPDX-License-Identifier: GPL-3.0-or-later
// Analytic test surfaces: spheres, planes, cylinders, saddles, as mesolens::TriangleMesh.
#pragma once

#include "mesolens/io/polygon_soup.h"
#include "mesolens/mesh/triangle_mesh.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <random>
#include <utility>
#include <vector>

namespace mesolens_test {

/// The polygons of `soup` as triangles, each polygon fanned from its first corner.
inline mesolens::TriangleMesh fan_triangulated(const mesolens::PolygonSoup& soup)
{
  mesolens::TriangleMesh mesh;
  mesh.points = soup.points;
  for (const auto& polygon : soup.polygons)
  {
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
    {
      mesh.triangles.insert(mesh.triangles.end(), { polygon[0], polygon[k], polygon[k + 1] });
    }
  }
  return mesh;
}

/// `count` points spread evenly over a sphere of `radius` around the origin (a Fibonacci
/// lattice), 3 coordinates each.
inline std::vector<double> fibonacci_sphere(int count, double radius)
{
  std::vector<double> points;
  const double golden = 3.14159265358979 * (3 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i)
  {
    const double z = 1 - 2 * (i + 0.5) / count;
    const double r = std::sqrt(1 - z * z);
    points.insert(
      points.end(),
      { radius * r * std::cos(golden * i), radius * r * std::sin(golden * i), radius * z });
  }
  return points;
}

/// Icosahedron subdivided `levels` times (midpoints pushed to the sphere): 20 * 4^levels
/// triangles on a sphere of `radius` around the origin, oriented outwards.
inline mesolens::TriangleMesh icosphere(double radius, int levels)
{
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<std::array<double, 3>> v = { { -1, t, 0 }, { 1, t, 0 }, { -1, -t, 0 }, { 1, -t, 0 },
                                           { 0, -1, t }, { 0, 1, t }, { 0, -1, -t }, { 0, 1, -t },
                                           { t, 0, -1 }, { t, 0, 1 }, { -t, 0, -1 }, { -t, 0, 1 } };
  std::vector<std::array<std::int64_t, 3>> f = {
    { 0, 11, 5 }, { 0, 5, 1 },  { 0, 1, 7 },   { 0, 7, 10 }, { 0, 10, 11 },
    { 1, 5, 9 },  { 5, 11, 4 }, { 11, 10, 2 }, { 10, 7, 6 }, { 7, 1, 8 },
    { 3, 9, 4 },  { 3, 4, 2 },  { 3, 2, 6 },   { 3, 6, 8 },  { 3, 8, 9 },
    { 4, 9, 5 },  { 2, 4, 11 }, { 6, 2, 10 },  { 8, 6, 7 },  { 9, 8, 1 }
  };
  auto normalize = [](std::array<double, 3> p) {
    const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    return std::array<double, 3>{ p[0] / n, p[1] / n, p[2] / n };
  };
  for (auto& p : v)
  {
    p = normalize(p);
  }
  for (int level = 0; level < levels; ++level)
  {
    std::map<std::pair<std::int64_t, std::int64_t>, std::int64_t> midpoint;
    auto middle = [&](std::int64_t a, std::int64_t b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      const auto found = midpoint.find(key);
      if (found != midpoint.end())
      {
        return found->second;
      }
      v.push_back(normalize({ (v[std::size_t(a)][0] + v[std::size_t(b)][0]) / 2,
                              (v[std::size_t(a)][1] + v[std::size_t(b)][1]) / 2,
                              (v[std::size_t(a)][2] + v[std::size_t(b)][2]) / 2 }));
      return midpoint[key] = std::int64_t(v.size() - 1);
    };
    std::vector<std::array<std::int64_t, 3>> finer;
    for (const auto& tri : f)
    {
      const auto ab = middle(tri[0], tri[1]);
      const auto bc = middle(tri[1], tri[2]);
      const auto ca = middle(tri[2], tri[0]);
      finer.push_back({ tri[0], ab, ca });
      finer.push_back({ tri[1], bc, ab });
      finer.push_back({ tri[2], ca, bc });
      finer.push_back({ ab, bc, ca });
    }
    f = finer;
  }
  mesolens::TriangleMesh mesh;
  for (const auto& p : v)
  {
    mesh.points.insert(mesh.points.end(), { radius * p[0], radius * p[1], radius * p[2] });
  }
  for (const auto& tri : f)
  {
    mesh.triangles.insert(mesh.triangles.end(), { tri[0], tri[1], tri[2] });
  }
  return mesh;
}

/// A grid of n x n vertices over [-half, half]^2, mapped through `lift` (u, v) -> 3D, interior
/// vertices jittered by up to `jitter` of a cell (seeded), split along alternating diagonals.
inline mesolens::TriangleMesh lifted_grid(
  int n, double half, const std::function<std::array<double, 3>(double, double)>& lift,
  double jitter = 0.0, unsigned seed = 1)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> offset(-jitter, jitter);
  const double cell = 2 * half / (n - 1);
  mesolens::TriangleMesh mesh;
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      double u = -half + i * cell;
      double v = -half + j * cell;
      if (i > 0 && j > 0 && i < n - 1 && j < n - 1)
      {
        u += offset(random) * cell;
        v += offset(random) * cell;
      }
      const auto p = lift(u, v);
      mesh.points.insert(mesh.points.end(), { p[0], p[1], p[2] });
    }
  }
  for (int j = 0; j + 1 < n; ++j)
  {
    for (int i = 0; i + 1 < n; ++i)
    {
      const std::int64_t a = j * n + i;
      const std::int64_t b = a + 1;
      const std::int64_t c = a + n;
      const std::int64_t d = c + 1;
      if ((i + j) % 2 == 0)
      {
        mesh.triangles.insert(mesh.triangles.end(), { a, b, d, a, d, c });
      }
      else
      {
        mesh.triangles.insert(mesh.triangles.end(), { a, b, c, b, d, c });
      }
    }
  }
  return mesh;
}

inline mesolens::TriangleMesh plane_grid(int n, double half, double jitter = 0.0, unsigned seed = 1)
{
  return lifted_grid(
    n, half,
    [](double u, double v) {
      return std::array<double, 3>{ u, v, 0.0 };
    },
    jitter, seed);
}

/// An open tube of radius `radius` around the z axis, z in [-half_length, half_length].
inline mesolens::TriangleMesh cylinder(double radius, double half_length, int around, int along)
{
  mesolens::TriangleMesh mesh;
  const double pi = 3.14159265358979323846;
  for (int j = 0; j <= along; ++j)
  {
    for (int i = 0; i < around; ++i)
    {
      const double angle = 2 * pi * i / around + (j % 2) * pi / around;
      mesh.points.insert(mesh.points.end(),
                         { radius * std::cos(angle), radius * std::sin(angle),
                           -half_length + 2 * half_length * j / along });
    }
  }
  for (int j = 0; j < along; ++j)
  {
    for (int i = 0; i < around; ++i)
    {
      const std::int64_t a = j * around + i;
      const std::int64_t b = j * around + (i + 1) % around;
      const std::int64_t c = (j + 1) * around + i;
      const std::int64_t d = (j + 1) * around + (i + 1) % around;
      mesh.triangles.insert(mesh.triangles.end(), { a, b, c, b, d, c });
    }
  }
  return mesh;
}

/// A closed torus around the z axis: a tube of radius `minor` around the circle of radius
/// `major`, `around` segments along that circle and `tube` around the tube; genus 1, oriented
/// outwards.
inline mesolens::TriangleMesh torus(double major, double minor, int around, int tube)
{
  mesolens::TriangleMesh mesh;
  const double pi = 3.14159265358979323846;
  for (int i = 0; i < around; ++i)
  {
    const double phi = 2 * pi * i / around;
    for (int j = 0; j < tube; ++j)
    {
      const double theta = 2 * pi * j / tube;
      const double ring = major + minor * std::cos(theta);
      mesh.points.insert(mesh.points.end(),
                         { ring * std::cos(phi), ring * std::sin(phi), minor * std::sin(theta) });
    }
  }
  auto id = [around, tube](int i, int j) { return std::int64_t((i % around) * tube + (j % tube)); };
  for (int i = 0; i < around; ++i)
  {
    for (int j = 0; j < tube; ++j)
    {
      mesh.triangles.insert(
        mesh.triangles.end(),
        { id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j), id(i + 1, j + 1), id(i, j + 1) });
    }
  }
  return mesh;
}

/// A flat polar disk: a centre vertex and `rings` rings of `around` vertices, jittered inside,
/// the outer ring exactly on the circle of radius `outer`.
inline mesolens::TriangleMesh polar_disk(int rings, int around, double outer)
{
  mesolens::TriangleMesh mesh;
  mesh.points = { 0, 0, 0 };
  for (int k = 1; k <= rings; ++k)
  {
    for (int i = 0; i < around; ++i)
    {
      const double angle = 2 * 3.14159265358979323846 * (i + 0.5 * (k % 2)) / around;
      const double r =
        outer * k / rings * (k < rings ? 1 + 0.1 * std::sin(7.0 * i + k) / rings : 1);
      mesh.points.insert(mesh.points.end(), { r * std::cos(angle), r * std::sin(angle), 0.0 });
    }
  }
  auto ring = [around](int k, int i) { return std::int64_t(1 + (k - 1) * around + (i % around)); };
  for (int i = 0; i < around; ++i)
  {
    mesh.triangles.insert(mesh.triangles.end(), { 0, ring(1, i), ring(1, i + 1) });
  }
  for (int k = 1; k < rings; ++k)
  {
    for (int i = 0; i < around; ++i)
    {
      mesh.triangles.insert(mesh.triangles.end(),
                            { ring(k, i), ring(k + 1, i), ring(k + 1, i + 1) });
      mesh.triangles.insert(mesh.triangles.end(),
                            { ring(k, i), ring(k + 1, i + 1), ring(k, i + 1) });
    }
  }
  return mesh;
}

/// A point inside triangle `triangle` with the given barycentric weights.
inline mesolens::SurfacePoint surface_point(const mesolens::TriangleMesh& mesh,
                                            std::int64_t triangle,
                                            std::array<double, 3> barycentric = { 0.2, 0.3, 0.5 })
{
  mesolens::SurfacePoint point;
  point.triangle = triangle;
  point.barycentric = barycentric;
  point.position = { 0, 0, 0 };
  for (int k = 0; k < 3; ++k)
  {
    const auto v = mesh.point(mesh.triangles[3 * std::size_t(triangle) + std::size_t(k)]);
    for (int d = 0; d < 3; ++d)
    {
      point.position[std::size_t(d)] += barycentric[std::size_t(k)] * v[std::size_t(d)];
    }
  }
  return point;
}

}
