// SPDX-License-Identifier: GPL-3.0-or-later
// Ray-primitive intersections of the atom impostors. The fragment shaders of the atom mapper
// (Rendering/glsl) evaluate the same formulas; these are their reference implementations.
#pragma once

#include <array>
#include <optional>

namespace mesolens {

using Vector3 = std::array<double, 3>;

/// Where a ray meets a surface: the ray parameter, the point and the unit outward normal.
struct RayHit
{
  double t = 0;
  Vector3 point{};
  Vector3 normal{};
};

/// The first intersection of the ray origin + t direction (direction of unit length, t > 0
/// counts) with the sphere. The discriminant comes from the ray's closest approach to the centre
/// (r² - |q|², q the centre's offset from the ray), not from b² - c, so spheres that are tiny
/// next to their distance from the eye (Å atoms in a µm scene) keep their precision in single
/// precision too. std::nullopt when the ray misses.
std::optional<RayHit> ray_sphere(const Vector3& origin, const Vector3& direction,
                                 const Vector3& centre, double radius);

/// The same in single precision, as the GPU computes it: the normal at the hit, or nullopt.
std::optional<std::array<float, 3>> ray_sphere_normal_float(const std::array<float, 3>& origin,
                                                            const std::array<float, 3>& direction,
                                                            const std::array<float, 3>& centre,
                                                            float radius);

/// The first intersection of the ray with the finite cylinder of `radius` around the segment
/// a-b (open: no caps; the atoms' spheres close the bonds). std::nullopt when the ray misses.
std::optional<RayHit> ray_cylinder(const Vector3& origin, const Vector3& direction,
                                   const Vector3& a, const Vector3& b, double radius);

/// Where the float twin of the bond shader meets its cylinder: the unit outward normal and the
/// hit's position along the bond (0 at a, 1 at b; the bond's colour changes at 0.5).
struct CylinderHitFloat
{
  std::array<float, 3> normal{};
  float axial = 0;
};

/// The bond fragment shader's intersection, in single precision as the GPU computes it: the
/// ray origin first moves to the ray's closest approach to the bond's middle, so the quadratic's
/// terms stay of the bond's size (Å bonds in a µm scene keep their precision). Open cylinder:
/// nullopt outside 0 <= axial <= 1, for a miss, or for a ray along the axis.
std::optional<CylinderHitFloat> ray_cylinder_float(const std::array<float, 3>& origin,
                                                   const std::array<float, 3>& direction,
                                                   const std::array<float, 3>& a,
                                                   const std::array<float, 3>& b, float radius);

} // namespace mesolens
