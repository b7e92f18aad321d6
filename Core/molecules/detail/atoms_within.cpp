// SPDX-License-Identifier: GPL-3.0-or-later
#include "molecules/detail/atoms_within.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

namespace mesolens {
namespace detail {

namespace {

bool finite_point(const float* p)
{
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

/// The reference atoms sorted into the cells of a dense grid over their bounding box; each
/// cell's atoms are consecutive in `Points` (x, y, z), so a query reads contiguous memory.
class ReferenceGrid
{
public:
  ReferenceGrid(PointSpan<const float> positions, const std::vector<std::size_t>& atoms,
                double distance)
  {
    for (int d = 0; d < 3; ++d)
    {
      this->Low[d] = std::numeric_limits<double>::max();
      double high = std::numeric_limits<double>::lowest();
      for (std::size_t i : atoms)
      {
        this->Low[d] = std::min(this->Low[d], double(positions[i][d]));
        high = std::max(high, double(positions[i][d]));
      }
      this->Extent[d] = high - this->Low[d];
    }
    this->choose_cells(distance, atoms.size());
    this->sort(positions, atoms);
  }

  /// True when a reference atom is at most `distance` from `p`.
  bool near(const float* p, double distance) const
  {
    std::array<std::int64_t, 3> first{};
    std::array<std::int64_t, 3> last{};
    for (int d = 0; d < 3; ++d)
    {
      const double low = std::floor((p[d] - distance - this->Low[d]) / this->Cell);
      const double high = std::floor((p[d] + distance - this->Low[d]) / this->Cell);
      if (high < 0.0 || low > double(this->Dims[d] - 1))
      {
        return false;
      }
      first[d] = low < 0.0 ? 0 : std::int64_t(low);
      last[d] = std::min(std::int64_t(high), this->Dims[d] - 1);
    }
    const double squared = distance * distance;
    for (std::int64_t z = first[2]; z <= last[2]; ++z)
    {
      for (std::int64_t y = first[1]; y <= last[1]; ++y)
      {
        const std::size_t row = std::size_t((z * this->Dims[1] + y) * this->Dims[0]);
        const std::size_t begin = this->Start[row + std::size_t(first[0])];
        const std::size_t end = this->Start[row + std::size_t(last[0]) + 1];
        for (std::size_t k = begin; k < end; ++k)
        {
          const double dx = double(this->Points[3 * k]) - p[0];
          const double dy = double(this->Points[3 * k + 1]) - p[1];
          const double dz = double(this->Points[3 * k + 2]) - p[2];
          if (dx * dx + dy * dy + dz * dz <= squared)
          {
            return true;
          }
        }
      }
    }
    return false;
  }

private:
  /// Cells at least `distance` wide (a query then spans at most 2 per axis), grown until there
  /// are at most 8 per reference atom, so a sparse reference costs little memory.
  void choose_cells(double distance, std::size_t count)
  {
    const double max_cells = 8.0 * double(count) + 64.0;
    this->Cell = std::max(distance, 1e-3);
    const double volume = (this->Extent[0] + this->Cell) * (this->Extent[1] + this->Cell) *
      (this->Extent[2] + this->Cell);
    this->Cell = std::max(this->Cell, std::cbrt(volume / max_cells));
    const auto cells_along = [this](int d) { return std::floor(this->Extent[d] / this->Cell) + 1; };
    while (cells_along(0) * cells_along(1) * cells_along(2) > max_cells)
    {
      this->Cell *= 1.25;
    }
    for (int d = 0; d < 3; ++d)
    {
      this->Dims[d] = std::int64_t(cells_along(d));
    }
  }

  std::size_t cell_of(const float* p) const
  {
    std::array<std::int64_t, 3> index{};
    for (int d = 0; d < 3; ++d)
    {
      const double cell = std::floor((p[d] - this->Low[d]) / this->Cell);
      index[d] = std::min(std::int64_t(std::max(cell, 0.0)), this->Dims[d] - 1);
    }
    return std::size_t((index[2] * this->Dims[1] + index[1]) * this->Dims[0] + index[0]);
  }

  /// Counting sort of the reference atoms by cell.
  void sort(PointSpan<const float> positions, const std::vector<std::size_t>& atoms)
  {
    const std::size_t cells = std::size_t(this->Dims[0] * this->Dims[1] * this->Dims[2]);
    this->Start.assign(cells + 1, 0);
    std::vector<std::size_t> cell_of_atom(atoms.size());
    for (std::size_t k = 0; k < atoms.size(); ++k)
    {
      cell_of_atom[k] = this->cell_of(positions[atoms[k]]);
      ++this->Start[cell_of_atom[k] + 1];
    }
    for (std::size_t c = 0; c < cells; ++c)
    {
      this->Start[c + 1] += this->Start[c];
    }
    std::vector<std::size_t> fill(this->Start.begin(), this->Start.end() - 1);
    this->Points.resize(3 * atoms.size());
    for (std::size_t k = 0; k < atoms.size(); ++k)
    {
      const std::size_t slot = fill[cell_of_atom[k]]++;
      std::copy_n(positions[atoms[k]], 3, this->Points.begin() + std::ptrdiff_t(3 * slot));
    }
  }

  std::array<double, 3> Low{};
  std::array<double, 3> Extent{};
  std::array<std::int64_t, 3> Dims{};
  double Cell = 1.0;
  std::vector<std::size_t> Start;
  std::vector<float> Points;
};

} // namespace

std::vector<std::uint8_t> atoms_within(PointSpan<const float> positions,
                                       const std::vector<std::uint8_t>& reference, double distance,
                                       const ParallelFor& parallel_for)
{
  const std::size_t count = positions.size();
  std::vector<std::uint8_t> result(count, 0);
  std::vector<std::size_t> atoms;
  for (std::size_t i = 0; i < count; ++i)
  {
    if (reference[i] && finite_point(positions[i]))
    {
      atoms.push_back(i);
    }
  }
  if (atoms.empty())
  {
    return result;
  }
  const ReferenceGrid grid(positions, atoms, distance);
  run_parallel(parallel_for, count, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
    {
      const float* p = positions[i];
      result[i] = finite_point(p) && (reference[i] || grid.near(p, distance)) ? 1 : 0;
    }
  });
  return result;
}

} // namespace detail
} // namespace mesolens
