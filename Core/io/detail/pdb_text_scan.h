// SPDX-License-Identifier: GPL-3.0-or-later
// The raw-text pass over a PDB file before its records are read (private to Core).
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace mesolens {
namespace detail {

/// The fields of one ATOM/HETATM record that gemmi 0.5 cannot read right from MD files.
struct PdbAtomFields
{
  int serial = 0;         ///< true serial; 0 when the field is no number ("*****")
  int residue_number = 0; ///< true residue number, when residue_number_read
  bool residue_number_read = false;
  char residue_name_end = ' '; ///< fourth letter of a four-letter name ("DPPC"), else ' '
};

/// What the raw-text pass found.
struct PdbTextScan
{
  /// Per ATOM/HETATM record, in file order (read_pdb_atoms indexes it by the records' order;
  /// the pass also writes n into the serial field of the n-th record, 1-based, whole file, see
  /// AtomRecordScanner::scan).
  std::vector<PdbAtomFields> atoms;
  std::vector<std::pair<int, int>> conect_pairs; ///< CONECT (serial, bonded serial)
  std::size_t unreadable_conect_fields = 0;      ///< CONECT fields that are no numbers
  std::size_t run_together_conect_records = 0;   ///< CONECT records whose serials touch
  std::size_t legacy_columns = 0;                ///< records whose columns 77-80 were blanked
  std::size_t element_records = 0;   ///< ATOM/HETATM records with an element in columns 77-78
  std::size_t shifted_records = 0;   ///< records pushed right by numbers wider than their field
  std::size_t continued_serials = 0; ///< records whose serial restarted after 99999
  std::size_t continued_residue_numbers = 0; ///< records whose resSeq restarted after 9999
};

/// Scans the PDB text once, before its records are read: collects CONECT pairs (gemmi 0.5
/// ignores CONECT), rejects ATOM/HETATM records without readable coordinates (the mark of a
/// truncated or corrupt file; throws FileError naming the line), and rewrites each ATOM/HETATM
/// record into the standard columns that read_pdb_atoms reads, as gemmi would:
/// - a serial over 99999 or a residue number over 9999 written in full ("%5d", "%4d" without a
///   modulo, as Open Babel writes them) pushes the rest of the record right; the shift is found
///   from where the three "%8.3f" coordinates really are;
/// - a five-digit residue number in columns 23-27 (CHARMM) is read whole;
/// - serials written modulo 100000 and residue numbers written modulo 10000 (GROMACS) are
///   continued where they restart (a drop by more than half the modulus; for residue numbers
///   only inside one chain with no TER between);
/// - hybrid-36 serials and residue numbers are read in both ranges (A0000 = 100000, a0000 =
///   43770016; A000 = 10000);
/// - a four-letter residue name in columns 18-21 is kept whole;
/// - legacy text in columns 77-80 (pre-remediation files) is blanked.
PdbTextScan scan_pdb_text(char* data, std::size_t size, const std::string& path);

} // namespace detail
} // namespace mesolens
