// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/periodic_box.h"

#include <Eigen/Dense>

#include <cmath>
#include <limits>

namespace mesolens {

namespace {
Eigen::Matrix3d as_matrix(const PeriodicBox& box)
{
  Eigen::Matrix3d m; // columns are a, b, c
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      m(c, r) = box.vectors[r][c];
    }
  }
  return m;
}
} // namespace

double PeriodicBox::volume() const
{
  return as_matrix(*this).determinant();
}

bool PeriodicBox::is_set() const
{
  return std::abs(this->volume()) > 1e-6;
}

bool PeriodicBox::is_orthorhombic() const
{
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      if (r != c && std::abs(this->vectors[r][c]) > 1e-9)
      {
        return false;
      }
    }
  }
  return true;
}

std::array<double, 3> PeriodicBox::minimum_image(const std::array<double, 3>& d) const
{
  if (!this->is_set())
  {
    return d;
  }
  const Eigen::Matrix3d m = as_matrix(*this);
  const Eigen::Vector3d v(d[0], d[1], d[2]);
  Eigen::Vector3d fractional = m.partialPivLu().solve(v);
  for (int i = 0; i < 3; ++i)
  {
    fractional[i] -= std::round(fractional[i]);
  }
  const Eigen::Vector3d reduced = m * fractional;
  // Rounding in fractional space is exact only for orthorhombic boxes; in a skewed box the
  // shortest image can be one lattice step away, so look at the neighbours.
  Eigen::Vector3d best = reduced;
  if (!this->is_orthorhombic())
  {
    double best_length = reduced.squaredNorm();
    for (int i = -1; i <= 1; ++i)
    {
      for (int j = -1; j <= 1; ++j)
      {
        for (int k = -1; k <= 1; ++k)
        {
          const Eigen::Vector3d candidate = reduced + m * Eigen::Vector3d(i, j, k);
          const double length = candidate.squaredNorm();
          if (length < best_length)
          {
            best_length = length;
            best = candidate;
          }
        }
      }
    }
  }
  return { best[0], best[1], best[2] };
}

PeriodicBox PeriodicBox::from_cell(double a,
                                   double b,
                                   double c,
                                   double alpha,
                                   double beta,
                                   double gamma)
{
  const double degree = std::acos(-1.0) / 180.0;
  const double cos_alpha = std::cos(alpha * degree);
  const double cos_beta = std::cos(beta * degree);
  const double cos_gamma = std::cos(gamma * degree);
  const double sin_gamma = std::sin(gamma * degree);
  PeriodicBox box;
  box.vectors[0] = { a, 0, 0 };
  box.vectors[1] = { b * cos_gamma, b * sin_gamma, 0 };
  const double cx = c * cos_beta;
  const double cy =
    std::abs(sin_gamma) > 1e-12 ? c * (cos_alpha - cos_beta * cos_gamma) / sin_gamma : 0.0;
  const double cz2 = c * c - cx * cx - cy * cy;
  box.vectors[2] = { cx, cy, cz2 > 0 ? std::sqrt(cz2) : 0.0 };
  return box;
}

} // namespace mesolens
