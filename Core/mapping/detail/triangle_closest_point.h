// SPDX-License-Identifier: GPL-3.0-or-later
// The point of a triangle closest to a point in space (private).
#pragma once

#include <array>

namespace mesolens {
namespace detail {

/// The closest point of triangle abc to p and its barycentric coordinates (weights of a, b, c),
/// by the Voronoi regions of the corners and edges (Ericson, Real-Time Collision Detection,
/// 5.1.5). Degenerate triangles give a point of one of their edges.
struct TriangleClosestPoint
{
  std::array<double, 3> position{};
  std::array<double, 3> barycentric{};
  double distance2 = 0; ///< squared distance from p
};

inline TriangleClosestPoint closest_on_triangle(const std::array<double, 3>& p,
                                                const std::array<double, 3>& a,
                                                const std::array<double, 3>& b,
                                                const std::array<double, 3>& c)
{
  auto minus = [](const std::array<double, 3>& x, const std::array<double, 3>& y) {
    return std::array<double, 3>{ x[0] - y[0], x[1] - y[1], x[2] - y[2] };
  };
  auto dot = [](const std::array<double, 3>& x, const std::array<double, 3>& y) {
    return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
  };
  auto result = [&](double u, double v, double w) {
    TriangleClosestPoint out;
    out.barycentric = { u, v, w };
    for (int d = 0; d < 3; ++d)
    {
      out.position[d] = u * a[d] + v * b[d] + w * c[d];
    }
    const auto offset = minus(p, out.position);
    out.distance2 = dot(offset, offset);
    return out;
  };
  const auto ab = minus(b, a), ac = minus(c, a), ap = minus(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0)
  {
    return result(1, 0, 0);
  }
  const auto bp = minus(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3)
  {
    return result(0, 1, 0);
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0)
  {
    const double t = d1 / (d1 - d3);
    return result(1 - t, t, 0);
  }
  const auto cp = minus(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6)
  {
    return result(0, 0, 1);
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0)
  {
    const double t = d2 / (d2 - d6);
    return result(1 - t, 0, t);
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
  {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return result(0, 1 - t, t);
  }
  const double denominator = va + vb + vc;
  if (!(denominator > 0))
  {
    return result(1, 0, 0);
  }
  const double v = vb / denominator, w = vc / denominator;
  return result(1 - v - w, v, w);
}

} // namespace detail
} // namespace mesolens
