// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/render/atom_cells.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

namespace mesolens {
namespace {

struct Grid
{
  std::array<double, 3> origin{};
  double edge = 1;
  std::array<std::uint64_t, 3> size{ 1, 1, 1 };

  std::uint64_t key(const float* p) const
  {
    std::uint64_t index[3];
    for (int d = 0; d < 3; ++d)
    {
      const double cell = std::floor((double(p[d]) - origin[d]) / edge);
      index[d] = static_cast<std::uint64_t>(std::clamp(cell, 0.0, double(size[d] - 1)));
    }
    return index[0] + size[0] * (index[1] + size[1] * index[2]);
  }
};

/// (cell key, atom) of every atom, sorted: the atoms of a cell are adjacent, in input order.
std::vector<std::pair<std::uint64_t, std::uint32_t>> sorted_keys(const float* xyz,
                                                                 std::size_t atom_count,
                                                                 const Grid& grid)
{
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keys(atom_count);
  for (std::size_t i = 0; i < atom_count; ++i)
  {
    keys[i] = { grid.key(xyz + 3 * i), static_cast<std::uint32_t>(i) };
  }
  std::sort(keys.begin(), keys.end());
  return keys;
}

std::size_t occupied_cells(const std::vector<std::pair<std::uint64_t, std::uint32_t>>& keys)
{
  std::size_t count = 0;
  for (std::size_t i = 0; i < keys.size(); ++i)
  {
    count += (i == 0 || keys[i].first != keys[i - 1].first) ? 1 : 0;
  }
  return count;
}

Grid grid_of_edge(const std::array<double, 6>& bounds, double edge)
{
  // At most 2^21 cells along an axis, so that a key fits in 63 bits.
  constexpr double max_cells = double(1 << 21);
  Grid grid;
  double largest = 0;
  for (int d = 0; d < 3; ++d)
  {
    largest = std::max(largest, bounds[3 + d] - bounds[d]);
  }
  grid.edge = std::max(edge, std::max(largest, 1e-30) / (max_cells - 1));
  for (int d = 0; d < 3; ++d)
  {
    grid.origin[d] = bounds[d];
    grid.size[d] =
      static_cast<std::uint64_t>(std::floor((bounds[3 + d] - bounds[d]) / grid.edge)) + 1;
  }
  return grid;
}
} // namespace

AtomCells group_atoms_into_cells(PointSpan<const float> atoms, std::size_t atoms_per_cell)
{
  const float* xyz = atoms.data();
  const std::size_t atom_count = atoms.size();
  AtomCells cells;
  if (atom_count == 0)
  {
    return cells;
  }
  const double target = double(std::max<std::size_t>(atoms_per_cell, 1));
  std::array<double, 6> bounds{ 1e300, 1e300, 1e300, -1e300, -1e300, -1e300 };
  for (std::size_t i = 0; i < atom_count; ++i)
  {
    for (int d = 0; d < 3; ++d)
    {
      bounds[d] = std::min(bounds[d], double(xyz[3 * i + d]));
      bounds[3 + d] = std::max(bounds[3 + d], double(xyz[3 * i + d]));
    }
  }
  // First guess: the atoms fill their box (flat or thin boxes count at 1/1000 of the largest
  // extent); then the edge follows the measured occupancy.
  double largest = 0;
  for (int d = 0; d < 3; ++d)
  {
    largest = std::max(largest, bounds[3 + d] - bounds[d]);
  }
  if (!(largest > 0))
  {
    cells.atom_of_slot.resize(atom_count);
    for (std::size_t i = 0; i < atom_count; ++i)
    {
      cells.atom_of_slot[i] = static_cast<std::uint32_t>(i);
    }
    cells.cell_start = { 0, static_cast<std::uint32_t>(atom_count) };
    return cells;
  }
  double volume = 1;
  for (int d = 0; d < 3; ++d)
  {
    volume *= std::max(bounds[3 + d] - bounds[d], largest * 1e-3);
  }
  double edge = std::cbrt(volume * target / double(atom_count));
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keys;
  for (int iteration = 0; iteration < 6; ++iteration)
  {
    keys = sorted_keys(xyz, atom_count, grid_of_edge(bounds, edge));
    const double mean = double(atom_count) / double(occupied_cells(keys));
    if (mean < 1.5 * target && mean > target / 1.5)
    {
      break;
    }
    edge *= std::cbrt(target / mean);
  }
  cells.atom_of_slot.resize(atom_count);
  for (std::size_t i = 0; i < atom_count; ++i)
  {
    cells.atom_of_slot[i] = keys[i].second;
    if (i == 0 || keys[i].first != keys[i - 1].first)
    {
      cells.cell_start.push_back(static_cast<std::uint32_t>(i));
    }
  }
  cells.cell_start.push_back(static_cast<std::uint32_t>(atom_count));
  return cells;
}

void gather_cell_positions(PointSpan<const float> xyz, const AtomCells& cells,
                           PointSpan<float> slot_xyz, std::vector<float>& boxes,
                           const ParallelFor& parallel_for)
{
  if (xyz.size() != cells.atom_of_slot.size() || slot_xyz.size() != cells.atom_of_slot.size())
  {
    throw InvalidInput("gather_cell_positions: the cells hold " +
                       std::to_string(cells.atom_of_slot.size()) + " atoms; got " +
                       std::to_string(xyz.size()) + " positions and " +
                       std::to_string(slot_xyz.size()) + " slots");
  }
  const std::size_t count = cells.cell_count();
  boxes.assign(6 * count, 0.0f);
  run_parallel(parallel_for, count, [&](std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c)
    {
      float box[6] = { std::numeric_limits<float>::max(),    std::numeric_limits<float>::max(),
                       std::numeric_limits<float>::max(),    std::numeric_limits<float>::lowest(),
                       std::numeric_limits<float>::lowest(), std::numeric_limits<float>::lowest() };
      for (std::uint32_t slot = cells.cell_start[c]; slot < cells.cell_start[c + 1]; ++slot)
      {
        const float* p = xyz[cells.atom_of_slot[slot]];
        float* q = slot_xyz[slot];
        for (int d = 0; d < 3; ++d)
        {
          q[d] = p[d];
          box[d] = std::min(box[d], p[d]);
          box[3 + d] = std::max(box[3 + d], p[d]);
        }
      }
      std::copy(box, box + 6, boxes.begin() + std::ptrdiff_t(6 * c));
    }
  });
}

std::array<double, 6> point_bounds(PointSpan<const float> xyz, const ParallelFor& parallel_for)
{
  constexpr std::size_t block = 65536;
  const std::size_t blocks = (xyz.size() + block - 1) / block;
  std::vector<std::array<float, 6>> partial(blocks);
  run_parallel(parallel_for, blocks, [&](std::size_t begin, std::size_t end) {
    for (std::size_t b = begin; b < end; ++b)
    {
      std::array<float, 6> box = {
        std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest(),
        std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest(),
        std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest()
      };
      for (std::size_t i = b * block; i < std::min(xyz.size(), (b + 1) * block); ++i)
      {
        for (int d = 0; d < 3; ++d)
        {
          box[2 * d] = std::min(box[2 * d], xyz[i][d]);
          box[2 * d + 1] = std::max(box[2 * d + 1], xyz[i][d]);
        }
      }
      partial[b] = box;
    }
  });
  if (blocks == 0)
  {
    return { 1, -1, 1, -1, 1, -1 };
  }
  std::array<double, 6> bounds{};
  std::copy(partial[0].begin(), partial[0].end(), bounds.begin());
  for (const auto& box : partial)
  {
    for (int d = 0; d < 3; ++d)
    {
      bounds[2 * d] = std::min<double>(bounds[2 * d], box[2 * d]);
      bounds[2 * d + 1] = std::max<double>(bounds[2 * d + 1], box[2 * d + 1]);
    }
  }
  return bounds;
}

double total_cell_diagonal(const std::vector<float>& boxes)
{
  double total = 0;
  for (std::size_t c = 0; c + 5 < boxes.size(); c += 6)
  {
    double squared = 0;
    for (int d = 0; d < 3; ++d)
    {
      const double extent = double(boxes[c + 3 + d]) - double(boxes[c + d]);
      squared += extent * extent;
    }
    total += std::sqrt(squared);
  }
  return total;
}

std::vector<CellInView> cells_in_view(const std::vector<float>& boxes, double pad,
                                      const double model_to_clip[16])
{
  const double* m = model_to_clip;
  std::vector<CellInView> cells;
  for (std::size_t c = 0; 6 * c + 5 < boxes.size(); ++c)
  {
    const float* box = boxes.data() + 6 * c;
    // Bits of the clip planes each corner is outside of; a cell is out when all share one.
    unsigned outside_all = 0x3f;
    bool must_draw = false;
    for (int k = 0; k < 8; ++k)
    {
      const double p[3] = { (k & 1) ? box[3] + pad : box[0] - pad,
                            (k & 2) ? box[4] + pad : box[1] - pad,
                            (k & 4) ? box[5] + pad : box[2] - pad };
      double clip[4];
      for (int r = 0; r < 4; ++r)
      {
        clip[r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
      }
      const double w = clip[3];
      unsigned outside = 0;
      for (int d = 0; d < 3; ++d)
      {
        outside |= (clip[d] < -w ? 1u : 0u) << (2 * d);
        outside |= (clip[d] > w ? 1u : 0u) << (2 * d + 1);
      }
      outside_all &= outside;
      if (!(w > 0) || clip[2] < -w)
      {
        must_draw = true; // behind the eye or before the near plane
      }
    }
    if (outside_all != 0)
    {
      continue;
    }
    double centre[4];
    for (int r = 0; r < 4; ++r)
    {
      centre[r] = m[4 * r] * 0.5 * (double(box[0]) + box[3]) +
        m[4 * r + 1] * 0.5 * (double(box[1]) + box[4]) +
        m[4 * r + 2] * 0.5 * (double(box[2]) + box[5]) + m[4 * r + 3];
    }
    const double depth = must_draw ? -1.0 : centre[2] / centre[3];
    cells.push_back({ static_cast<std::uint32_t>(c), depth, must_draw });
  }
  std::stable_sort(cells.begin(), cells.end(),
                   [](const CellInView& a, const CellInView& b) { return a.depth < b.depth; });
  return cells;
}

} // namespace mesolens
