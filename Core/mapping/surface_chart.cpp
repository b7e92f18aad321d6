// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/mapping/surface_chart.h"

#include "mesolens/common/errors.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace mesolens {

SurfaceChart::SurfaceChart(TriangleMesh disk, std::vector<double> uv, std::vector<double> normals,
                           SurfacePlacement placement)
  : Disk(std::move(disk))
  , Uv(std::move(uv))
  , Normals(std::move(normals))
  , Placement(std::move(placement))
{
  if (this->Uv.size() != 2 * this->Disk.vertex_count() || this->Disk.triangle_count() == 0)
  {
    throw InvalidInput("a surface chart needs one (u, v) per vertex of a non-empty mesh");
  }
  if (!std::all_of(this->Uv.begin(), this->Uv.end(), [](double x) { return std::isfinite(x); }))
  {
    throw InvalidInput("the texture coordinates of the surface chart are not finite");
  }
  if (this->Normals.empty())
  {
    this->Normals = vertex_normals(this->Disk);
  }
  if (this->Normals.size() != this->Disk.points.size())
  {
    throw InvalidInput("a surface chart needs one normal per vertex");
  }
  double low_u = std::numeric_limits<double>::max(), low_v = low_u;
  double high_u = -low_u, high_v = -low_u;
  for (std::size_t i = 0; i < this->Uv.size(); i += 2)
  {
    low_u = std::min(low_u, this->Uv[i]);
    high_u = std::max(high_u, this->Uv[i]);
    low_v = std::min(low_v, this->Uv[i + 1]);
    high_v = std::max(high_v, this->Uv[i + 1]);
  }
  const std::size_t triangles = this->Disk.triangle_count();
  // About one triangle per cell.
  this->Cell = std::max(std::sqrt((high_u - low_u) * (high_v - low_v) / double(triangles)), 1e-300);
  this->Low = { low_u, low_v };
  this->Columns = std::max(1, int((high_u - low_u) / this->Cell) + 1);
  this->Rows = std::max(1, int((high_v - low_v) / this->Cell) + 1);
  const std::size_t cells = std::size_t(this->Columns) * std::size_t(this->Rows);
  std::vector<std::array<int, 4>> extent(triangles);
  this->Start.assign(cells + 1, 0);
  for (std::size_t t = 0; t < triangles; ++t)
  {
    double u0 = std::numeric_limits<double>::max(), v0 = u0, u1 = -u0, v1 = -u0;
    for (int k = 0; k < 3; ++k)
    {
      const auto vertex = std::size_t(this->Disk.triangles[3 * t + std::size_t(k)]);
      u0 = std::min(u0, this->Uv[2 * vertex]);
      u1 = std::max(u1, this->Uv[2 * vertex]);
      v0 = std::min(v0, this->Uv[2 * vertex + 1]);
      v1 = std::max(v1, this->Uv[2 * vertex + 1]);
    }
    auto column = [&](double u) {
      return std::clamp(int((u - low_u) / this->Cell), 0, this->Columns - 1);
    };
    auto row = [&](double v) {
      return std::clamp(int((v - low_v) / this->Cell), 0, this->Rows - 1);
    };
    extent[t] = { column(u0), column(u1), row(v0), row(v1) };
    for (int r = extent[t][2]; r <= extent[t][3]; ++r)
    {
      for (int c = extent[t][0]; c <= extent[t][1]; ++c)
      {
        ++this->Start[std::size_t(r) * std::size_t(this->Columns) + std::size_t(c) + 1];
      }
    }
  }
  std::partial_sum(this->Start.begin(), this->Start.end(), this->Start.begin());
  this->Triangles.resize(this->Start.back());
  std::vector<std::size_t> fill(this->Start.begin(), this->Start.end() - 1);
  for (std::size_t t = 0; t < triangles; ++t)
  {
    for (int r = extent[t][2]; r <= extent[t][3]; ++r)
    {
      for (int c = extent[t][0]; c <= extent[t][1]; ++c)
      {
        this->Triangles[fill[std::size_t(r) * std::size_t(this->Columns) + std::size_t(c)]++] =
          std::uint32_t(t);
      }
    }
  }
}

std::array<double, 2> SurfaceChart::uv_of(const SurfacePoint& point) const
{
  std::array<double, 2> uv{ 0, 0 };
  for (int k = 0; k < 3; ++k)
  {
    const auto vertex =
      std::size_t(this->Disk.triangles[3 * std::size_t(point.triangle) + std::size_t(k)]);
    uv[0] += point.barycentric[std::size_t(k)] * this->Uv[2 * vertex];
    uv[1] += point.barycentric[std::size_t(k)] * this->Uv[2 * vertex + 1];
  }
  return uv;
}

bool SurfaceChart::locate(double u, double v, SurfacePoint& point) const
{
  if (!std::isfinite(u) || !std::isfinite(v))
  {
    return false;
  }
  const int column = int(std::floor((u - this->Low[0]) / this->Cell));
  const int row = int(std::floor((v - this->Low[1]) / this->Cell));
  if (column < 0 || row < 0 || column >= this->Columns || row >= this->Rows)
  {
    return false;
  }
  const std::size_t cell = std::size_t(row) * std::size_t(this->Columns) + std::size_t(column);
  double best_outside = 1e-9; // accept points on edges, within round-off
  bool found = false;
  for (std::size_t k = this->Start[cell]; k < this->Start[cell + 1]; ++k)
  {
    const std::size_t t = this->Triangles[k];
    const auto a = std::size_t(this->Disk.triangles[3 * t]);
    const auto b = std::size_t(this->Disk.triangles[3 * t + 1]);
    const auto c = std::size_t(this->Disk.triangles[3 * t + 2]);
    const double x0 = this->Uv[2 * a], y0 = this->Uv[2 * a + 1];
    const double x1 = this->Uv[2 * b] - x0, y1 = this->Uv[2 * b + 1] - y0;
    const double x2 = this->Uv[2 * c] - x0, y2 = this->Uv[2 * c + 1] - y0;
    const double determinant = x1 * y2 - x2 * y1;
    if (determinant == 0)
    {
      continue;
    }
    const double b1 = ((u - x0) * y2 - x2 * (v - y0)) / determinant;
    const double b2 = (x1 * (v - y0) - (u - x0) * y1) / determinant;
    const double b0 = 1 - b1 - b2;
    const double outside = std::max({ 0.0, -b0, -b1, -b2 });
    if (outside <= best_outside)
    {
      best_outside = outside;
      point.triangle = std::int64_t(t);
      point.barycentric = { b0, b1, b2 };
      found = true;
      if (outside == 0)
      {
        break;
      }
    }
  }
  if (found)
  {
    point.position = { 0, 0, 0 };
    for (int k = 0; k < 3; ++k)
    {
      const auto p =
        this->Disk.point(this->Disk.triangles[3 * std::size_t(point.triangle) + std::size_t(k)]);
      for (int d = 0; d < 3; ++d)
      {
        point.position[std::size_t(d)] += point.barycentric[std::size_t(k)] * p[std::size_t(d)];
      }
    }
  }
  return found;
}

namespace {
/// The vertex normals interpolated at `point` (a point of `disk`), unit length.
std::array<double, 3> interpolated_normal(const TriangleMesh& disk,
                                          const std::vector<double>& normals,
                                          const SurfacePoint& point)
{
  const auto t = std::size_t(point.triangle);
  std::array<double, 3> normal{ 0, 0, 0 };
  for (std::size_t k = 0; k < 3; ++k)
  {
    const auto vertex = std::size_t(disk.triangles[3 * t + k]);
    for (std::size_t d = 0; d < 3; ++d)
    {
      normal[d] += point.barycentric[k] * normals[3 * vertex + d];
    }
  }
  const double length =
    std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
  for (double& x : normal)
  {
    x /= length;
  }
  return normal;
}

/// Sets frame.tangent_u (d position / du of the triangle's affine map, made orthogonal to
/// frame.normal) and frame.tangent_v.
void set_tangents(const TriangleMesh& disk, const std::vector<double>& uv, std::int64_t triangle,
                  SurfaceFrame& frame)
{
  const auto t = std::size_t(triangle);
  std::array<std::size_t, 3> vertex{};
  for (std::size_t k = 0; k < 3; ++k)
  {
    vertex[k] = std::size_t(disk.triangles[3 * t + k]);
  }
  // d position / du: E * inverse(UV), with E the 3D edge vectors and UV the uv edge vectors.
  const auto p0 = disk.point(std::int64_t(vertex[0]));
  const auto p1 = disk.point(std::int64_t(vertex[1]));
  const auto p2 = disk.point(std::int64_t(vertex[2]));
  const double du1 = uv[2 * vertex[1]] - uv[2 * vertex[0]];
  const double dv1 = uv[2 * vertex[1] + 1] - uv[2 * vertex[0] + 1];
  const double du2 = uv[2 * vertex[2]] - uv[2 * vertex[0]];
  const double dv2 = uv[2 * vertex[2] + 1] - uv[2 * vertex[0] + 1];
  const double determinant = du1 * dv2 - du2 * dv1;
  const std::array<double, 3>& normal = frame.normal;
  std::array<double, 3> along_u{};
  for (std::size_t d = 0; d < 3; ++d)
  {
    along_u[d] = ((p1[d] - p0[d]) * dv2 - (p2[d] - p0[d]) * dv1) / determinant;
  }
  const double along_normal =
    along_u[0] * normal[0] + along_u[1] * normal[1] + along_u[2] * normal[2];
  for (std::size_t d = 0; d < 3; ++d)
  {
    along_u[d] -= along_normal * normal[d];
  }
  const double tangent_length =
    std::sqrt(along_u[0] * along_u[0] + along_u[1] * along_u[1] + along_u[2] * along_u[2]);
  for (std::size_t d = 0; d < 3; ++d)
  {
    frame.tangent_u[d] = along_u[d] / tangent_length;
  }
  frame.tangent_v = { normal[1] * frame.tangent_u[2] - normal[2] * frame.tangent_u[1],
                      normal[2] * frame.tangent_u[0] - normal[0] * frame.tangent_u[2],
                      normal[0] * frame.tangent_u[1] - normal[1] * frame.tangent_u[0] };
}
} // namespace

bool SurfaceChart::frame(double u, double v, SurfaceFrame& frame) const
{
  SurfacePoint point;
  if (!this->locate(u, v, point))
  {
    return false;
  }
  frame.position = point.position;
  frame.normal = interpolated_normal(this->Disk, this->Normals, point);
  if (this->Placement)
  {
    this->Placement(point.triangle, point.barycentric, frame);
  }
  set_tangents(this->Disk, this->Uv, point.triangle, frame);
  return true;
}

} // namespace mesolens
