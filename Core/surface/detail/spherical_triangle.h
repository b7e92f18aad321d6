// SPDX-License-Identifier: GPL-3.0-or-later
// A triangle on the unit sphere, prepared for the range of u . e over it (private to
// MesoLensCore): how far a concave patch reaches in a direction.
#pragma once

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <utility>

namespace mesolens {

/// A spherical triangle (counter-clockwise unit corners, each edge shorter than a half circle),
/// prepared for the range of u . e over it, for many directions e.
class SphericalTriangle
{
public:
  SphericalTriangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c)
    : corner_{ a, b, c }
  {
    for (int k = 0; k < 3; ++k)
    {
      const Eigen::Vector3d& from = this->corner_[k];
      const Eigen::Vector3d& to = this->corner_[(k + 1) % 3];
      this->normal_[k] = from.cross(to).normalized();
      this->after_[k] = this->normal_[k].cross(from);
      this->before_[k] = to.cross(this->normal_[k]);
    }
  }

  /// The smallest and largest u . e over the triangle (e a unit vector): at +-e itself when
  /// inside, else on an edge's great circle (where the plane through e and the edge's normal
  /// meets the edge) or at a corner. Both are 1-Lipschitz in e.
  std::pair<double, double> dot_range(const Eigen::Vector3d& e) const
  {
    double low =
      std::min({ e.dot(this->corner_[0]), e.dot(this->corner_[1]), e.dot(this->corner_[2]) });
    double high =
      std::max({ e.dot(this->corner_[0]), e.dot(this->corner_[1]), e.dot(this->corner_[2]) });
    int above = 0, below = 0;
    for (int k = 0; k < 3; ++k)
    {
      const double across = e.dot(this->normal_[k]);
      above += across >= 0;
      below += across <= 0;
      // The nearest point of the edge's great circle to e, and its dot product: within the
      // edge when on the inner side of both ends.
      const double length = std::sqrt(std::max(0.0, 1.0 - across * across));
      const double after = e.dot(this->after_[k]), before = e.dot(this->before_[k]);
      if (after >= 0 && before >= 0)
      {
        high = std::max(high, length);
      }
      if (after <= 0 && before <= 0)
      {
        low = std::min(low, -length);
      }
    }
    return { below == 3 ? -1.0 : low, above == 3 ? 1.0 : high };
  }

private:
  Eigen::Vector3d corner_[3], normal_[3], after_[3], before_[3];
};

} // namespace mesolens
