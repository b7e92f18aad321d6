// SPDX-License-Identifier: GPL-3.0-or-later
// Distance-based bond perception in O(n) with a uniform spatial grid.
#pragma once

#include "mesolens/common/point_span.h"
#include "mesolens/molecules/atom_table.h"
#include "mesolens/common/parallel_for.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace mesolens {

/// Parameters of perceive_bonds().
struct BondPerceptionParams
{
  /// Two atoms bond when their distance is below r_cov(a) + r_cov(b) + tolerance, Å (covalent
  /// radii of Cordero 2008). Range [0, 1]; default 0.45 (the value of Open Babel and Jmol).
  float tolerance = 0.45f;
  /// Pairs closer than this (Å) are overlapping atoms (alternate sites, bad models), not bonds.
  /// >= 0; default 0.4.
  float minimum_distance = 0.4f;
  /// Coarse-grained mode: beads of one molecule closer than bead_cutoff bond (radii ignored).
  /// Default false.
  bool coarse_grained = false;
  /// Bead bond cutoff in Å for coarse-grained files; Martini bonds are 3.0-4.8 Å. Range (0, 10];
  /// default 5.
  float bead_cutoff = 5.0f;
};

/// Read-only view over the atoms that bond perception looks at.
struct BondPerceptionInput
{
  PointSpan<const float> positions;             ///< one per atom, Å; non-finite atoms never bond
  const std::uint8_t* atomic_numbers = nullptr; ///< per atom (0 = unknown: radius 0.5 Å)
  const int* molecule_ids = nullptr;            ///< per atom; only atoms of one molecule bond
  const char* alt_locs = nullptr; ///< optional; different non-blank altlocs never bond

  std::size_t atom_count() const
  {
    return this->positions.size();
  }
};

/// Bonds between atoms of the same molecule by distance, sorted by (first, second), unique.
/// Runs in O(n) expected time: atoms are binned in a uniform grid whose cell is the longest
/// possible bond, and only neighbouring cells are searched; grid planes run through
/// `parallel_for` (the result does not depend on it).
/// Throws InvalidInput for a null array or an out-of-range parameter.
std::vector<Bond> perceive_bonds(const BondPerceptionInput& input,
                                 const BondPerceptionParams& params = {},
                                 const ParallelFor& parallel_for = {});

/// True when most atoms of multi-atom molecules have no bond in `atomistic_bonds` (bonds
/// perceived with covalent radii): the file then holds coarse-grained beads (Martini, whose
/// bonded beads are 3-5 Å apart), not atoms.
bool looks_coarse_grained(const BondPerceptionInput& input,
                          const std::vector<Bond>& atomistic_bonds);

/// Merges two sorted unique bond lists into one sorted unique list.
std::vector<Bond> merge_bonds(const std::vector<Bond>& a, const std::vector<Bond>& b);

} // namespace mesolens
