// SPDX-License-Identifier: GPL-3.0-or-later
// The in-memory form of a molecular structure that readers fill and filters consume.
#pragma once

#include "mesolens/molecules/periodic_box.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace mesolens {

/// Secondary-structure class of a residue, stored per atom. The values are stable: they are
/// written to the `SecondaryStructure` point array. PDB HELIX classes map to the helix kinds
/// (class 1 -> AlphaHelix, 3 -> PiHelix, 5 -> Helix310, others -> OtherHelix); SHEET strands
/// map to Strand. Turn, Bend, Bridge and Polyproline come from DSSP (mesolens/dssp.h).
enum class SecondaryStructure : std::uint8_t
{
  Coil = 0,
  AlphaHelix = 1,
  Helix310 = 2,
  PiHelix = 3,
  Strand = 4,
  Turn = 5,
  Bend = 6,
  Bridge = 7,
  OtherHelix = 8,
  Polyproline = 9, ///< a polyproline II (kappa) helix
};

/// A bond between two atoms of one AtomTable (indices, first < second).
struct Bond
{
  std::uint32_t first = 0;
  std::uint32_t second = 0;
  friend bool operator==(const Bond& a, const Bond& b)
  {
    return a.first == b.first && a.second == b.second;
  }
  friend bool operator<(const Bond& a, const Bond& b)
  {
    return a.first != b.first ? a.first < b.first : a.second < b.second;
  }
};

/// Atoms of one model (or one trajectory frame) as parallel arrays (structure of arrays).
/// Every per-atom vector has size() entries, except positions (3 per atom). Lengths are in
/// Ångström. Strings are trimmed of the blanks of fixed-column formats. label_asym_ids are
/// mmCIF's ids of chain instances (a polymer, a ligand, the waters of a chain: several per
/// author chain), which mmCIF assemblies list (mesolens/protein/assembly.h).
struct AtomTable
{
  std::vector<float> positions;                  ///< x, y, z per atom, Å
  std::vector<std::string> atom_names;           ///< e.g. "CA", "O1P", "NC3"
  std::vector<std::uint8_t> atomic_numbers;      ///< 0 = unknown element or coarse-grained bead
  std::vector<std::string> residue_names;        ///< e.g. "ALA", "DPPC", "HOH"
  std::vector<int> residue_numbers;              ///< author residue number (PDB resSeq, GRO resnr)
  std::vector<char> insertion_codes;             ///< ' ' when none
  std::vector<std::string> chain_ids;            ///< author chain id, "" when none
  std::vector<std::string> label_asym_ids;       ///< mmCIF label_asym_id (see above), else ""
  std::vector<char> alt_locs;                    ///< ' ' when none
  std::vector<float> occupancies;                ///< 1 when the format has none
  std::vector<float> b_factors;                  ///< Å², 0 when the format has none
  std::vector<std::uint8_t> is_hetero;           ///< 1 for HETATM records
  std::vector<int> serials;                      ///< serial number in the file (1-based; 0 = none)
  std::vector<std::int8_t> formal_charges;       ///< elementary charges, 0 when none
  std::vector<std::uint8_t> secondary_structure; ///< SecondaryStructure values
  std::vector<int> secondary_structure_ids;      ///< index of the HELIX/strand span, -1 = none
  std::vector<int> residue_indices;              ///< 0-based running residue index
  std::vector<int> molecule_ids;                 ///< 0-based molecule index (see assign_molecules)
  std::vector<Bond> bonds;                       ///< sorted, unique
  PeriodicBox box;                               ///< unit cell, if the file gives one

  std::size_t size() const
  {
    return atom_names.size();
  }

  /// Reserves room for `count` atoms in every per-atom array.
  void reserve(std::size_t count);

  /// Sets the number of atoms; new atoms get the defaults append_atom() gives (empty name,
  /// origin).
  void resize(std::size_t count);

  /// Appends one atom with default values for every field but name and position.
  void append_atom(const std::string& name, float x, float y, float z);

  /// Keeps the atoms whose keep[i] is true, in order; remaps bonds and drops those that lose an
  /// end. Residue and molecule indices are renumbered densely.
  void filter(const std::vector<bool>& keep);

  /// Throws InvalidInput when a per-atom array has the wrong length.
  void check_consistent() const;
};

/// True for the usual water residue names (HOH, WAT, SOL, TIP3, TIP4, SPC, DOD, H2O, W, PW...).
bool is_water_residue(const std::string& residue_name);

} // namespace mesolens
