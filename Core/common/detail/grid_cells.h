// SPDX-License-Identifier: GPL-3.0-or-later
// Cells of a uniform grid as hash keys (private to MesoLensCore): the neighbour searches of
// the point-cloud sampling, DSSP and the sphere-union area bin their points this way.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

namespace mesolens {

using GridCell = std::array<std::int64_t, 3>;

/// floor() and ceil() to an int, for values well within its range, without a library call
/// (hot loops over grid points: the library's rounding is a call without SSE4.1).
inline int floor_to_int(double x)
{
  const int truncated = static_cast<int>(x);
  return truncated - (x < truncated ? 1 : 0);
}
inline int ceil_to_int(double x)
{
  const int truncated = static_cast<int>(x);
  return truncated + (x > truncated ? 1 : 0);
}

/// The cell of edge `size` holding `p` (finite). Cells past +-2^62 per axis (points 1e18 cells
/// away, which only hostile input has) are clamped there: converting them would be undefined,
/// and a shared far cell only adds candidates that the searches' distance tests drop.
inline GridCell grid_cell(const std::array<double, 3>& p, double size)
{
  constexpr double limit = 4.611686018427387904e18; // 2^62
  const auto axis = [size](double x) {
    const double cell = std::floor(x / size);
    return static_cast<std::int64_t>(cell < -limit ? -limit : (cell > limit ? limit : cell));
  };
  return { axis(p[0]), axis(p[1]), axis(p[2]) };
}

/// A cell as one 64-bit key: 21 bits per axis, cells up to +-1e6 per axis (far more than any
/// molecule or cloud here needs). `dx`, `dy`, `dz` offset the cell (its neighbours).
inline std::uint64_t grid_cell_key(const GridCell& c, int dx = 0, int dy = 0, int dz = 0)
{
  const auto part = [](std::int64_t v) {
    return static_cast<std::uint64_t>(v + (1 << 20)) & 0x1fffff;
  };
  return part(c[0] + dx) | (part(c[1] + dy) << 21) | (part(c[2] + dz) << 42);
}

} // namespace mesolens
