// SPDX-License-Identifier: GPL-3.0-or-later
// The backbone atoms of a structure's amino-acid residues, as secondary structure and ribbons
// need them.
#pragma once

#include "mesolens/common/point_span.h"
#include "mesolens/molecules/atom_table.h"

#include <array>
#include <cstdint>
#include <vector>

namespace mesolens {

/// One amino-acid residue's backbone, Å. Residues are given in chain order; `chain` tells the
/// chains apart (consecutive residues of different chains are never bonded).
struct BackboneResidue
{
  std::array<double, 3> n{};
  std::array<double, 3> ca{};
  std::array<double, 3> c{};
  std::array<double, 3> o{};
  std::array<double, 3> h{}; ///< the amide hydrogen from the file, when has_h
  bool has_n = false;
  bool has_ca = false;
  bool has_c = false;
  bool has_o = false;
  bool has_h = false;
  bool proline = false; ///< no amide hydrogen: never an H-bond donor
  int chain = 0;
};

/// The amino-acid residues of a table of atoms as DSSP needs them.
struct ProteinBackbone
{
  std::vector<BackboneResidue> residues;
  /// Per backbone residue, the table's residue index (AtomTable::residue_indices).
  std::vector<int> residue_index;
  /// Per backbone residue, the table rows of its N, CA, C, O and H atoms (-1: absent): a new
  /// frame of the same atoms only needs update_positions().
  std::vector<std::array<std::int64_t, 5>> atom_rows;

  /// Takes every present atom's position from `positions` (one per table row, Å). Throws
  /// InvalidInput when `positions` lacks a row the backbone uses.
  void update_positions(PointSpan<const float> positions);
};

/// The amino-acid residues of `atoms` (standard and modified amino acids by name, or any
/// residue with N, CA and C atoms), in table order, with their N, CA, C, O (else OT1, O1, OC1)
/// and H (else HN) atoms; of alternate atoms the one of highest occupancy (the first of equal
/// ones). A new chain starts where the chain id or the molecule changes (so GRO files, which
/// have no chain ids, are split where their polymer molecules end). Needs residue_indices
/// (assign_residues); molecule_ids are used when present.
ProteinBackbone protein_backbone(const AtomTable& atoms);

} // namespace mesolens
