// SPDX-License-Identifier: GPL-3.0-or-later
// Items binned to the blocks of a contour grid (private to MesoLensCore): what each block of
// the molecular surfaces' grid must look at when it samples its field.
#pragma once

#include "surface/detail/contour_tetrahedra.h"

#include "mesolens/common/parallel_for.h"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace mesolens {

/// Per block of a ContourGrid, the items whose box meets the box of its points (each block's
/// items in increasing order). Only the blocks some item meets are stored, so that a grid
/// whose atoms lie far apart costs what its occupied blocks do, not what its box does.
class BlockBins
{
public:
  BlockBins() = default;

  /// Bins items 0 .. count - 1; `box(k, from, to)` sets item k's box (Å) and returns false to
  /// leave the item out. The boxes are found on the threads of `parallel_for` (empty: the
  /// calling thread), so `box` may be called concurrently for different items.
  template<typename Box>
  BlockBins(const ContourGrid& grid, std::size_t count, Box&& box,
            const ParallelFor& parallel_for = {})
  {
    std::vector<std::array<std::int64_t, 6>> ranges(count);
    std::vector<char> binned(count, 0);
    run_parallel(parallel_for, count, [&](std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k)
      {
        Eigen::Vector3d from, to;
        std::array<std::int64_t, 3> first{}, last{};
        if (box(k, from, to) && grid.blocks_meeting(from, to, first, last))
        {
          binned[k] = 1;
          ranges[k] = { first[0], first[1], first[2], last[0], last[1], last[2] };
        }
      }
    });
    std::size_t pairs = 0;
    for (std::size_t k = 0; k < count; ++k)
    {
      if (binned[k])
      {
        pairs += static_cast<std::size_t>((ranges[k][3] - ranges[k][0] + 1) *
                                          (ranges[k][4] - ranges[k][1] + 1) *
                                          (ranges[k][5] - ranges[k][2] + 1));
      }
    }
    // Counted per block where the grid has few blocks for its items (linear), sorted where it
    // has many (their count would be the cost).
    if (grid.block_count() <= 4 * pairs + 4096)
    {
      this->bin_by_counting(grid, ranges, binned, pairs);
    }
    else
    {
      this->bin_by_sorting(grid, ranges, binned, pairs);
    }
  }

  /// The items of block `block` (an empty range for a block none meets).
  struct Items
  {
    const std::uint32_t* first = nullptr;
    const std::uint32_t* last = nullptr;
    bool empty() const
    {
      return this->first == this->last;
    }
    const std::uint32_t* begin() const
    {
      return this->first;
    }
    const std::uint32_t* end() const
    {
      return this->last;
    }
  };
  Items items(std::size_t block) const
  {
    const auto at = std::lower_bound(this->blocks_.begin(), this->blocks_.end(), block);
    if (at == this->blocks_.end() || *at != block)
    {
      return {};
    }
    const std::size_t k = static_cast<std::size_t>(at - this->blocks_.begin());
    return { this->items_.data() + this->start_[k], this->items_.data() + this->start_[k + 1] };
  }
  /// The blocks some item meets, in increasing order.
  const std::vector<std::size_t>& occupied_blocks() const
  {
    return this->blocks_;
  }

private:
  using Ranges = std::vector<std::array<std::int64_t, 6>>;

  template<typename Visit>
  static void for_blocks(const ContourGrid& grid, const std::array<std::int64_t, 6>& range,
                         Visit&& visit)
  {
    for (std::int64_t z = range[2]; z <= range[5]; ++z)
      for (std::int64_t y = range[1]; y <= range[4]; ++y)
        for (std::int64_t x = range[0]; x <= range[3]; ++x)
        {
          visit(static_cast<std::size_t>(x + grid.blocks[0] * (y + grid.blocks[1] * z)));
        }
  }

  void bin_by_counting(const ContourGrid& grid, const Ranges& ranges,
                       const std::vector<char>& binned, std::size_t pairs)
  {
    const std::size_t blocks = grid.block_count();
    std::vector<std::uint32_t> start(blocks + 1, 0);
    for (std::size_t k = 0; k < ranges.size(); ++k)
    {
      if (binned[k])
      {
        for_blocks(grid, ranges[k], [&](std::size_t block) { ++start[block + 1]; });
      }
    }
    for (std::size_t b = 0; b < blocks; ++b)
    {
      if (start[b + 1] > 0)
      {
        this->blocks_.push_back(b);
      }
      start[b + 1] += start[b];
    }
    this->items_.resize(pairs);
    for (std::size_t k = 0; k < ranges.size(); ++k)
    {
      if (binned[k])
      {
        for_blocks(grid, ranges[k], [&](std::size_t block) {
          this->items_[start[block]++] = static_cast<std::uint32_t>(k);
        });
      }
    }
    // start[b] now ends block b: the occupied blocks' starts are their predecessors' ends.
    this->start_.assign(1, 0);
    for (const std::size_t block : this->blocks_)
    {
      this->start_.push_back(start[block]);
    }
  }

  void bin_by_sorting(const ContourGrid& grid, const Ranges& ranges,
                      const std::vector<char>& binned, std::size_t pairs)
  {
    std::vector<std::pair<std::size_t, std::uint32_t>> entries;
    entries.reserve(pairs);
    for (std::size_t k = 0; k < ranges.size(); ++k)
    {
      if (binned[k])
      {
        for_blocks(grid, ranges[k], [&](std::size_t block) {
          entries.emplace_back(block, static_cast<std::uint32_t>(k));
        });
      }
    }
    std::sort(entries.begin(), entries.end());
    this->items_.resize(entries.size());
    this->start_.assign(1, 0);
    for (std::size_t e = 0; e < entries.size(); ++e)
    {
      if (e == 0 || entries[e].first != entries[e - 1].first)
      {
        if (e > 0)
        {
          this->start_.push_back(static_cast<std::uint32_t>(e));
        }
        this->blocks_.push_back(entries[e].first);
      }
      this->items_[e] = entries[e].second;
    }
    if (!entries.empty())
    {
      this->start_.push_back(static_cast<std::uint32_t>(entries.size()));
    }
  }

  std::vector<std::size_t> blocks_;       ///< occupied, increasing
  std::vector<std::uint32_t> start_{ 0 }; ///< per occupied block and one past, its first item
  std::vector<std::uint32_t> items_;
};

} // namespace mesolens
