// SPDX-License-Identifier: GPL-3.0-or-later
// Reading the atoms of a GROMACS .gro file (names, residues, first-frame coordinates, box)
// through GROMACS' own library.
#pragma once

#include "mesolens/molecules/atom_table.h"

#include <string>

namespace mesolens {

/// Reads the first frame of a .gro file: atom and residue names, residue numbers, positions
/// (converted from nm to Å) and the box. Elements are guessed from names
/// (guess_atomic_number()); bonds, residues and molecules are not assigned here.
/// Throws FileError for a missing, empty or malformed file (GROMACS' own message included).
AtomTable read_gro_topology(const std::string& path);

} // namespace mesolens
