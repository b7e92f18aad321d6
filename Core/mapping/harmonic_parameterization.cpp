// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/mapping/harmonic_parameterization.h"

#include "mesolens/common/errors.h"
#include "mesolens/mesh/mesh_report.h"

#include <Eigen/Sparse>
#include <Eigen/SparseLU>

#include <algorithm>
#include <cmath>

namespace mesolens {

namespace {
constexpr double pi = 3.14159265358979323846;

using Vec3 = std::array<double, 3>;

Vec3 minus(const Vec3& a, const Vec3& b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}
double dot(const Vec3& a, const Vec3& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
double length(const Vec3& a)
{
  return std::sqrt(dot(a, a));
}
Vec3 cross(const Vec3& a, const Vec3& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}

/// The one boundary loop of a disk, in the triangles' orientation.
std::vector<std::int64_t> boundary_loop(const TriangleMesh& disk)
{
  std::vector<std::vector<std::int64_t>> loops = boundary_loops(disk);
  if (loops.size() != 1)
  {
    throw TopologyError("the mesh to parameterize has " + std::to_string(loops.size()) +
                        " boundary loops; a disk has one");
  }
  return std::move(loops.front());
}

/// The disk's boundary loop on the circle of `radius` by arc length, counter-clockwise; sets
/// those vertices' uv and numbers the others (the unknowns) in `unknown` (-1 on the boundary).
/// Returns the number of unknowns.
std::int64_t place_boundary(const TriangleMesh& disk, double radius, std::vector<double>& uv,
                            std::vector<std::int64_t>& unknown)
{
  const std::vector<std::int64_t> loop = boundary_loop(disk);
  std::vector<double> arc(loop.size() + 1, 0.0);
  for (std::size_t i = 0; i < loop.size(); ++i)
  {
    arc[i + 1] =
      arc[i] + length(minus(disk.point(loop[(i + 1) % loop.size()]), disk.point(loop[i])));
  }
  std::vector<bool> on_boundary(disk.vertex_count(), false);
  for (std::size_t i = 0; i < loop.size(); ++i)
  {
    const double angle = 2 * pi * arc[i] / arc.back();
    const auto v = std::size_t(loop[i]);
    uv[2 * v] = radius * std::cos(angle);
    uv[2 * v + 1] = radius * std::sin(angle);
    on_boundary[v] = true;
  }
  unknown.assign(disk.vertex_count(), -1);
  std::int64_t interior = 0;
  for (std::size_t v = 0; v < disk.vertex_count(); ++v)
  {
    if (!on_boundary[v])
    {
      unknown[v] = interior++;
    }
  }
  return interior;
}

/// The mean-value system of the interior vertices: A (as triplets) and the right-hand sides
/// (u, v) that the boundary contributes.
struct MeanValueSystem
{
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixXd rhs;
};

/// Mean-value weights: w_ij = (tan(a/2) + tan(b/2)) / |x_j - x_i|, with a and b the angles at
/// x_i of the two triangles on edge ij. Each triangle adds its half-angle tangents at i to the
/// weights of its two other vertices.
MeanValueSystem mean_value_system(const TriangleMesh& disk, const std::vector<double>& uv,
                                  const std::vector<std::int64_t>& unknown, std::int64_t interior)
{
  MeanValueSystem system;
  system.entries.reserve(12 * std::size_t(interior));
  system.rhs = Eigen::MatrixXd::Zero(interior, 2);
  std::vector<double> diagonal(std::size_t(interior), 0.0);
  for (std::size_t t = 0; t < disk.triangle_count(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      const std::int64_t i = disk.triangles[3 * t + std::size_t(k)];
      if (unknown[std::size_t(i)] < 0)
      {
        continue;
      }
      const std::int64_t j = disk.triangles[3 * t + std::size_t((k + 1) % 3)];
      const std::int64_t l = disk.triangles[3 * t + std::size_t((k + 2) % 3)];
      const Vec3 xi = disk.point(i);
      const Vec3 eij = minus(disk.point(j), xi);
      const Vec3 eil = minus(disk.point(l), xi);
      const double angle = std::atan2(length(cross(eij, eil)), dot(eij, eil));
      const double half_tangent = std::tan(angle / 2);
      for (const auto& [other, edge] : { std::make_pair(j, eij), std::make_pair(l, eil) })
      {
        const double w = half_tangent / length(edge);
        const auto row = unknown[std::size_t(i)];
        diagonal[std::size_t(row)] += w;
        if (unknown[std::size_t(other)] >= 0)
        {
          system.entries.emplace_back(row, unknown[std::size_t(other)], -w);
        }
        else
        {
          system.rhs(row, 0) += w * uv[2 * std::size_t(other)];
          system.rhs(row, 1) += w * uv[2 * std::size_t(other) + 1];
        }
      }
    }
  }
  for (std::int64_t row = 0; row < interior; ++row)
  {
    system.entries.emplace_back(row, row, diagonal[std::size_t(row)]);
  }
  return system;
}

/// Solves the system (sparse LU) and writes the interior vertices' uv.
void solve_interior(const MeanValueSystem& system, const std::vector<std::int64_t>& unknown,
                    std::int64_t interior, std::vector<double>& uv)
{
  Eigen::SparseMatrix<double> matrix(interior, interior);
  matrix.setFromTriplets(system.entries.begin(), system.entries.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> solver;
  solver.analyzePattern(matrix);
  solver.factorize(matrix);
  if (solver.info() != Eigen::Success)
  {
    throw SolverFailure("the mean-value system could not be factorized: " +
                        solver.lastErrorMessage());
  }
  const Eigen::MatrixXd solution = solver.solve(system.rhs);
  if (solver.info() != Eigen::Success || !solution.allFinite())
  {
    throw SolverFailure("the mean-value system could not be solved");
  }
  for (std::size_t v = 0; v < unknown.size(); ++v)
  {
    if (unknown[v] >= 0)
    {
      uv[2 * v] = solution(unknown[v], 0);
      uv[2 * v + 1] = solution(unknown[v], 1);
    }
  }
}

/// Per triangle, the distortion of the affine map 3D triangle -> uv triangle (its Jacobian's
/// singular values), and the triangles it flips.
void measure_distortion(const TriangleMesh& disk, DiskParameterization& result)
{
  // Distortion per triangle, from the Jacobian of the affine map 3D triangle -> uv triangle.
  const std::size_t triangles = disk.triangle_count();
  result.angle_distortion.resize(triangles);
  result.area_distortion.resize(triangles);
  result.stretch.resize(triangles);
  std::vector<double> ratio(triangles);
  double total_uv = 0;
  double total_3d = 0;
  for (std::size_t t = 0; t < triangles; ++t)
  {
    const std::int64_t a = disk.triangles[3 * t];
    const std::int64_t b = disk.triangles[3 * t + 1];
    const std::int64_t c = disk.triangles[3 * t + 2];
    const Vec3 e1 = minus(disk.point(b), disk.point(a));
    const Vec3 e2 = minus(disk.point(c), disk.point(a));
    // Local orthonormal frame of the 3D triangle.
    const double l1 = length(e1);
    const Vec3 x_axis{ e1[0] / l1, e1[1] / l1, e1[2] / l1 };
    const double area_3d = 0.5 * length(cross(e1, e2));
    const double p2x = dot(e2, x_axis);
    const double p2y = 2 * area_3d / l1;
    const double du1 = result.uv[2 * std::size_t(b)] - result.uv[2 * std::size_t(a)];
    const double dv1 = result.uv[2 * std::size_t(b) + 1] - result.uv[2 * std::size_t(a) + 1];
    const double du2 = result.uv[2 * std::size_t(c)] - result.uv[2 * std::size_t(a)];
    const double dv2 = result.uv[2 * std::size_t(c) + 1] - result.uv[2 * std::size_t(a) + 1];
    const double area_uv = 0.5 * (du1 * dv2 - dv1 * du2);
    if (!(area_uv > 0))
    {
      ++result.flipped_triangles;
    }
    // J maps local (x, y) to (u, v): columns J * (l1, 0) = (du1, dv1), J * (p2x, p2y) = (du2, dv2).
    const double j11 = du1 / l1;
    const double j21 = dv1 / l1;
    const double j12 = (du2 - j11 * p2x) / p2y;
    const double j22 = (dv2 - j21 * p2x) / p2y;
    // Singular values of a 2x2 matrix without cancellation: (Q + R, |Q - R|).
    const double q = std::hypot((j11 + j22) / 2, (j21 - j12) / 2);
    const double r = std::hypot((j11 - j22) / 2, (j21 + j12) / 2);
    const double s_max = q + r;
    const double s_min = std::abs(q - r);
    result.angle_distortion[t] =
      s_min > 0 ? s_max / s_min : std::numeric_limits<double>::infinity();
    result.stretch[t] = s_min > 0 && std::isfinite(s_max) ? std::max(s_max, 1 / s_min)
                                                          : std::numeric_limits<double>::infinity();
    ratio[t] = std::abs(area_uv) / area_3d;
    total_uv += std::abs(area_uv);
    total_3d += area_3d;
  }
  const double global = total_uv / total_3d;
  for (std::size_t t = 0; t < triangles; ++t)
  {
    result.area_distortion[t] = ratio[t] / global;
  }
}
} // namespace

DiskParameterization harmonic_parameterization(const TriangleMesh& disk, double radius)
{
  if (!(radius > 0) || !std::isfinite(radius))
  {
    throw InvalidInput("the parameterization radius must be positive and finite");
  }
  require_manifold(disk, "the disk to parameterize");
  const MeshReport report = mesh_report(disk.view());
  if (report.euler_characteristic != 1 || report.boundary_loops != 1)
  {
    throw TopologyError(
      "the mesh to parameterize is not a topological disk (Euler characteristic " +
      std::to_string(report.euler_characteristic) + ", " + std::to_string(report.boundary_loops) +
      " boundary loops)");
  }
  DiskParameterization result;
  result.uv.assign(2 * disk.vertex_count(), 0.0);
  std::vector<std::int64_t> unknown;
  const std::int64_t interior = place_boundary(disk, radius, result.uv, unknown);
  if (interior > 0)
  {
    solve_interior(mean_value_system(disk, result.uv, unknown, interior), unknown, interior,
                   result.uv);
  }
  measure_distortion(disk, result);
  return result;
}

} // namespace mesolens
