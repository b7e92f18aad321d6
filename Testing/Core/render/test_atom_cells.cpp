// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/render/atom_cells.h"

#include "mesolens_test_threads.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <random>

namespace {
/// A simple cubic lattice of side^3 atoms, spacing 1, in a shuffled order.
std::vector<float> shuffled_lattice(int side, unsigned seed)
{
  std::vector<int> order(std::size_t(side * side * side));
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937(seed));
  std::vector<float> xyz;
  for (int i : order)
  {
    xyz.insert(xyz.end(), { float(i % side), float(i / side % side), float(i / (side * side)) });
  }
  return xyz;
}

/// Row-major orthographic projection of the box [-1, 1]^2 x depth [near, far] seen down -z
/// from the origin (view z = -depth).
std::array<double, 16> orthographic(double near, double far)
{
  return {
    1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -2 / (far - near), -(far + near) / (far - near), 0, 0, 0, 1
  };
}
} // namespace

TEST(AtomCells, EveryAtomHasOneSlotAndCellsAreCompact)
{
  const std::vector<float> xyz = shuffled_lattice(40, 7); // 64000 atoms
  const std::size_t n = xyz.size() / 3;
  const auto cells = mesolens::group_atoms_into_cells(xyz, 500);
  ASSERT_EQ(cells.atom_of_slot.size(), n);
  std::vector<std::uint32_t> sorted = cells.atom_of_slot;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t i = 0; i < n; ++i)
  {
    ASSERT_EQ(sorted[i], i);
  }
  ASSERT_GE(cells.cell_count(), 64u);
  ASSERT_LE(cells.cell_count(), 256u);
  EXPECT_EQ(cells.cell_start.front(), 0u);
  EXPECT_EQ(cells.cell_start.back(), n);

  std::vector<float> slot_xyz(xyz.size());
  std::vector<float> boxes;
  mesolens::gather_cell_positions(xyz, cells, slot_xyz, boxes);
  ASSERT_EQ(boxes.size(), 6 * cells.cell_count());
  double largest_extent = 0;
  for (std::size_t c = 0; c < cells.cell_count(); ++c)
  {
    ASSERT_LT(cells.cell_start[c], cells.cell_start[c + 1]); // no empty cells
    for (std::uint32_t slot = cells.cell_start[c]; slot < cells.cell_start[c + 1]; ++slot)
    {
      for (int d = 0; d < 3; ++d)
      {
        const float v = slot_xyz[3 * slot + d];
        ASSERT_EQ(v, xyz[3 * cells.atom_of_slot[slot] + d]);
        ASSERT_GE(v, boxes[6 * c + d]);
        ASSERT_LE(v, boxes[6 * c + 3 + d]);
      }
      // Input order within a cell.
      if (slot > cells.cell_start[c])
      {
        ASSERT_LT(cells.atom_of_slot[slot - 1], cells.atom_of_slot[slot]);
      }
    }
    for (int d = 0; d < 3; ++d)
    {
      largest_extent = std::max(largest_extent, double(boxes[6 * c + 3 + d] - boxes[6 * c + d]));
    }
  }
  // About 500 atoms per cell at unit spacing: cells about 8 atoms wide, never the whole lattice.
  EXPECT_LT(largest_extent, 12.0);
  EXPECT_NEAR(
    mesolens::total_cell_diagonal(boxes),
    [&] {
      double total = 0;
      for (std::size_t c = 0; c < boxes.size(); c += 6)
      {
        total += std::hypot(double(boxes[c + 3] - boxes[c]), double(boxes[c + 4] - boxes[c + 1]),
                            double(boxes[c + 5] - boxes[c + 2]));
      }
      return total;
    }(),
    1e-3);

  // Same input, same grouping.
  const auto again = mesolens::group_atoms_into_cells(xyz, 500);
  EXPECT_EQ(again.atom_of_slot, cells.atom_of_slot);
  EXPECT_EQ(again.cell_start, cells.cell_start);
}

TEST(AtomCells, SparseSheetKeepsTheCellSize)
{
  // 20000 atoms on a thin spherical shell of radius 100: its box is mostly empty.
  std::mt19937 random(3);
  std::normal_distribution<float> normal;
  std::vector<float> xyz;
  for (int i = 0; i < 20000; ++i)
  {
    float p[3] = { normal(random), normal(random), normal(random) };
    const float length = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    for (float v : p)
    {
      xyz.push_back(100.0f * v / length);
    }
  }
  const auto cells = mesolens::group_atoms_into_cells(xyz, 200);
  const double mean = 20000.0 / double(cells.cell_count());
  EXPECT_GT(mean, 200.0 / 1.6);
  EXPECT_LT(mean, 200.0 * 1.6);
}

TEST(AtomCells, DegenerateInputs)
{
  EXPECT_EQ(mesolens::group_atoms_into_cells({}, 100).cell_count(), 0u);
  const std::vector<float> same(30, 2.5f); // ten coincident atoms
  const auto one = mesolens::group_atoms_into_cells(same, 4);
  ASSERT_EQ(one.cell_count(), 1u);
  EXPECT_EQ(one.atom_of_slot.size(), 10u);
  // Positions or slots of another count than the cells' atoms are refused.
  std::vector<float> slots(30);
  std::vector<float> boxes;
  const std::vector<float> nine(27, 2.5f);
  EXPECT_THROW(mesolens::gather_cell_positions(nine, one, slots, boxes), mesolens::InvalidInput);
  std::vector<float> eleven_slots(33);
  EXPECT_THROW(mesolens::gather_cell_positions(same, one, eleven_slots, boxes),
               mesolens::InvalidInput);
  // A line of atoms (flat in two axes) and a cell size of 1.
  std::vector<float> line;
  for (int i = 0; i < 50; ++i)
  {
    line.insert(line.end(), { float(i), 0.0f, 0.0f });
  }
  const auto singles = mesolens::group_atoms_into_cells(line, 1);
  EXPECT_GE(singles.cell_count(), 34u);
  EXPECT_EQ(singles.cell_start.back(), 50u);
}

TEST(AtomCells, ViewKeepsCellsInTheVolumeNearestFirst)
{
  // Three unit boxes along the view axis at depths 2, 5 and 8, one to the side, one behind
  // the eye reaching into the view volume, one across the near plane.
  const std::vector<float> boxes = {
    -0.5f, -0.5f, -8.5f, 0.5f, 0.5f, -7.5f, // far
    -0.5f, -0.5f, -2.5f, 0.5f, 0.5f, -1.5f, // near
    -0.5f, -0.5f, -5.5f, 0.5f, 0.5f, -4.5f, // middle
    3.0f,  -0.5f, -5.5f, 4.0f, 0.5f, -4.5f, // outside x > 1
    -0.5f, -0.5f, 20.0f, 0.5f, 0.5f, 21.0f, // behind the far... beyond the eye side
    -0.5f, -0.5f, -1.2f, 0.5f, 0.5f, -0.8f, // across the near plane at depth 1
  };
  const auto m = orthographic(1.0, 10.0);
  const auto in_view = mesolens::cells_in_view(boxes, 0.0, m.data());
  ASSERT_EQ(in_view.size(), 4u);
  EXPECT_EQ(in_view[0].cell, 5u);
  EXPECT_TRUE(in_view[0].must_draw);
  EXPECT_EQ(in_view[1].cell, 1u);
  EXPECT_EQ(in_view[2].cell, 2u);
  EXPECT_EQ(in_view[3].cell, 0u);
  EXPECT_FALSE(in_view[1].must_draw);
  EXPECT_LT(in_view[1].depth, in_view[2].depth);
  // The padding brings the side box in: its nearest x is 3 - 2.5 = 0.5.
  const auto padded = mesolens::cells_in_view(boxes, 2.5, m.data());
  EXPECT_EQ(padded.size(), 5u);
}

TEST(AtomCells, PointBoundsTakeEveryPointWhateverTheThreads)
{
  const std::vector<float> xyz = shuffled_lattice(40, 7); // 64000 atoms, 40 per side
  const auto bounds = mesolens::point_bounds(xyz);
  std::array<double, 6> expected = { 1e300, -1e300, 1e300, -1e300, 1e300, -1e300 };
  for (std::size_t i = 0; i < xyz.size(); ++i)
  {
    const std::size_t d = i % 3;
    expected[2 * d] = std::min<double>(expected[2 * d], xyz[i]);
    expected[2 * d + 1] = std::max<double>(expected[2 * d + 1], xyz[i]);
  }
  EXPECT_EQ(bounds, expected);
  EXPECT_EQ(mesolens::point_bounds(xyz, mesolens_test::two_threads()), expected);
  EXPECT_EQ(mesolens::point_bounds({}), (std::array<double, 6>{ 1, -1, 1, -1, 1, -1 }));
}
