// SPDX-License-Identifier: GPL-3.0-or-later
// The ATOM/HETATM records of a PDB file read straight into atom tables (private to Core).
#pragma once

#include "io/detail/pdb_text_scan.h"
#include "io/detail/residue_layout.h"
#include "io/detail/text_fields.h"
#include "mesolens/common/parallel_for.h"
#include "mesolens/molecules/atom_table.h"

#include <cstddef>
#include <string>
#include <vector>

namespace mesolens {
namespace detail {

/// One model's atoms and where its residues are.
struct PdbModelAtoms
{
  AtomTable table;
  std::vector<ChainResidues> chains;
};

/// A PDB text split into its atoms and the rest.
struct PdbAtomsAndHeader
{
  std::vector<PdbModelAtoms> models; ///< in the file's order; a model may be empty
  std::string header;                ///< the other records, for gemmi to read
  /// The REMARK records, views into the text: gemmi reads nothing from them that MesoLens
  /// uses, and the REMARK 350 records of a virus capsid number thousands.
  std::vector<NumberedLine> remarks;
};

/// Reads the ATOM/HETATM records of a PDB text that scan_pdb_text has been through (and found
/// `scan` in) into one table per model, grouped and ordered as gemmi 0.5 groups them: a new
/// chain at each change of chain id, within it the atoms of a residue (number, insertion code,
/// name, segment) together in the order the residues first appear; records after END are not
/// read. Fields are read as gemmi reads them (elements inferred from the atom name when columns
/// 77-78 hold none, B 20 and occupancy 1 when the record is too short to give them); the
/// serials, residue numbers and four-letter names come from `scan`. Records are parsed
/// concurrently through `parallel_for`. The ANISOU, MODEL, ENDMDL and TER records are checked
/// and left out of `header`, as are ATOM/HETATM and REMARK (which go to `remarks`). Throws
/// FileError for what gemmi refuses (a record too short, atoms between models, a repeated MODEL
/// number, a bad charge).
PdbAtomsAndHeader read_pdb_atoms(const char* text, std::size_t size, const PdbTextScan& scan,
                                 const ParallelFor& parallel_for, const std::string& path);

} // namespace detail
} // namespace mesolens
