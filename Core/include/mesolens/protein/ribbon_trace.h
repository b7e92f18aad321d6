// SPDX-License-Identifier: GPL-3.0-or-later
// Which residues a ribbon is traced through, and through which of their atoms.
#pragma once

#include "mesolens/common/point_span.h"
#include "mesolens/molecules/atom_table.h"
#include "mesolens/protein/ribbon_geometry.h"

#include <cstdint>
#include <vector>

namespace mesolens {

/// The residues of a table that a ribbon passes through, in table order, with the atom rows
/// they come from (kept while the atoms stay the same: a new frame needs only update()).
struct RibbonTrace
{
  std::vector<RibbonResidue> residues;   ///< id = the residue's place in this list
  std::vector<std::int64_t> trace_atom;  ///< per residue: the row of its Cα (or P)
  std::vector<std::int64_t> oxygen_atom; ///< per residue: the row of its carbonyl O, -1: none
  std::vector<int> residue_index;        ///< per residue: AtomTable::residue_indices

  /// Takes the residues' trace and oxygen positions from `positions` (one per table row, Å) and
  /// their classes from `classes` (a SecondaryStructure per row; nullptr: coil, ' '). Throws
  /// InvalidInput when `positions` lacks a row the trace uses.
  void update(PointSpan<const float> positions, const std::uint8_t* classes);
};

/// Amino acids traced through their Cα (oriented by their carbonyl O when present) and
/// nucleotides through their P; residues with neither are left out. A new chain starts where
/// the chain id or the molecule changes. Classes come from the table's secondary_structure.
RibbonTrace ribbon_trace(const AtomTable& table);

} // namespace mesolens
