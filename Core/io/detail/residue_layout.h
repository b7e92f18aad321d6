// SPDX-License-Identifier: GPL-3.0-or-later
// Where each residue's atoms sit in a model's atom table (private to Core).
#pragma once

#include "mesolens/molecules/atom_table.h"

#include <gemmi/seqid.hpp>

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace mesolens {
namespace detail {

/// One residue: its number, name and segment as the file's records give them (the name gemmi
/// reads: three letters for PDB), and its atoms' range [begin, end) in the table.
struct ResidueRange
{
  gemmi::SeqId seqid;
  std::string name;
  std::string segment;
  std::size_t begin = 0;
  std::size_t end = 0;
};

/// One chain (a run of records of one chain id; a chain id that comes back starts another), its
/// residues in table order.
struct ChainResidues
{
  std::string name;
  std::vector<ResidueRange> residues;
};

constexpr std::size_t no_atom = std::numeric_limits<std::size_t>::max();

/// The residue a link record names (chain, residue number and name; and segment unless
/// `ignore_segment`), or nullptr: the first that matches, as gemmi's Model::find_cra finds it.
const ResidueRange* find_linked_residue(const gemmi::AtomAddress& address,
                                        const std::vector<ChainResidues>& chains,
                                        bool ignore_segment);

/// The table index of the atom a link record names in `residue`: the first of that name whose
/// alternate location is blank or the one asked for (any, for '*'), or `no_atom`.
std::size_t find_linked_atom(const gemmi::AtomAddress& address, const ResidueRange& residue,
                             const AtomTable& table);

/// SSBOND records name no atom: sets `address` to the residue's SG, or to its first sulfur when
/// SG is missing or no sulfur (gemmi's rule, applied to the first model).
void complete_disulfide_partner(gemmi::AtomAddress& address,
                                const std::vector<ChainResidues>& chains, const AtomTable& table);

} // namespace detail
} // namespace mesolens
