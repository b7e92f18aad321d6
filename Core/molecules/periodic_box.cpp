// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/molecules/periodic_box.h"

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
  return MinimumImage(*this)(d);
}

double PeriodicBox::smallest_height() const
{
  if (!this->is_set())
  {
    return 0;
  }
  const auto cross = [](const std::array<double, 3>& u, const std::array<double, 3>& v) {
    return std::array<double, 3>{ u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                                  u[0] * v[1] - u[1] * v[0] };
  };
  const auto& [a, b, c] = this->vectors;
  double largest_face = 0;
  for (const auto& face : { cross(b, c), cross(c, a), cross(a, b) })
  {
    largest_face =
      std::max(largest_face, std::sqrt(face[0] * face[0] + face[1] * face[1] + face[2] * face[2]));
  }
  return std::abs(this->volume()) / largest_face;
}

MinimumImage::MinimumImage(const PeriodicBox& box)
  : Box(box)
  , Set(box.is_set())
  , Orthorhombic(box.is_orthorhombic())
{
  if (this->Set)
  {
    const Eigen::Matrix3d inverse = as_matrix(box).inverse();
    for (int r = 0; r < 3; ++r)
    {
      for (int c = 0; c < 3; ++c)
      {
        this->Inverse[std::size_t(r)][std::size_t(c)] = inverse(r, c);
      }
    }
  }
}

std::array<double, 3> MinimumImage::operator()(const std::array<double, 3>& d) const
{
  if (!this->Set)
  {
    return d;
  }
  std::array<double, 3> reduced = d;
  for (std::size_t axis = 0; axis < 3; ++axis)
  {
    const double fractional =
      this->Inverse[axis][0] * d[0] + this->Inverse[axis][1] * d[1] + this->Inverse[axis][2] * d[2];
    const double steps = std::round(fractional);
    for (std::size_t k = 0; k < 3; ++k)
    {
      reduced[k] -= steps * this->Box.vectors[axis][k];
    }
  }
  if (this->Orthorhombic)
  {
    return reduced;
  }
  // Rounding in fractional space is exact only for orthorhombic boxes; in a skewed box the
  // shortest image can be one lattice step away, so look at the neighbours.
  auto length2 = [](const std::array<double, 3>& v) {
    return v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  };
  std::array<double, 3> best = reduced;
  double best_length = length2(reduced);
  for (int i = -1; i <= 1; ++i)
  {
    for (int j = -1; j <= 1; ++j)
    {
      for (int k = -1; k <= 1; ++k)
      {
        std::array<double, 3> candidate = reduced;
        for (std::size_t c = 0; c < 3; ++c)
        {
          candidate[c] +=
            i * this->Box.vectors[0][c] + j * this->Box.vectors[1][c] + k * this->Box.vectors[2][c];
        }
        const double length = length2(candidate);
        if (length < best_length)
        {
          best_length = length;
          best = candidate;
        }
      }
    }
  }
  return best;
}

PeriodicBox PeriodicBox::from_cell(double a, double b, double c, double alpha, double beta,
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
