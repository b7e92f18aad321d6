// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/molecules/bond_consensus.h"

#include "mesolens/common/errors.h"

#include <algorithm>
#include <map>
#include <string>
#include <unordered_map>

namespace mesolens {

std::vector<Bond> consensus_bonds(const AtomTable& table, const std::vector<Bond>& bonds,
                                  const BondConsensusParams& params)
{
  if (!(params.min_fraction > 0.0 && params.min_fraction <= 1.0) || params.min_copies < 1)
  {
    throw InvalidInput("consensus bonds: min_fraction must lie in (0, 1] and min_copies >= 1");
  }
  if (table.molecule_ids.size() != table.size())
  {
    throw InvalidInput("consensus bonds: the table has no molecule ids");
  }
  // Atoms of each molecule in file order, and each atom's position within its molecule.
  int molecule_count = 0;
  for (const int m : table.molecule_ids)
  {
    molecule_count = std::max(molecule_count, m + 1);
  }
  std::vector<std::vector<std::uint32_t>> members(static_cast<std::size_t>(molecule_count));
  std::vector<std::uint32_t> local_index(table.size());
  for (std::size_t i = 0; i < table.size(); ++i)
  {
    auto& list = members[std::size_t(table.molecule_ids[i])];
    local_index[i] = std::uint32_t(list.size());
    list.push_back(std::uint32_t(i));
  }
  // Molecule type = the sequence of residue and atom names.
  std::unordered_map<std::string, int> type_of_signature;
  std::vector<int> type_of_molecule(members.size());
  std::vector<std::size_t> copies;
  for (std::size_t m = 0; m < members.size(); ++m)
  {
    std::string signature;
    for (const std::uint32_t i : members[m])
    {
      signature += table.residue_names[i] + ':' + table.atom_names[i] + ';';
    }
    const auto found = type_of_signature.emplace(signature, int(copies.size()));
    if (found.second)
    {
      copies.push_back(0);
    }
    type_of_molecule[m] = found.first->second;
    ++copies[std::size_t(found.first->second)];
  }
  // Count each local pair per type.
  std::vector<std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t>> votes(copies.size());
  for (const Bond& bond : bonds)
  {
    const int m = table.molecule_ids[bond.first];
    if (m != table.molecule_ids[bond.second])
    {
      continue;
    }
    const auto a = local_index[bond.first];
    const auto b = local_index[bond.second];
    ++votes[std::size_t(type_of_molecule[std::size_t(m)])][{ std::min(a, b), std::max(a, b) }];
  }
  auto uses_consensus = [&](int type) { return copies[std::size_t(type)] >= params.min_copies; };
  std::vector<Bond> result;
  result.reserve(bonds.size());
  for (const Bond& bond : bonds)
  {
    const int m = table.molecule_ids[bond.first];
    if (m != table.molecule_ids[bond.second] || !uses_consensus(type_of_molecule[std::size_t(m)]))
    {
      result.push_back(bond);
    }
  }
  for (std::size_t m = 0; m < members.size(); ++m)
  {
    const int type = type_of_molecule[m];
    if (!uses_consensus(type))
    {
      continue;
    }
    const double needed = params.min_fraction * double(copies[std::size_t(type)]);
    for (const auto& vote : votes[std::size_t(type)])
    {
      if (double(vote.second) >= needed)
      {
        const std::uint32_t a = members[m][vote.first.first];
        const std::uint32_t b = members[m][vote.first.second];
        result.push_back({ std::min(a, b), std::max(a, b) });
      }
    }
  }
  std::sort(result.begin(), result.end());
  result.erase(std::unique(result.begin(), result.end()), result.end());
  return result;
}

} // namespace mesolens
