// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/detail/residue_layout.h"

namespace mesolens {
namespace detail {

const ResidueRange* find_linked_residue(const gemmi::AtomAddress& address,
                                        const std::vector<ChainResidues>& chains,
                                        bool ignore_segment)
{
  for (const ChainResidues& chain : chains)
  {
    if (chain.name != address.chain_name)
    {
      continue;
    }
    for (const ResidueRange& residue : chain.residues)
    {
      if (residue.seqid == address.res_id.seqid && residue.name == address.res_id.name &&
          (ignore_segment || residue.segment == address.res_id.segment))
      {
        return &residue;
      }
    }
  }
  return nullptr;
}

std::size_t find_linked_atom(const gemmi::AtomAddress& address, const ResidueRange& residue,
                             const AtomTable& table)
{
  if (address.atom_name.empty())
  {
    return no_atom;
  }
  for (std::size_t i = residue.begin; i < residue.end; ++i)
  {
    const char altloc = table.alt_locs[i];
    if (table.atom_names[i] == address.atom_name &&
        (address.altloc == '*' || altloc == ' ' || altloc == address.altloc))
    {
      return i;
    }
  }
  return no_atom;
}

void complete_disulfide_partner(gemmi::AtomAddress& address,
                                const std::vector<ChainResidues>& chains, const AtomTable& table)
{
  constexpr std::uint8_t sulfur = 16;
  address.atom_name = "SG";
  const ResidueRange* residue = find_linked_residue(address, chains, false);
  if (!residue)
  {
    return;
  }
  const std::size_t sg = find_linked_atom(address, *residue, table);
  if (sg != no_atom && table.atomic_numbers[sg] == sulfur)
  {
    return;
  }
  for (std::size_t i = residue->begin; i < residue->end; ++i)
  {
    if (table.atomic_numbers[i] == sulfur)
    {
      address.atom_name = table.atom_names[i];
      address.altloc = table.alt_locs[i] == ' ' ? '\0' : table.alt_locs[i];
      return;
    }
  }
}

} // namespace detail
} // namespace mesolens
