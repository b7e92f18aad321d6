// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/mapping/smooth_surface.h"

#include "mesolens/common/errors.h"

#include <cmath>

namespace mesolens {

namespace {
using Vec3 = std::array<double, 3>;

Vec3 operator+(const Vec3& a, const Vec3& b)
{
  return { a[0] + b[0], a[1] + b[1], a[2] + b[2] };
}
Vec3 operator-(const Vec3& a, const Vec3& b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}
Vec3 operator*(double s, const Vec3& a)
{
  return { s * a[0], s * a[1], s * a[2] };
}
double dot(const Vec3& a, const Vec3& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Vec3 normalized(const Vec3& a)
{
  const double length = std::sqrt(dot(a, a));
  return length > 0 ? (1 / length) * a : a;
}

/// Control point next to corner p on edge pq: a third of the way to q, pulled into p's tangent
/// plane.
Vec3 edge_control(const Vec3& p, const Vec3& q, const Vec3& np)
{
  return (1.0 / 3) * (2.0 * p + q - dot(q - p, np) * np);
}

/// Normal control point of edge pq: the mean of the end normals, reflected in the plane
/// perpendicular to the edge so that an S-shaped edge gets the normal of its inflection.
Vec3 edge_normal(const Vec3& p, const Vec3& q, const Vec3& np, const Vec3& nq)
{
  const Vec3 edge = q - p;
  const double length2 = dot(edge, edge);
  const double v = length2 > 0 ? 2 * dot(edge, np + nq) / length2 : 0.0;
  return normalized(np + nq - v * edge);
}
} // namespace

SmoothSurface::SmoothSurface(TriangleMesh mesh, std::vector<double> normals)
  : Mesh(std::move(mesh))
  , Normals(std::move(normals))
{
  if (this->Normals.empty())
  {
    this->Normals = mesolens::vertex_normals(this->Mesh);
  }
  if (this->Normals.size() != this->Mesh.points.size())
  {
    throw InvalidInput("a smooth surface needs one normal per mesh vertex");
  }
}

SmoothPoint SmoothSurface::evaluate(std::int64_t triangle,
                                    const std::array<double, 3>& barycentric) const
{
  std::array<Vec3, 3> p;
  std::array<Vec3, 3> n;
  for (std::size_t k = 0; k < 3; ++k)
  {
    const auto v = std::size_t(this->Mesh.triangles[3 * std::size_t(triangle) + k]);
    p[k] = this->Mesh.point(std::int64_t(v));
    n[k] = { this->Normals[3 * v], this->Normals[3 * v + 1], this->Normals[3 * v + 2] };
  }
  // Edge control points b_ij: on edge (i, j), next to corner i.
  std::array<std::array<Vec3, 3>, 3> b{};
  Vec3 edge_sum{ 0, 0, 0 };
  for (std::size_t i = 0; i < 3; ++i)
  {
    for (std::size_t j = 0; j < 3; ++j)
    {
      if (i != j)
      {
        b[i][j] = edge_control(p[i], p[j], n[i]);
        edge_sum = edge_sum + b[i][j];
      }
    }
  }
  const Vec3 centroid = (1.0 / 3) * (p[0] + p[1] + p[2]);
  const Vec3 e = (1.0 / 6) * edge_sum;
  const Vec3 middle = e + 0.5 * (e - centroid);

  const double u = barycentric[0], v = barycentric[1], w = barycentric[2];
  SmoothPoint out;
  out.position = (u * u * u) * p[0] + (v * v * v) * p[1] + (w * w * w) * p[2] +
    (3 * u * u * v) * b[0][1] + (3 * u * v * v) * b[1][0] + (3 * v * v * w) * b[1][2] +
    (3 * v * w * w) * b[2][1] + (3 * w * w * u) * b[2][0] + (3 * w * u * u) * b[0][2] +
    (6 * u * v * w) * middle;
  const Vec3 n01 = edge_normal(p[0], p[1], n[0], n[1]);
  const Vec3 n12 = edge_normal(p[1], p[2], n[1], n[2]);
  const Vec3 n20 = edge_normal(p[2], p[0], n[2], n[0]);
  out.normal = normalized((u * u) * n[0] + (v * v) * n[1] + (w * w) * n[2] + (u * v) * n01 +
                          (v * w) * n12 + (w * u) * n20);
  return out;
}

} // namespace mesolens
