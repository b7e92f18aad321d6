// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/cutaway/surface_sampling.h"

#include "mesolens/common/errors.h"

#include "common/detail/grid_cells.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <unordered_map>

namespace mesolens {

namespace {
using Cell = GridCell;

/// The 27 cells around a cell, its own first: in a dense cloud a point's conflict is usually
/// in its own cell, found with one lookup.
const std::array<std::array<int, 3>, 27> neighbour_offsets = [] {
  std::array<std::array<int, 3>, 27> offsets{};
  int k = 1;
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dz = -1; dz <= 1; ++dz)
        if (dx != 0 || dy != 0 || dz != 0)
          offsets[k++] = { dx, dy, dz };
  return offsets;
}();

/// The points binned in cubic cells of one size, each cell's points contiguous.
class PointGrid
{
public:
  PointGrid(PointSpan<const double> points, double cell_size)
    : Points(points)
    , Size(cell_size)
  {
    const std::size_t n = points.size();
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(n);
    for (std::size_t i = 0; i < n; ++i)
    {
      keyed[i] = { grid_cell_key(this->cell_of(points[i])), static_cast<std::uint32_t>(i) };
    }
    std::sort(keyed.begin(), keyed.end());
    this->Order.resize(n);
    for (std::size_t i = 0; i < n; ++i)
    {
      this->Order[i] = keyed[i].second;
      if (i == 0 || keyed[i].first != keyed[i - 1].first)
      {
        this->Ranges[keyed[i].first] = { i, i };
      }
      this->Ranges[keyed[i].first].second = i + 1;
    }
  }

  Cell cell_of(const double* p) const
  {
    return grid_cell({ p[0], p[1], p[2] }, this->Size);
  }

  /// Calls visit(index, squared distance) for every point within the cells `reach` cells
  /// around the one of `p`.
  template<typename Visit>
  void for_each_near(const double* p, int reach, Visit&& visit) const
  {
    const Cell centre = this->cell_of(p);
    for (int dx = -reach; dx <= reach; ++dx)
      for (int dy = -reach; dy <= reach; ++dy)
        for (int dz = -reach; dz <= reach; ++dz)
        {
          const auto found = this->Ranges.find(grid_cell_key(centre, dx, dy, dz));
          if (found == this->Ranges.end())
          {
            continue;
          }
          for (std::size_t k = found->second.first; k < found->second.second; ++k)
          {
            const std::uint32_t i = this->Order[k];
            const double* q = this->Points[i];
            const double d2 = (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
              (p[2] - q[2]) * (p[2] - q[2]);
            visit(i, d2);
          }
        }
  }

private:
  PointSpan<const double> Points;
  double Size;
  std::vector<std::uint32_t> Order;
  std::unordered_map<std::uint64_t, std::pair<std::size_t, std::size_t>> Ranges;
};

void require_cloud(PointSpan<const double> points, std::size_t minimum)
{
  if (points.size() < minimum)
  {
    throw InvalidInput("the point cloud needs at least " + std::to_string(minimum) +
                       " points; got " + std::to_string(points.size()));
  }
  for (std::size_t i = 0; i < points.value_count(); ++i)
  {
    if (!std::isfinite(points.data()[i]))
    {
      throw InvalidInput("point " + std::to_string(i / 3) + " of the cloud is not finite");
    }
  }
}
} // namespace

double median_spacing(PointSpan<const double> points, std::size_t probes)
{
  require_cloud(points, 2);
  const std::size_t n = points.size();
  // A first cell size from the bounding box as if the points covered its largest face evenly.
  std::array<double, 3> low{}, high{};
  for (int d = 0; d < 3; ++d)
  {
    low[d] = high[d] = points[0][d];
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    for (int d = 0; d < 3; ++d)
    {
      low[d] = std::min(low[d], points[i][d]);
      high[d] = std::max(high[d], points[i][d]);
    }
  }
  std::array<double, 3> extent{ high[0] - low[0], high[1] - low[1], high[2] - low[2] };
  std::sort(extent.begin(), extent.end());
  if (!(extent[2] > 0))
  {
    throw InvalidInput("all " + std::to_string(n) + " points of the cloud coincide");
  }
  // About ten points per cell: few cells to hash, few points to measure.
  const double face = extent[2] * std::max(extent[1], extent[2] * 1e-3);
  const double cell = 3.0 * std::sqrt(face / double(n));
  const PointGrid grid(points, cell);
  const std::size_t step = std::max<std::size_t>(1, n / std::max<std::size_t>(1, probes));
  std::vector<double> nearest;
  for (std::size_t i = 0; i < n; i += step)
  {
    double best = std::numeric_limits<double>::infinity();
    // Widen the search until a neighbour is found and every closer one is surely seen.
    for (int reach = 1; reach <= 8; reach *= 2)
    {
      grid.for_each_near(points[i], reach, [&](std::uint32_t j, double d2) {
        if (j != i && d2 > 0)
        {
          best = std::min(best, d2);
        }
      });
      if (best <= (reach * cell) * (reach * cell))
      {
        break;
      }
    }
    if (std::isfinite(best))
    {
      nearest.push_back(std::sqrt(best));
    }
  }
  if (nearest.empty())
  {
    throw InvalidInput("no two points of the cloud are near each other");
  }
  std::nth_element(nearest.begin(), nearest.begin() + nearest.size() / 2, nearest.end());
  return nearest[nearest.size() / 2];
}

std::vector<double> poisson_disk_subset(PointSpan<const double> points, double spacing)
{
  require_cloud(points, 0);
  if (!(spacing > 0) || !std::isfinite(spacing))
  {
    throw InvalidInput("the Poisson-disk spacing must be positive, not " + std::to_string(spacing));
  }
  // Cells of the spacing: a conflicting sample is in one of the 27 cells around.
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells;
  std::vector<double> kept;
  const double limit = spacing * spacing;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    const double* p = points[i];
    const Cell c = grid_cell({ p[0], p[1], p[2] }, spacing);
    bool free = true;
    for (std::size_t o = 0; o < neighbour_offsets.size() && free; ++o)
    {
      const auto& offset = neighbour_offsets[o];
      const auto found = cells.find(grid_cell_key(c, offset[0], offset[1], offset[2]));
      if (found == cells.end())
      {
        continue;
      }
      for (const std::uint32_t k : found->second)
      {
        const double* q = &kept[3 * k];
        if ((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
              (p[2] - q[2]) * (p[2] - q[2]) <
            limit)
        {
          free = false;
          break;
        }
      }
    }
    if (free)
    {
      cells[grid_cell_key(c)].push_back(static_cast<std::uint32_t>(kept.size() / 3));
      kept.insert(kept.end(), { p[0], p[1], p[2] });
    }
  }
  return kept;
}

std::vector<double> mid_surface_points(PointSpan<const double> points, double spacing,
                                       double radius, int iterations,
                                       const ParallelFor& parallel_for)
{
  require_cloud(points, 1);
  if (!(radius > 0) || !std::isfinite(radius) || iterations < 0)
  {
    throw InvalidInput("the mid-surface radius must be positive and the iterations >= 0");
  }
  std::vector<double> samples = poisson_disk_subset(points, spacing);
  const std::size_t sample_count = samples.size() / 3;
  const PointGrid grid(points, radius);
  const double limit = radius * radius;
  std::vector<std::size_t> neighbours(sample_count, 0);
  run_parallel(parallel_for, sample_count, [&](std::size_t begin, std::size_t end) {
    for (std::size_t s = begin; s < end; ++s)
    {
      double* p = &samples[3 * s];
      for (int step = 0; step <= iterations; ++step)
      {
        double sum[3] = { 0, 0, 0 };
        std::size_t count = 0;
        grid.for_each_near(p, 1, [&](std::uint32_t i, double d2) {
          if (d2 <= limit)
          {
            sum[0] += points[i][0];
            sum[1] += points[i][1];
            sum[2] += points[i][2];
            count += 1;
          }
        });
        if (step == 0)
        {
          neighbours[s] = count;
        }
        for (int d = 0; d < 3 && step < iterations; ++d)
        {
          p[d] = sum[d] / double(count); // count >= 1: the sample itself is a point
        }
      }
    }
  });
  // Stray points (a lipid that left the membrane) have almost no neighbours: drop them, or the
  // reconstruction would span a surface through them.
  std::vector<std::size_t> sorted = neighbours;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const std::size_t fewest = sorted.empty() ? 0 : sorted[sorted.size() / 2] / 10;
  std::vector<double> kept;
  kept.reserve(samples.size());
  for (std::size_t s = 0; s < sample_count; ++s)
  {
    if (neighbours[s] > fewest)
    {
      kept.insert(kept.end(), { samples[3 * s], samples[3 * s + 1], samples[3 * s + 2] });
    }
  }
  return poisson_disk_subset(kept, 0.5 * spacing);
}

} // namespace mesolens
