// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/molecules/molecule_groups.h"

#include "mesolens/common/errors.h"

#include <cmath>
#include <limits>
#include <string>
#include <unordered_map>

namespace mesolens {

MoleculeGroups group_molecules(const int* ids, std::size_t atom_count)
{
  if (atom_count >= std::numeric_limits<std::uint32_t>::max())
  {
    throw InvalidInput("cannot group " + std::to_string(atom_count) +
                       " atoms into molecules (at most 2^32 - 2)");
  }
  MoleculeGroups groups;
  groups.of_atom.resize(atom_count);
  std::unordered_map<int, std::uint32_t> index;
  int previous = 0;
  std::uint32_t current = 0;
  for (std::size_t a = 0; a < atom_count; ++a)
  {
    const int id = ids ? ids[a] : int(a);
    // Atoms of a molecule are usually consecutive: look the id up only when it changes.
    if (a == 0 || id != previous || !ids)
    {
      const auto found = index.emplace(id, std::uint32_t(groups.ids.size()));
      if (found.second)
      {
        groups.ids.push_back(id);
      }
      current = found.first->second;
      previous = id;
    }
    groups.of_atom[a] = current;
  }
  // Atoms by molecule (a counting sort keeps them in increasing order).
  groups.first.assign(groups.ids.size() + 1, 0);
  for (const std::uint32_t m : groups.of_atom)
  {
    ++groups.first[m + 1];
  }
  for (std::size_t m = 0; m < groups.ids.size(); ++m)
  {
    groups.first[m + 1] += groups.first[m];
  }
  groups.atoms.resize(atom_count);
  std::vector<std::size_t> next(groups.first.begin(), groups.first.end() - 1);
  for (std::size_t a = 0; a < atom_count; ++a)
  {
    groups.atoms[next[groups.of_atom[a]]++] = std::uint32_t(a);
  }
  return groups;
}

namespace {
template<typename Coordinate>
std::vector<double> centres_of(const MoleculeGroups& groups, PointSpan<const Coordinate> positions,
                               const float* masses)
{
  if (positions.size() != groups.of_atom.size())
  {
    throw InvalidInput("molecule centres need one position per grouped atom (" +
                       std::to_string(groups.of_atom.size()) + "); got " +
                       std::to_string(positions.size()));
  }
  std::vector<double> centres(3 * groups.count(), 0.0);
  for (std::size_t m = 0; m < groups.count(); ++m)
  {
    double sum[3] = { 0, 0, 0 };
    double total = 0;
    double weighted[3] = { 0, 0, 0 };
    double mass = 0;
    for (std::size_t k = groups.first[m]; k < groups.first[m + 1]; ++k)
    {
      const std::size_t a = groups.atoms[k];
      const double w = masses ? double(masses[a]) : 1.0;
      for (std::size_t d = 0; d < 3; ++d)
      {
        const double p = double(positions[a][d]);
        if (!std::isfinite(p))
        {
          throw InvalidInput("atom " + std::to_string(a) + " has a non-finite position");
        }
        sum[d] += p;
        weighted[d] += w * p;
      }
      total += 1;
      mass += w;
    }
    for (std::size_t d = 0; d < 3; ++d)
    {
      centres[3 * m + d] = masses && mass > 0 ? weighted[d] / mass : sum[d] / total;
    }
  }
  return centres;
}
} // namespace

std::vector<double> molecule_centres(const MoleculeGroups& groups, PointSpan<const float> positions,
                                     const float* masses)
{
  return centres_of(groups, positions, masses);
}

std::vector<double> molecule_centres(const MoleculeGroups& groups,
                                     PointSpan<const double> positions, const float* masses)
{
  return centres_of(groups, positions, masses);
}

} // namespace mesolens
