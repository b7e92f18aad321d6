// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/mesh/surface_locator.h"

#include "mesolens/common/errors.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <cmath>
#include <vector>

namespace mesolens {

namespace {
using Kernel = CGAL::Simple_cartesian<double>;
using CgalTriangle = Kernel::Triangle_3;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<CgalTriangle>::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
} // namespace

struct SurfaceLocator::Impl
{
  std::vector<CgalTriangle> Triangles;
  std::unique_ptr<Tree> SearchTree;
};

SurfaceLocator::SurfaceLocator(const TriangleMesh& mesh)
  : Internal(std::make_unique<Impl>())
{
  if (mesh.triangle_count() == 0)
  {
    throw InvalidInput("the surface has no triangles");
  }
  for (double value : mesh.points)
  {
    if (!std::isfinite(value))
    {
      throw InvalidInput("the surface has a non-finite point");
    }
  }
  Impl& impl = *this->Internal;
  impl.Triangles.reserve(mesh.triangle_count());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
  {
    const auto a = mesh.point(mesh.triangles[3 * t]);
    const auto b = mesh.point(mesh.triangles[3 * t + 1]);
    const auto c = mesh.point(mesh.triangles[3 * t + 2]);
    impl.Triangles.emplace_back(Kernel::Point_3(a[0], a[1], a[2]),
                                Kernel::Point_3(b[0], b[1], b[2]),
                                Kernel::Point_3(c[0], c[1], c[2]));
  }
  impl.SearchTree = std::make_unique<Tree>(impl.Triangles.begin(), impl.Triangles.end());
  impl.SearchTree->accelerate_distance_queries();
}

SurfaceLocator::~SurfaceLocator() = default;

SurfacePoint SurfaceLocator::closest_point(const std::array<double, 3>& point,
                                           double* distance) const
{
  return this->closest_point(point, nullptr, distance);
}

SurfacePoint SurfaceLocator::closest_point(const std::array<double, 3>& point,
                                           const SurfacePoint* hint, double* distance) const
{
  if (!std::isfinite(point[0]) || !std::isfinite(point[1]) || !std::isfinite(point[2]))
  {
    throw InvalidInput("the query point has a non-finite coordinate");
  }
  const Impl& impl = *this->Internal;
  const Kernel::Point_3 query(point[0], point[1], point[2]);
  const bool usable_hint =
    hint && hint->triangle >= 0 && std::size_t(hint->triangle) < impl.Triangles.size();
  const auto closest = usable_hint
    ? impl.SearchTree->closest_point_and_primitive(
        query,
        std::make_pair(Kernel::Point_3(hint->position[0], hint->position[1], hint->position[2]),
                       impl.Triangles.cbegin() + hint->triangle))
    : impl.SearchTree->closest_point_and_primitive(query);
  SurfacePoint result;
  result.triangle = std::int64_t(closest.second - impl.Triangles.begin());
  result.position = { closest.first.x(), closest.first.y(), closest.first.z() };
  // Barycentric coordinates of the closest point (it lies in the triangle's plane).
  const CgalTriangle& t = *closest.second;
  const Kernel::Vector_3 v0 = t[1] - t[0];
  const Kernel::Vector_3 v1 = t[2] - t[0];
  const Kernel::Vector_3 v2 = closest.first - t[0];
  const double d00 = v0 * v0;
  const double d01 = v0 * v1;
  const double d11 = v1 * v1;
  const double d20 = v2 * v0;
  const double d21 = v2 * v1;
  const double denominator = d00 * d11 - d01 * d01;
  const double b1 = denominator > 0 ? (d11 * d20 - d01 * d21) / denominator : 0.0;
  const double b2 = denominator > 0 ? (d00 * d21 - d01 * d20) / denominator : 0.0;
  result.barycentric = { 1.0 - b1 - b2, b1, b2 };
  if (distance)
  {
    *distance = std::sqrt(CGAL::squared_distance(query, closest.first));
  }
  return result;
}

} // namespace mesolens
