// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/render/first_occluders.h"

#include "mesolens/common/errors.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace mesolens {

std::vector<std::uint8_t> first_occluders(const CellAtoms& atoms, const std::vector<float>& boxes,
                                          const std::vector<CellInView>& in_view, double padding,
                                          const ViewTransform& view, int width, int height,
                                          int block)
{
  if (block < 1)
  {
    throw InvalidInput("first_occluders: blocks of " + std::to_string(block) + " pixels");
  }
  std::vector<std::uint8_t> chosen(atoms.cell_count(), 0);
  if (width <= 0 || height <= 0)
  {
    return chosen;
  }
  const int columns = (width + block - 1) / block;
  const int rows = (height + block - 1) / block;
  const double b = double(block);
  const auto column_at = [&](double x) {
    return int(std::clamp(std::floor(x), 0.0, double(columns)));
  };
  const auto row_at = [&](double y) { return int(std::clamp(std::floor(y), 0.0, double(rows))); };
  std::vector<std::uint8_t> covered(std::size_t(columns) * std::size_t(rows), 0);
  for (const CellInView& viewed : in_view)
  {
    ScreenFootprint footprint;
    if (viewed.must_draw ||
        !atoms.cell_footprint(viewed.cell, boxes, padding, view, width, height, footprint))
    {
      chosen[viewed.cell] = 1;
      continue;
    }
    // The blocks the footprint covers whole; a footprint smaller than a block stands for the
    // block of its centre. Blocks it only reaches at its edges do not count: box footprints
    // overlap there (and reach beyond their atoms), which would choose nearly every cell.
    int i0 = column_at(std::ceil(footprint.x0 / b));
    int i1 = column_at(std::floor(footprint.x1 / b));
    int j0 = row_at(std::ceil(footprint.y0 / b));
    int j1 = row_at(std::floor(footprint.y1 / b));
    if (i0 >= i1 || j0 >= j1)
    {
      i0 = column_at(0.5 * (footprint.x0 + footprint.x1) / b);
      j0 = row_at(0.5 * (footprint.y0 + footprint.y1) / b);
      if (i0 >= columns || j0 >= rows)
      {
        continue; // off the screen's edge: the test decides
      }
      i1 = i0 + 1;
      j1 = j0 + 1;
    }
    bool uncovered = false;
    for (int j = j0; j < j1 && !uncovered; ++j)
    {
      for (int i = i0; i < i1 && !uncovered; ++i)
      {
        uncovered = covered[std::size_t(j) * std::size_t(columns) + std::size_t(i)] == 0;
      }
    }
    if (!uncovered)
    {
      continue;
    }
    chosen[viewed.cell] = 1;
    for (int j = j0; j < j1; ++j)
    {
      std::fill(covered.begin() + std::ptrdiff_t(j) * columns + i0,
                covered.begin() + std::ptrdiff_t(j) * columns + i1, std::uint8_t(1));
    }
  }
  return chosen;
}

} // namespace mesolens
