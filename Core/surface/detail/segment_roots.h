// SPDX-License-Identifier: GPL-3.0-or-later
// Where a grid edge crosses a surface (private to MesoLensCore): the molecular surfaces'
// vertices, on one sphere in closed form, on a circle's tube by Newton's method, on any other
// piece by regula falsi.
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <cmath>

namespace mesolens {

/// The point at parameter t of the segment from a to b, never exactly at an end, so that
/// vertices of different edges stay apart where the surface passes through a grid point.
inline Eigen::Vector3d on_segment(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double t)
{
  return a + std::clamp(t, 1e-5, 1.0 - 1e-5) * (b - a);
}

/// t when it lies in the bracket [t0, t1], else (NaN included) the bracket's middle: a step
/// from values that break the precondition (both ends on one side, an infinite value) stays on
/// the segment.
inline double within_bracket(double t, double t0, double t1)
{
  return t >= t0 && t <= t1 ? t : 0.5 * (t0 + t1);
}

/// The parameters along the line a + t (b - a) where it enters (`entry`) and leaves (`exit`) the
/// sphere (`centre`, `radius`), from the quadratic formula in its cancellation-free form; false
/// when the line misses it. Precondition: a != b.
inline bool line_sphere(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                        const Eigen::Vector3d& centre, double radius, double& entry, double& exit)
{
  const Eigen::Vector3d d = b - a, e = a - centre;
  const double dd = d.squaredNorm(), ed = e.dot(d), c = e.squaredNorm() - radius * radius;
  const double discriminant = ed * ed - dd * c;
  if (!(discriminant >= 0) || !(dd > 0))
  {
    return false;
  }
  const double q = -(ed + std::copysign(std::sqrt(discriminant), ed));
  const double first = q / dd, second = q != 0 ? c / q : first;
  entry = std::min(first, second);
  exit = std::max(first, second);
  return true;
}

/// The root of `value` on the segment from a (value <= 0) to b (value > 0), by the Illinois
/// variant of regula falsi, to 1e-9 Å, kept 1e-5 of the segment from either end (so no triangle
/// degenerates where the surface passes through a grid point).
template<typename Value>
Eigen::Vector3d segment_root(const Eigen::Vector3d& a, double value_a, const Eigen::Vector3d& b,
                             double value_b, Value&& value)
{
  double t0 = 0, t1 = 1, f0 = value_a, f1 = value_b;
  const double length = (b - a).norm();
  int side = 0;
  double t = within_bracket(f0 / (f0 - f1), t0, t1);
  for (int iteration = 0; iteration < 60 && (t1 - t0) * length > 1e-9; ++iteration)
  {
    t = within_bracket((t0 * f1 - t1 * f0) / (f1 - f0), t0, t1);
    const double f = value(a + t * (b - a));
    if (f == 0)
    {
      break;
    }
    if (f < 0)
    {
      t0 = t;
      f0 = f;
      if (side == -1)
      {
        f1 *= 0.5;
      }
      side = -1;
    }
    else
    {
      t1 = t;
      f1 = f;
      if (side == 1)
      {
        f0 *= 0.5;
      }
      side = 1;
    }
  }
  return on_segment(a, b, t);
}

/// The root of `value` on the segment from a (value <= 0) to b (value > 0) as segment_root()
/// finds it, by Newton's method where `value(x, slope)` also gives the slope along the segment
/// (per unit of its parameter): steps that leave the bracket, or a slope that is not positive,
/// fall back to regula falsi. Quadratic near a simple root, so a few evaluations do.
template<typename ValueAndSlope>
Eigen::Vector3d segment_root_newton(const Eigen::Vector3d& a, double value_a,
                                    const Eigen::Vector3d& b, double value_b, ValueAndSlope&& value)
{
  double t0 = 0, t1 = 1, f0 = value_a, f1 = value_b;
  const double length = (b - a).norm();
  double t = within_bracket(f0 / (f0 - f1), t0, t1);
  for (int iteration = 0; iteration < 60; ++iteration)
  {
    double slope = 0;
    const double f = value(a + t * (b - a), slope);
    if (f == 0)
    {
      break;
    }
    if (f < 0)
    {
      t0 = t;
      f0 = f;
    }
    else
    {
      t1 = t;
      f1 = f;
    }
    double next = slope > 0 ? t - f / slope : -1.0;
    if (!(next > t0 && next < t1))
    {
      next = within_bracket((t0 * f1 - t1 * f0) / (f1 - f0), t0, t1);
    }
    const bool converged = std::abs(next - t) * length <= 1e-10 || (t1 - t0) * length <= 1e-9;
    t = next;
    if (converged)
    {
      break;
    }
  }
  return on_segment(a, b, t);
}

} // namespace mesolens
