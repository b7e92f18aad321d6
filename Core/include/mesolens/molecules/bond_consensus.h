// SPDX-License-Identifier: GPL-3.0-or-later
// Making bonds identical across the copies of one molecule type (coarse-grained topologies).
#pragma once

#include "mesolens/molecules/atom_table.h"

#include <cstddef>
#include <vector>

namespace mesolens {

/// Parameters of consensus_bonds().
struct BondConsensusParams
{
  /// A bond of a molecule type is kept when at least this fraction of its copies has it.
  /// Range (0, 1]; default 0.5.
  double min_fraction = 0.5;
  /// Molecule types with fewer copies keep their own bonds. Minimum 1; default 3.
  std::size_t min_copies = 3;
};

/// Distance cutoffs alone give coarse-grained beads wrong bonds: stretched bonds are missed and
/// close non-bonded beads are joined. Copies of a molecule type (same residue and atom names in
/// the same order, e.g. every DPPC of a Martini membrane) share one topology, so this returns
/// `bonds` where every molecule of a type with enough copies gets the type's consensus bonds:
/// the pairs (by position in the molecule) found in at least min_fraction of its copies.
/// Needs table.molecule_ids; `bonds` must be within molecules. Result sorted and unique.
std::vector<Bond> consensus_bonds(const AtomTable& table, const std::vector<Bond>& bonds,
                                  const BondConsensusParams& params = {});

} // namespace mesolens
