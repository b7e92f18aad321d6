// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/mapping/chart_lattice.h"

#include "mesolens/common/errors.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

namespace mesolens {

namespace {
/// Points and counter-clockwise triangles of an equilateral lattice covering [low, high] with a
/// vertex at its centre: rows of `width` points, odd rows half an edge to the right.
struct Lattice
{
  std::vector<std::array<double, 2>> points;
  std::vector<std::array<std::size_t, 3>> triangles;
};

Lattice equilateral_lattice(const std::array<double, 2>& low, const std::array<double, 2>& high,
                            double edge)
{
  const double row_height = edge * std::sqrt(3.0) / 2;
  const std::array<double, 2> centre{ (low[0] + high[0]) / 2, (low[1] + high[1]) / 2 };
  const long half_columns = long(std::ceil((high[0] - low[0]) / (2 * edge))) + 1;
  const long half_rows = long(std::ceil((high[1] - low[1]) / (2 * row_height))) + 1;
  const auto width = std::size_t(2 * half_columns + 1);
  const auto height = std::size_t(2 * half_rows + 1);
  if (double(width) * double(height) > 4e6)
  {
    throw InvalidInput("a lattice of edge " + std::to_string(edge) + " needs " +
                       std::to_string(width * height) +
                       " points to cover the disk (at most 4 million): choose a longer edge");
  }
  auto shifted = [half_rows](std::size_t row) { return (long(row) - half_rows) % 2 != 0; };
  Lattice lattice;
  lattice.points.reserve(width * height);
  for (std::size_t row = 0; row < height; ++row)
  {
    for (std::size_t column = 0; column < width; ++column)
    {
      const double x = double(long(column) - half_columns) * edge + (shifted(row) ? edge / 2 : 0);
      const double y = double(long(row) - half_rows) * row_height;
      lattice.points.push_back({ x + centre[0], y + centre[1] });
    }
  }
  // Each quad of neighbouring rows splits into two triangles along the diagonal that the rows'
  // shift makes short: all first triangles, then all second ones.
  for (const bool second : { false, true })
  {
    for (std::size_t row = 0; row + 1 < height; ++row)
    {
      const bool up = shifted(row + 1); // the row above sits to the right of this one
      for (std::size_t column = 0; column + 1 < width; ++column)
      {
        const std::size_t here = row * width + column, right = here + 1, above = here + width,
                          above_right = above + 1;
        if (!second)
        {
          lattice.triangles.push_back(up ? std::array<std::size_t, 3>{ here, right, above }
                                         : std::array<std::size_t, 3>{ here, above_right, above });
        }
        else
        {
          lattice.triangles.push_back(up ? std::array<std::size_t, 3>{ right, above_right, above }
                                         : std::array<std::size_t, 3>{ here, right, above_right });
        }
      }
    }
  }
  return lattice;
}
} // namespace

TriangleMesh chart_lattice(const SurfaceChart& chart, const std::vector<double>& uv, double edge)
{
  if (!(edge > 0) || !std::isfinite(edge))
  {
    throw InvalidInput("the lattice edge must be positive, not " + std::to_string(edge));
  }
  TriangleMesh result;
  if (uv.size() < 2)
  {
    return result;
  }
  std::array<double, 2> low{ std::numeric_limits<double>::max(),
                             std::numeric_limits<double>::max() };
  std::array<double, 2> high{ std::numeric_limits<double>::lowest(),
                              std::numeric_limits<double>::lowest() };
  for (std::size_t i = 0; i + 1 < uv.size(); i += 2)
  {
    for (std::size_t d = 0; d < 2; ++d)
    {
      low[d] = std::min(low[d], uv[i + d]);
      high[d] = std::max(high[d], uv[i + d]);
    }
  }
  const Lattice lattice = equilateral_lattice(low, high, edge);

  // Where each lattice point lies on the disk (NaN off it).
  std::vector<std::array<double, 3>> on_disk(lattice.points.size());
  std::vector<bool> valid(lattice.points.size());
  for (std::size_t p = 0; p < lattice.points.size(); ++p)
  {
    SurfacePoint point;
    valid[p] = chart.locate(lattice.points[p][0], lattice.points[p][1], point);
    on_disk[p] = point.position;
  }
  // The triangles wholly on the disk, their vertices renumbered in lattice order.
  std::vector<std::int64_t> renumbered(lattice.points.size(), -1);
  std::vector<std::array<std::size_t, 3>> kept;
  for (const auto& triangle : lattice.triangles)
  {
    if (valid[triangle[0]] && valid[triangle[1]] && valid[triangle[2]])
    {
      kept.push_back(triangle);
      for (const std::size_t corner : triangle)
      {
        renumbered[corner] = 0;
      }
    }
  }
  std::int64_t next = 0;
  for (std::size_t p = 0; p < lattice.points.size(); ++p)
  {
    if (renumbered[p] >= 0)
    {
      renumbered[p] = next++;
      result.points.insert(result.points.end(), on_disk[p].begin(), on_disk[p].end());
    }
  }
  for (const auto& triangle : kept)
  {
    for (const std::size_t corner : triangle)
    {
      result.triangles.push_back(renumbered[corner]);
    }
  }
  return result;
}

} // namespace mesolens
