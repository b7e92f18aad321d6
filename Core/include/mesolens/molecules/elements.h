// SPDX-License-Identifier: GPL-3.0-or-later
// Chemical element data: symbols, covalent and van der Waals radii (from gemmi's tables:
// covalent radii of Cordero et al., Dalton Trans. 2008; van der Waals radii of Bondi, J. Phys.
// Chem. 1964, completed by Alvarez, Dalton Trans. 2013).
#pragma once

#include <string>

namespace mesolens {

/// Largest atomic number known to the tables (oganesson).
constexpr int max_atomic_number = 118;

/// Element symbol in standard case ("C", "Fe"); "X" for 0 or out of range.
const char* element_symbol(int atomic_number);

/// Atomic number of a symbol, case-insensitive ("FE", "fe", "Fe" -> 26); 0 when unknown.
/// "D" (deuterium) gives 1.
int atomic_number_from_symbol(const std::string& symbol);

/// Covalent radius in Å (Cordero 2008); 0.5 Å for unknown (0).
float covalent_radius(int atomic_number);

/// Van der Waals radius in Å (Bondi 1964 / Alvarez 2013); 1.0 Å for unknown (0).
float van_der_waals_radius(int atomic_number);

/// The radius given to atoms without an element (coarse-grained beads), Å: a Martini bead's
/// (van der Waals radius of a 0.47 nm bead). Filters take it as their BeadRadius default.
constexpr double bead_radius = 2.35;

/// Standard atomic weight in daltons (gemmi's table); 1 for unknown (0) and for coarse-grained
/// beads, so their centres of mass are centroids.
float atomic_mass(int atomic_number);

/// Guesses the element of an atom from its name when a file gives none (GRO, old PDB files).
/// Ions whose atom name repeats the residue name (NA, CL, MG, ZN, CA in "CA"/"CAL" residues,
/// CHARMM's SOD/POT/CLA/CAL) get the two-letter element; otherwise the first letter that names an
/// element (leading digits are skipped, so "1HB" is H). Returns 0 when nothing fits.
int guess_atomic_number(const std::string& atom_name, const std::string& residue_name);

} // namespace mesolens
