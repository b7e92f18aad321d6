// SPDX-License-Identifier: GPL-3.0-or-later
// The molecule clouds of the cutaway and structure-mesh fuzz targets.
#pragma once

#include "fuzz_input.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace mesolens_fuzz {

/// A cloud of molecule centres: a flat bilayer, a vesicle's two shells, or scattered points, with
/// some made to coincide or line up.
inline std::vector<double> molecule_cloud(FuzzInput& input)
{
  const std::uint8_t shape = input.byte();
  const std::size_t count = 4 + input.byte() % 120;
  std::vector<double> points;
  for (std::size_t i = 0; i < count; ++i)
  {
    const double u = input.ranged(0, 1), v = input.ranged(0, 1);
    const double leaflet = (i % 2) ? 1.0 : -1.0;
    switch (shape % 3)
    {
      case 0:
        points.insert(points.end(), { 60 * u, 60 * v, 20 * leaflet });
        break;
      case 1: {
        const double theta = std::acos(1 - 2 * u), phi = 2 * M_PI * v, r = 50 + 10 * leaflet;
        points.insert(points.end(),
                      { r * std::sin(theta) * std::cos(phi), r * std::sin(theta) * std::sin(phi),
                        r * std::cos(theta) });
        break;
      }
      default:
        points.insert(points.end(),
                      { input.ranged(-50, 50), input.ranged(-50, 50), input.ranged(-50, 50) });
    }
    const std::uint8_t twist = input.byte();
    if (twist < 8 && i > 0) // onto the previous point
    {
      std::copy_n(&points[3 * (i - 1)], 3, &points[3 * i]);
    }
    else if (twist < 12) // onto one line
    {
      points[3 * i + 1] = points[3 * i + 2] = 0;
    }
  }
  return points;
}

} // namespace mesolens_fuzz
