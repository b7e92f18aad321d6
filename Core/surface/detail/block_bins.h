// SPDX-License-Identifier: GPL-3.0-or-later
// Items binned to the blocks of a contour grid (private to MesoLensCore): what each block of
// the molecular surfaces' grid must look at when it samples its field.
#pragma once

#include "surface/detail/contour_tetrahedra.h"

#include "mesolens/common/parallel_for.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <vector>

namespace mesolens {

/// Per block of a ContourGrid, the items whose box meets the box of its points (compressed
/// rows, each block's items in increasing order).
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
    const std::size_t blocks = grid.block_count();
    this->start_.assign(blocks + 1, 0);
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
    for (std::size_t k = 0; k < count; ++k)
    {
      if (binned[k])
      {
        this->for_blocks(grid, ranges[k], [&](std::size_t block) { ++this->start_[block + 1]; });
      }
    }
    for (std::size_t b = 0; b < blocks; ++b)
    {
      this->start_[b + 1] += this->start_[b];
    }
    this->items_.resize(this->start_[blocks]);
    std::vector<std::uint32_t> next(this->start_.begin(), this->start_.end() - 1);
    for (std::size_t k = 0; k < count; ++k)
    {
      if (binned[k])
      {
        this->for_blocks(grid, ranges[k], [&](std::size_t block) {
          this->items_[next[block]++] = static_cast<std::uint32_t>(k);
        });
      }
    }
  }

  const std::uint32_t* begin(std::size_t block) const
  {
    return this->items_.data() + this->start_[block];
  }
  const std::uint32_t* end(std::size_t block) const
  {
    return this->items_.data() + this->start_[block + 1];
  }
  bool empty(std::size_t block) const
  {
    return this->start_[block] == this->start_[block + 1];
  }

private:
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

  std::vector<std::uint32_t> start_{ 0 };
  std::vector<std::uint32_t> items_;
};

} // namespace mesolens
