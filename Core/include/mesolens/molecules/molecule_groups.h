// SPDX-License-Identifier: GPL-3.0-or-later
// Atoms grouped into molecules by their ids, and the molecules' centres: the one grouping that
// the mapping, the cutaway, the trajectory's unwrapping and the atom mapper share.
#pragma once

#include "mesolens/common/point_span.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace mesolens {

/// Atoms grouped into molecules: molecules numbered 0, 1, ... in order of first appearance,
/// each with its id and its atoms in increasing order.
struct MoleculeGroups
{
  std::vector<std::uint32_t> of_atom; ///< per atom: its molecule
  std::vector<int> ids;               ///< per molecule: its id
  std::vector<std::size_t> first;     ///< per molecule, and the total at the end: where
                                      ///< its atoms start in `atoms`
  std::vector<std::uint32_t> atoms;   ///< molecule m's atoms: [first[m], first[m + 1])

  std::size_t count() const
  {
    return this->ids.size();
  }
  std::size_t size_of(std::size_t molecule) const
  {
    return this->first[molecule + 1] - this->first[molecule];
  }

  /// The atoms of one molecule, for range-for.
  struct AtomRange
  {
    const std::uint32_t* from;
    const std::uint32_t* to;
    const std::uint32_t* begin() const
    {
      return this->from;
    }
    const std::uint32_t* end() const
    {
      return this->to;
    }
  };
  AtomRange atoms_of(std::size_t molecule) const
  {
    return { this->atoms.data() + this->first[molecule],
             this->atoms.data() + this->first[molecule + 1] };
  }
};

/// Groups `atom_count` atoms by `ids` (per atom, any values; atoms of a molecule need not be
/// consecutive); nullptr: every atom its own molecule (id = its index). Throws InvalidInput for
/// more than 2^32 - 1 atoms.
MoleculeGroups group_molecules(const int* ids, std::size_t atom_count);

/// Per molecule, 3 values: the mean position of its atoms, or with `masses` (per atom) the
/// centre of mass (an all-zero mass molecule: the mean). `positions`: one per grouped atom,
/// summed in atom order in double precision. Throws InvalidInput for another number of
/// positions, or naming the first atom with a non-finite coordinate.
std::vector<double> molecule_centres(const MoleculeGroups& groups, PointSpan<const float> positions,
                                     const float* masses = nullptr);
std::vector<double> molecule_centres(const MoleculeGroups& groups,
                                     PointSpan<const double> positions,
                                     const float* masses = nullptr);

} // namespace mesolens
