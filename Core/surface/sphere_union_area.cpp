// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/surface/sphere_union_area.h"

#include "surface/detail/sas_boundary.h"

#include <Eigen/Core>

namespace mesolens {

SphereUnionArea sphere_union_area(PointSpan<const double> centres, const std::vector<double>& radii,
                                  const ParallelFor& parallel_for)
{
  const SasBoundary boundary = sas_boundary(centres, radii, false, parallel_for);
  SphereUnionArea result;
  result.per_sphere = boundary.area;
  for (std::size_t i = 0; i < centres.size(); ++i)
  {
    const Eigen::Vector3d c(centres[i][0], centres[i][1], centres[i][2]);
    // The divergence theorem over the exposed patch: (1/3) of x . n dA, x = c + r u.
    result.total += boundary.area[i];
    result.volume += (radii[i] * boundary.area[i] + c.dot(boundary.normal_integral[i])) / 3.0;
  }
  return result;
}

} // namespace mesolens
