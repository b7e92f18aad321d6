// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/bond_perception.h"

#include "mesolens/elements.h"
#include "mesolens/errors.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <vector>

namespace mesolens
{

namespace
{

/// Atoms binned in a uniform grid (counting sort): cell c holds sorted_atoms[start[c]..start[c+1]).
class UniformGrid
{
public:
  UniformGrid(const float* positions, std::size_t count, double cell_size)
  {
    std::array<double, 3> low{ std::numeric_limits<double>::max(),
      std::numeric_limits<double>::max(), std::numeric_limits<double>::max() };
    std::array<double, 3> high{ -low[0], -low[1], -low[2] };
    for (std::size_t i = 0; i < count; ++i)
    {
      if (!finite_atom(positions, i))
      {
        continue;
      }
      for (int d = 0; d < 3; ++d)
      {
        low[d] = std::min(low[d], double(positions[3 * i + d]));
        high[d] = std::max(high[d], double(positions[3 * i + d]));
      }
    }
    if (low[0] > high[0])
    {
      low = high = { 0, 0, 0 };
    }
    // Keep the grid at most a few cells per atom so sparse inputs (a vesicle) stay O(n) in
    // memory: grow the cell until the cell count is below 8 n + 64.
    const double max_cells = 8.0 * double(count) + 64.0;
    this->Cell = std::max(cell_size, 1e-3);
    for (;;)
    {
      double cells = 1;
      for (int d = 0; d < 3; ++d)
      {
        this->Dims[d] = std::int64_t((high[d] - low[d]) / this->Cell) + 1;
        cells *= double(this->Dims[d]);
      }
      if (cells <= max_cells)
      {
        break;
      }
      this->Cell *= 1.5;
    }
    this->Low = low;
    const std::size_t cell_count = std::size_t(this->Dims[0] * this->Dims[1] * this->Dims[2]);
    this->Start.assign(cell_count + 1, 0);
    this->CellOfAtom.assign(count, -1);
    for (std::size_t i = 0; i < count; ++i)
    {
      if (finite_atom(positions, i))
      {
        this->CellOfAtom[i] = this->cell_index(positions + 3 * i);
        ++this->Start[std::size_t(this->CellOfAtom[i]) + 1];
      }
    }
    std::partial_sum(this->Start.begin(), this->Start.end(), this->Start.begin());
    this->SortedAtoms.resize(this->Start.back());
    std::vector<std::size_t> fill(this->Start.begin(), this->Start.end() - 1);
    for (std::size_t i = 0; i < count; ++i)
    {
      if (this->CellOfAtom[i] >= 0)
      {
        this->SortedAtoms[fill[std::size_t(this->CellOfAtom[i])]++] = std::uint32_t(i);
      }
    }
  }

  static bool finite_atom(const float* positions, std::size_t i)
  {
    return std::isfinite(positions[3 * i]) && std::isfinite(positions[3 * i + 1]) &&
      std::isfinite(positions[3 * i + 2]);
  }

  std::int64_t cell_index(const float* p) const
  {
    std::array<std::int64_t, 3> c{};
    for (int d = 0; d < 3; ++d)
    {
      c[d] = std::clamp<std::int64_t>(
        std::int64_t((double(p[d]) - this->Low[d]) / this->Cell), 0, this->Dims[d] - 1);
    }
    return (c[2] * this->Dims[1] + c[1]) * this->Dims[0] + c[0];
  }

  /// Calls visit(j) for every atom in the 27 cells around atom i.
  template <typename Visit>
  void for_each_neighbour_candidate(std::size_t i, Visit&& visit) const
  {
    const std::int64_t cell = this->CellOfAtom[i];
    if (cell < 0)
    {
      return;
    }
    const std::int64_t cx = cell % this->Dims[0];
    const std::int64_t cy = (cell / this->Dims[0]) % this->Dims[1];
    const std::int64_t cz = cell / (this->Dims[0] * this->Dims[1]);
    for (std::int64_t z = std::max<std::int64_t>(cz - 1, 0);
         z <= std::min(cz + 1, this->Dims[2] - 1); ++z)
    {
      for (std::int64_t y = std::max<std::int64_t>(cy - 1, 0);
           y <= std::min(cy + 1, this->Dims[1] - 1); ++y)
      {
        for (std::int64_t x = std::max<std::int64_t>(cx - 1, 0);
             x <= std::min(cx + 1, this->Dims[0] - 1); ++x)
        {
          const std::size_t c = std::size_t((z * this->Dims[1] + y) * this->Dims[0] + x);
          for (std::size_t k = this->Start[c]; k < this->Start[c + 1]; ++k)
          {
            visit(this->SortedAtoms[k]);
          }
        }
      }
    }
  }

private:
  std::array<double, 3> Low{};
  std::array<std::int64_t, 3> Dims{ 1, 1, 1 };
  double Cell = 1;
  std::vector<std::size_t> Start;
  std::vector<std::uint32_t> SortedAtoms;
  std::vector<std::int64_t> CellOfAtom;
};

void check_input(const BondPerceptionInput& input)
{
  if (input.atom_count > 0 &&
    (!input.positions || !input.atomic_numbers || !input.molecule_ids))
  {
    throw InvalidInput("bond perception needs positions, atomic numbers and molecule ids");
  }
  if (input.atom_count >= std::numeric_limits<std::uint32_t>::max())
  {
    throw InvalidInput("bond perception supports at most 2^32 - 1 atoms");
  }
}

double squared_distance(const float* positions, std::size_t i, std::size_t j)
{
  double sum = 0;
  for (int d = 0; d < 3; ++d)
  {
    const double delta = double(positions[3 * i + d]) - double(positions[3 * j + d]);
    sum += delta * delta;
  }
  return sum;
}

} // namespace

std::vector<Bond> perceive_bonds(
  const BondPerceptionInput& input, const BondPerceptionParams& params)
{
  check_input(input);
  if (!(params.tolerance >= 0.0f && params.tolerance <= 1.0f))
  {
    throw InvalidInput("bond tolerance must lie in [0, 1] Å, got " +
      std::to_string(params.tolerance));
  }
  if (!(params.bead_cutoff > 0.0f && params.bead_cutoff <= 10.0f))
  {
    throw InvalidInput("bead cutoff must lie in (0, 10] Å, got " +
      std::to_string(params.bead_cutoff));
  }
  const std::size_t n = input.atom_count;
  std::vector<float> radius(n);
  float largest_radius = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    radius[i] = covalent_radius(input.atomic_numbers[i]);
    largest_radius = std::max(largest_radius, radius[i]);
  }
  const double reach = params.coarse_grained
    ? double(params.bead_cutoff)
    : 2.0 * double(largest_radius) + double(params.tolerance);
  const UniformGrid grid(input.positions, n, reach);
  const double min2 = double(params.minimum_distance) * double(params.minimum_distance);

  std::vector<Bond> bonds;
  std::vector<std::uint32_t> partners;
  for (std::size_t i = 0; i < n; ++i)
  {
    partners.clear();
    grid.for_each_neighbour_candidate(i, [&](std::uint32_t j) {
      if (j <= i || input.molecule_ids[j] != input.molecule_ids[i])
      {
        return;
      }
      if (input.alt_locs && input.alt_locs[i] != ' ' && input.alt_locs[j] != ' ' &&
        input.alt_locs[i] != input.alt_locs[j])
      {
        return;
      }
      const double limit = params.coarse_grained
        ? double(params.bead_cutoff)
        : double(radius[i]) + double(radius[j]) + double(params.tolerance);
      const double d2 = squared_distance(input.positions, i, j);
      if (d2 < limit * limit && d2 >= min2)
      {
        partners.push_back(j);
      }
    });
    std::sort(partners.begin(), partners.end());
    for (const std::uint32_t j : partners)
    {
      bonds.push_back({ std::uint32_t(i), j });
    }
  }
  return bonds;
}

bool looks_coarse_grained(const BondPerceptionInput& input)
{
  check_input(input);
  const std::size_t n = input.atom_count;
  std::vector<int> molecule_size;
  for (std::size_t i = 0; i < n; ++i)
  {
    const int m = input.molecule_ids[i];
    if (m >= int(molecule_size.size()))
    {
      molecule_size.resize(std::size_t(m) + 1, 0);
    }
    ++molecule_size[std::size_t(m)];
  }
  const double reach = 2.0;
  const UniformGrid grid(input.positions, n, reach);
  std::size_t candidates = 0;
  std::size_t with_neighbour = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (molecule_size[std::size_t(input.molecule_ids[i])] < 2)
    {
      continue;
    }
    ++candidates;
    bool found = false;
    grid.for_each_neighbour_candidate(i, [&](std::uint32_t j) {
      if (!found && j != i && input.molecule_ids[j] == input.molecule_ids[i] &&
        squared_distance(input.positions, i, j) < reach * reach)
      {
        found = true;
      }
    });
    with_neighbour += found ? 1 : 0;
  }
  return candidates > 0 && 2 * with_neighbour < candidates;
}

std::vector<Bond> merge_bonds(const std::vector<Bond>& a, const std::vector<Bond>& b)
{
  std::vector<Bond> merged;
  merged.reserve(a.size() + b.size());
  std::set_union(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(merged));
  merged.erase(std::unique(merged.begin(), merged.end()), merged.end());
  return merged;
}

} // namespace mesolens
