// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/molecules/bond_perception.h"

#include "mesolens/molecules/elements.h"
#include "mesolens/molecules/molecule_groups.h"
#include "mesolens/common/errors.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <vector>

namespace mesolens {

namespace {

/// Atoms binned in a uniform grid by a counting sort: cell c holds the sorted atoms
/// [Start[c], Start[c + 1]). Coordinates are copied in sorted order for cache-friendly scans.
class UniformGrid
{
public:
  /// Bins the atoms i < count with include[i] != 0 (all atoms when include is empty) and
  /// finite coordinates.
  UniformGrid(const float* positions, std::size_t count, double cell_size,
              const std::vector<std::uint8_t>& include = {})
  {
    auto wanted = [&](std::size_t i) {
      return (include.empty() || include[i] != 0) && finite_atom(positions, i);
    };
    std::array<double, 3> low{ std::numeric_limits<double>::max(),
                               std::numeric_limits<double>::max(),
                               std::numeric_limits<double>::max() };
    std::array<double, 3> high{ -low[0], -low[1], -low[2] };
    for (std::size_t i = 0; i < count; ++i)
    {
      if (!wanted(i))
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
    // At most a few cells per atom, so sparse inputs (a vesicle) stay O(n) in memory: grow the
    // cell until the cell count is below 8 n + 64.
    const double max_cells = 8.0 * double(count) + 64.0;
    this->Cell = std::max(cell_size, 1e-3);
    // Counted in doubles: atoms spread over 1e30 Å would overflow an integer count.
    const auto cells_along = [&](int d) { return std::floor((high[d] - low[d]) / this->Cell) + 1; };
    while (cells_along(0) * cells_along(1) * cells_along(2) > max_cells)
    {
      this->Cell *= 1.5;
    }
    for (int d = 0; d < 3; ++d)
    {
      this->Dims[d] = std::int64_t(cells_along(d));
    }
    this->Low = low;
    const std::size_t cell_count = std::size_t(this->Dims[0] * this->Dims[1] * this->Dims[2]);
    this->Start.assign(cell_count + 1, 0);
    std::vector<std::int64_t> cell_of_atom(count, -1);
    for (std::size_t i = 0; i < count; ++i)
    {
      if (wanted(i))
      {
        cell_of_atom[i] = this->cell_index(positions + 3 * i);
        ++this->Start[std::size_t(cell_of_atom[i]) + 1];
      }
    }
    std::partial_sum(this->Start.begin(), this->Start.end(), this->Start.begin());
    this->Atoms.resize(this->Start.back());
    this->Sorted.resize(3 * this->Start.back());
    std::vector<std::size_t> fill(this->Start.begin(), this->Start.end() - 1);
    for (std::size_t i = 0; i < count; ++i)
    {
      if (cell_of_atom[i] >= 0)
      {
        const std::size_t k = fill[std::size_t(cell_of_atom[i])]++;
        this->Atoms[k] = std::uint32_t(i);
        std::copy(positions + 3 * i, positions + 3 * i + 3, this->Sorted.begin() + 3 * k);
      }
    }
  }

  static bool finite_atom(const float* positions, std::size_t i)
  {
    return std::isfinite(positions[3 * i]) && std::isfinite(positions[3 * i + 1]) &&
      std::isfinite(positions[3 * i + 2]);
  }

  /// Number of grid planes (z layers of cells).
  std::size_t plane_count() const
  {
    return std::size_t(this->Dims[2]);
  }

  /// Calls visit(k, l) once for every pair of sorted slots k != l in the same or adjacent cells
  /// (the cell itself and a half shell of 13 neighbours), for the cells of planes
  /// [first_plane, end_plane). Cells of one grid row are contiguous in slot order, so the half
  /// shell is five contiguous slot ranges: the rest of this cell and the next one in the row,
  /// then three cells in each of the rows (y+1, z), (y-1, z+1), (y, z+1) and (y+1, z+1).
  template<typename Visit>
  void for_each_close_pair(std::size_t first_plane, std::size_t end_plane, Visit&& visit) const
  {
    const std::int64_t dx = this->Dims[0];
    const std::int64_t dy = this->Dims[1];
    const std::int64_t dz = this->Dims[2];
    static const std::array<std::array<int, 2>, 4> rows = {
      { { 1, 0 }, { -1, 1 }, { 0, 1 }, { 1, 1 } }
    };
    for (std::int64_t z = std::int64_t(first_plane); z < std::int64_t(end_plane); ++z)
    {
      for (std::int64_t y = 0; y < dy; ++y)
      {
        const std::int64_t row = (z * dy + y) * dx;
        for (std::int64_t x = 0; x < dx; ++x)
        {
          const std::size_t begin = this->Start[std::size_t(row + x)];
          const std::size_t end = this->Start[std::size_t(row + x + 1)];
          if (begin == end)
          {
            continue;
          }
          std::array<std::size_t, 8> ranges{};
          std::size_t range_count = 0;
          const std::int64_t x_low = std::max<std::int64_t>(x - 1, 0);
          const std::int64_t x_high = std::min<std::int64_t>(x + 1, dx - 1);
          for (const auto& offset : rows)
          {
            const std::int64_t ny = y + offset[0];
            const std::int64_t nz = z + offset[1];
            if (ny < 0 || ny >= dy || nz >= dz)
            {
              continue;
            }
            const std::int64_t other = (nz * dy + ny) * dx;
            ranges[range_count++] = this->Start[std::size_t(other + x_low)];
            ranges[range_count++] = this->Start[std::size_t(other + x_high + 1)];
          }
          const std::size_t row_end = this->Start[std::size_t(row + x_high + 1)];
          for (std::size_t k = begin; k < end; ++k)
          {
            for (std::size_t l = k + 1; l < row_end; ++l)
            {
              visit(k, l);
            }
            for (std::size_t r = 0; r < range_count; r += 2)
            {
              for (std::size_t l = ranges[r]; l < ranges[r + 1]; ++l)
              {
                visit(k, l);
              }
            }
          }
        }
      }
    }
  }

  /// Number of sorted slots (atoms with finite coordinates).
  std::size_t slot_count() const
  {
    return this->Atoms.size();
  }

  /// Original atom index of a sorted slot.
  std::uint32_t atom(std::size_t slot) const
  {
    return this->Atoms[slot];
  }

  /// Squared distance between two sorted slots.
  float squared_distance(std::size_t k, std::size_t l) const
  {
    const float dx = this->Sorted[3 * k] - this->Sorted[3 * l];
    const float dy = this->Sorted[3 * k + 1] - this->Sorted[3 * l + 1];
    const float dz = this->Sorted[3 * k + 2] - this->Sorted[3 * l + 2];
    return dx * dx + dy * dy + dz * dz;
  }

private:
  std::int64_t cell_index(const float* p) const
  {
    std::array<std::int64_t, 3> c{};
    for (int d = 0; d < 3; ++d)
    {
      c[d] = std::clamp<std::int64_t>(std::int64_t((double(p[d]) - this->Low[d]) / this->Cell), 0,
                                      this->Dims[d] - 1);
    }
    return (c[2] * this->Dims[1] + c[1]) * this->Dims[0] + c[0];
  }

  std::array<double, 3> Low{};
  std::array<std::int64_t, 3> Dims{ 1, 1, 1 };
  double Cell = 1;
  std::vector<std::size_t> Start;
  std::vector<std::uint32_t> Atoms;
  std::vector<float> Sorted;
};

/// Sorts bonds by (first, second) in O(n + bonds): a counting sort on the first atom, then an
/// insertion sort of each atom's few partners.
std::vector<Bond> sorted_bonds(const std::vector<Bond>& bonds, std::size_t atom_count)
{
  std::vector<std::uint32_t> start(atom_count + 1, 0);
  for (const Bond& bond : bonds)
  {
    ++start[bond.first + 1];
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<Bond> sorted(bonds.size());
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (const Bond& bond : bonds)
  {
    sorted[fill[bond.first]++] = bond;
  }
  for (std::size_t i = 0; i < atom_count; ++i)
  {
    std::sort(sorted.begin() + start[i], sorted.begin() + start[i + 1]);
  }
  return sorted;
}

void check_input(const BondPerceptionInput& input)
{
  if (input.atom_count() > 0 &&
      (!input.positions.data() || !input.atomic_numbers || !input.molecule_ids))
  {
    throw InvalidInput("bond perception needs positions, atomic numbers and molecule ids");
  }
  if (input.atom_count() >= std::numeric_limits<std::uint32_t>::max())
  {
    throw InvalidInput("bond perception supports at most 2^32 - 1 atoms");
  }
}

} // namespace

std::vector<Bond> perceive_bonds(const BondPerceptionInput& input,
                                 const BondPerceptionParams& params,
                                 const ParallelFor& parallel_for)
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
  const std::size_t n = input.atom_count();
  // Atoms alone in their molecule (ions, crystal waters) cannot bond: leave them out of the grid
  // and out of the cell size, which the largest radius sets.
  std::vector<std::uint8_t> has_partner(n, 0);
  {
    const MoleculeGroups molecules = group_molecules(input.molecule_ids, n);
    for (std::size_t i = 0; i < n; ++i)
    {
      has_partner[i] = molecules.size_of(molecules.of_atom[i]) > 1 ? 1 : 0;
    }
  }
  std::vector<float> radius(n);
  float largest_radius = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    radius[i] = covalent_radius(input.atomic_numbers[i]);
    if (has_partner[i])
    {
      largest_radius = std::max(largest_radius, radius[i]);
    }
  }
  const double reach = params.coarse_grained
    ? double(params.bead_cutoff)
    : 2.0 * double(largest_radius) + double(params.tolerance);
  const UniformGrid grid(input.positions.data(), n, reach, has_partner);
  const float min2 = params.minimum_distance * params.minimum_distance;
  const float bead2 = params.bead_cutoff * params.bead_cutoff;

  // Per-slot copies in grid order keep the pair loop on contiguous memory.
  const std::size_t slots = grid.slot_count();
  std::vector<float> slot_radius(slots);
  std::vector<int> slot_molecule(slots);
  std::vector<char> slot_alt(slots, ' ');
  for (std::size_t k = 0; k < slots; ++k)
  {
    const std::uint32_t i = grid.atom(k);
    slot_radius[k] = radius[i] + 0.5f * params.tolerance;
    slot_molecule[k] = input.molecule_ids[i];
    slot_alt[k] = input.alt_locs ? input.alt_locs[i] : ' ';
  }
  // One bond list per grid plane, filled concurrently, joined in plane order.
  std::vector<std::vector<Bond>> plane_bonds(grid.plane_count());
  run_parallel(parallel_for, grid.plane_count(), [&](std::size_t first, std::size_t end) {
    for (std::size_t plane = first; plane < end; ++plane)
    {
      std::vector<Bond>& found = plane_bonds[plane];
      grid.for_each_close_pair(plane, plane + 1, [&](std::size_t k, std::size_t l) {
        if (slot_molecule[k] != slot_molecule[l] ||
            (slot_alt[k] != ' ' && slot_alt[l] != ' ' && slot_alt[k] != slot_alt[l]))
        {
          return;
        }
        const float d2 = grid.squared_distance(k, l);
        const float limit = slot_radius[k] + slot_radius[l];
        const float limit2 = params.coarse_grained ? bead2 : limit * limit;
        if (d2 < limit2 && d2 >= min2)
        {
          const std::uint32_t i = grid.atom(k);
          const std::uint32_t j = grid.atom(l);
          found.push_back({ std::min(i, j), std::max(i, j) });
        }
      });
    }
  });
  std::vector<Bond> bonds;
  bonds.reserve(n + n / 4);
  for (const std::vector<Bond>& found : plane_bonds)
  {
    bonds.insert(bonds.end(), found.begin(), found.end());
  }
  return sorted_bonds(bonds, n);
}

bool looks_coarse_grained(const BondPerceptionInput& input,
                          const std::vector<Bond>& atomistic_bonds)
{
  check_input(input);
  const std::size_t n = input.atom_count();
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
  std::vector<std::uint8_t> bonded(n, 0);
  for (const Bond& bond : atomistic_bonds)
  {
    if (bond.first < n && bond.second < n)
    {
      bonded[bond.first] = bonded[bond.second] = 1;
    }
  }
  std::size_t candidates = 0;
  std::size_t with_bond = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (molecule_size[std::size_t(input.molecule_ids[i])] >= 2)
    {
      ++candidates;
      with_bond += bonded[i];
    }
  }
  return candidates > 0 && 2 * with_bond < candidates;
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
