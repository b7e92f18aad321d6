// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/render/impostor_geometry.h"

#include <cmath>

namespace mesolens {

namespace {
double dot(const Vector3& a, const Vector3& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Vector3 sub(const Vector3& a, const Vector3& b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}
Vector3 add_scaled(const Vector3& a, double s, const Vector3& b)
{
  return { a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2] };
}
Vector3 normalized(const Vector3& a)
{
  const double length = std::sqrt(dot(a, a));
  return { a[0] / length, a[1] / length, a[2] / length };
}
} // namespace

std::optional<RayHit> ray_sphere(const Vector3& origin, const Vector3& direction,
                                 const Vector3& centre, double radius)
{
  const Vector3 to_centre = sub(centre, origin);
  const double along = dot(to_centre, direction);                  // closest approach along the ray
  const Vector3 offset = add_scaled(to_centre, -along, direction); // centre - closest point
  const double half_chord2 = radius * radius - dot(offset, offset);
  if (half_chord2 < 0)
  {
    return std::nullopt;
  }
  const double t = along - std::sqrt(half_chord2);
  if (t <= 0)
  {
    return std::nullopt;
  }
  RayHit hit;
  hit.t = t;
  hit.point = add_scaled(origin, t, direction);
  hit.normal = normalized(sub(hit.point, centre));
  return hit;
}

std::optional<std::array<float, 3>> ray_sphere_normal_float(const std::array<float, 3>& origin,
                                                            const std::array<float, 3>& direction,
                                                            const std::array<float, 3>& centre,
                                                            float radius)
{
  // Line by line what the fragment shader does, in float.
  const float cx = centre[0] - origin[0], cy = centre[1] - origin[1], cz = centre[2] - origin[2];
  const float along = cx * direction[0] + cy * direction[1] + cz * direction[2];
  const float qx = cx - along * direction[0], qy = cy - along * direction[1],
              qz = cz - along * direction[2];
  const float half_chord2 = radius * radius - (qx * qx + qy * qy + qz * qz);
  if (half_chord2 < 0)
  {
    return std::nullopt;
  }
  const float half_chord = std::sqrt(half_chord2);
  // Hit point relative to the centre: -q - half_chord * direction (no large numbers involved).
  std::array<float, 3> normal{ (-qx - half_chord * direction[0]) / radius,
                               (-qy - half_chord * direction[1]) / radius,
                               (-qz - half_chord * direction[2]) / radius };
  return normal;
}

std::optional<RayHit> ray_cylinder(const Vector3& origin, const Vector3& direction,
                                   const Vector3& a, const Vector3& b, double radius)
{
  // Work relative to a, with the axis w of unit length: the ray's components orthogonal to w
  // form a 2D circle problem.
  const Vector3 axis = sub(b, a);
  const double length = std::sqrt(dot(axis, axis));
  if (!(length > 0))
  {
    return std::nullopt;
  }
  const Vector3 w{ axis[0] / length, axis[1] / length, axis[2] / length };
  const Vector3 start = sub(origin, a);
  const Vector3 d_perp = add_scaled(direction, -dot(direction, w), w);
  const Vector3 s_perp = add_scaled(start, -dot(start, w), w);
  const double qa = dot(d_perp, d_perp);
  if (qa <= 0)
  {
    return std::nullopt; // the ray runs along the axis
  }
  // Closest approach in the orthogonal plane, then the half chord (as for the sphere).
  const double along = -dot(s_perp, d_perp) / qa;
  const Vector3 closest = add_scaled(s_perp, along, d_perp);
  const double half_chord2 = (radius * radius - dot(closest, closest)) / qa;
  if (half_chord2 < 0)
  {
    return std::nullopt;
  }
  const double t = along - std::sqrt(half_chord2);
  if (t <= 0)
  {
    return std::nullopt;
  }
  const Vector3 point_from_a = add_scaled(start, t, direction);
  const double height = dot(point_from_a, w);
  if (height < 0 || height > length)
  {
    return std::nullopt;
  }
  RayHit hit;
  hit.t = t;
  hit.point = add_scaled(origin, t, direction);
  hit.normal = normalized(add_scaled(point_from_a, -height, w));
  return hit;
}

std::optional<CylinderHitFloat> ray_cylinder_float(const std::array<float, 3>& origin,
                                                   const std::array<float, 3>& direction,
                                                   const std::array<float, 3>& a,
                                                   const std::array<float, 3>& b, float radius)
{
  // Line by line what the fragment shader does, in float.
  auto dotf = [](const std::array<float, 3>& u, const std::array<float, 3>& v) {
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
  };
  std::array<float, 3> ray_origin = origin;
  const std::array<float, 3> middle{ 0.5f * (a[0] + b[0]), 0.5f * (a[1] + b[1]),
                                     0.5f * (a[2] + b[2]) };
  const std::array<float, 3> to_middle{ middle[0] - origin[0], middle[1] - origin[1],
                                        middle[2] - origin[2] };
  const float shift = dotf(to_middle, direction);
  for (int d = 0; d < 3; ++d)
  {
    ray_origin[d] += shift * direction[d];
  }
  const std::array<float, 3> axis{ b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const std::array<float, 3> from_start{ ray_origin[0] - a[0], ray_origin[1] - a[1],
                                         ray_origin[2] - a[2] };
  const float axis2 = dotf(axis, axis);
  const float axis_ray = dotf(axis, direction);
  const float axis_start = dotf(axis, from_start);
  const float k2 = axis2 - axis_ray * axis_ray;
  const float k1 = axis2 * dotf(from_start, direction) - axis_start * axis_ray;
  const float k0 =
    axis2 * dotf(from_start, from_start) - axis_start * axis_start - radius * radius * axis2;
  const float discriminant = k1 * k1 - k2 * k0;
  if (k2 <= 0 || discriminant < 0)
  {
    return std::nullopt;
  }
  const float hit_along = (-k1 - std::sqrt(discriminant)) / k2;
  CylinderHitFloat hit;
  hit.axial = (axis_start + hit_along * axis_ray) / axis2;
  if (hit.axial < 0 || hit.axial > 1)
  {
    return std::nullopt;
  }
  for (int d = 0; d < 3; ++d)
  {
    const float point = ray_origin[d] + hit_along * direction[d];
    hit.normal[d] = (point - a[d] - hit.axial * axis[d]) / radius;
  }
  return hit;
}

} // namespace mesolens
