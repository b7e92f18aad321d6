// SPDX-License-Identifier: GPL-3.0-or-later
// Grouping atoms into residues and residue-level molecules.
#pragma once

#include "mesolens/molecules/atom_table.h"

namespace mesolens {

/// Fills table.residue_indices: a new residue starts whenever chain id, residue number,
/// insertion code or residue name changes from the previous atom.
void assign_residues(AtomTable& table);

/// Fills table.molecule_ids (needs residue_indices). One molecule per residue (a lipid, a water,
/// an ion, a ligand), except that consecutive polymer residues (amino acids, nucleotides) of one
/// chain form a single molecule: with a chain id, the whole chain segment of that polymer kind;
/// without one (GRO files), consecutive residues whose link atoms (C-N, O3'-P; CA-CA or BB-BB
/// for CA-only and coarse-grained chains) are within bonding distance (minimum image when the
/// box is set). Molecule ids are 0-based and increase with the atom index.
void assign_molecules(AtomTable& table);

/// True when the residue name is a standard or common modified amino acid.
bool is_amino_acid_residue(const std::string& residue_name);
/// True when the residue name is a standard nucleotide (DNA or RNA).
bool is_nucleotide_residue(const std::string& residue_name);
/// True when the residue name is a lipid of the common force fields (case-insensitive): four
/// letters of two tail codes and a head group PC, PE, PS, PG, PA, PI or SM (CHARMM36, Slipids,
/// Martini: DPPC, POPE, DOPS...), sterols (CHOL, CHL1, CLR, ERG), cardiolipins (CDL0-2, TOCL,
/// POCL), PSM, and AMBER Lipid14/21's head and tail residues (PC, PE, PS, PGR, PA, OL, ST, MY,
/// DHA; not LA and AR, which ion residues use).
bool is_lipid_residue(const std::string& residue_name);

} // namespace mesolens
