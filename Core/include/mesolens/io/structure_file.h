// SPDX-License-Identifier: GPL-3.0-or-later
// Reading PDB and PDBx/mmCIF files (plain or gzipped), losing no atom: PDB atom records by
// MesoLens (as gemmi reads them), the rest through gemmi.
#pragma once

#include "mesolens/molecules/atom_table.h"
#include "mesolens/molecules/bond_perception.h"
#include "mesolens/common/parallel_for.h"
#include "mesolens/protein/assembly.h"

#include <functional>
#include <string>
#include <vector>

namespace mesolens {

/// How alternate locations (altlocs) are resolved.
enum class AltLocPolicy
{
  /// Per residue, keep the conformer with the highest summed occupancy (ties: first letter);
  /// atoms without an altloc are always kept.
  HighestOccupancy,
  /// Keep every alternate atom (the `AltLoc` array tells them apart).
  KeepAll,
};

/// Parameters of read_structure().
struct StructureReadParams
{
  /// Which alternate locations are kept. Default HighestOccupancy.
  AltLocPolicy alt_locs = AltLocPolicy::HighestOccupancy;
  /// Drop water residues (is_water_residue()), as the membrane-mapping paper does on import.
  /// Default false.
  bool remove_waters = false;
  /// Drop hydrogen and deuterium atoms. Default false.
  bool remove_hydrogens = false;
  /// Perceive covalent bonds from distances (explicit CONECT/LINK/SSBOND/struct_conn bonds are
  /// always added). Default true.
  bool perceive_bonds = true;
  /// Bond perception; coarse_grained is decided per file by looks_coarse_grained() unless
  /// force_coarse_grained is set.
  BondPerceptionParams bonds;
  /// Treat the particles as coarse-grained beads even when looks_coarse_grained() says they
  /// are atoms. Default false.
  bool force_coarse_grained = false;
  /// Runs the data-parallel loops (bond perception); empty: the calling thread only.
  ParallelFor parallel_for;
};

/// A structure file: one AtomTable per model (NMR ensembles have several).
struct StructureFile
{
  std::vector<AtomTable> models;
  std::string title;                 ///< TITLE / _struct.title, may be empty
  bool coarse_grained = false;       ///< bonds were perceived with the bead cutoff
  std::vector<std::string> warnings; ///< things a user should know (ignored CONECT serials...)
  /// The biological assemblies the file defines, in its order (see read_structure()); the
  /// models hold the asymmetric unit. Build one with expand_assembly() or draw it with
  /// assembly_instances() (mesolens/protein/assembly.h).
  std::vector<Assembly> assemblies;
};

/// Progress callback: fraction in [0, 1]. Return false to abort (read_structure then throws
/// FileError("aborted")).
using ProgressCallback = std::function<bool(double)>;

/// Reads a PDB or mmCIF file (format from the extension, else from the content; `.gz` is
/// decompressed). Every atom of every model is kept (hydrogens included) unless the params
/// drop some; HELIX/SHEET records become per-atom secondary structure; CONECT records (which
/// gemmi does not read) and LINK/SSBOND/struct_conn covalent and disulfide links become bonds.
///
/// PDB files written by MD programs keep their true serials and residue numbers past 99999 and
/// 9999: hybrid-36 (A0000 = 100000, A000 = 10000; also in CONECT), numbers written in full that
/// push the rest of the record right (Open Babel; found from where the "%8.3f" coordinates
/// are), CHARMM's five-digit residue numbers in columns 23-27, and numbers written modulo
/// 100000 and 10000, as GROMACS writes them, continued where they restart (a drop by more than
/// half the modulus; for residue numbers inside one chain with no TER between). Four-letter
/// residue names in columns 18-21 ("DPPC") are kept whole unless the file uses two-letter chain
/// ids there. StructureFile::warnings says when any of this was needed. VMD's hexadecimal
/// numbers past 99999 and 9999 are not recognized.
///
/// Biological assemblies come from REMARK 350 (PDB: BIOMOLECULE, APPLY THE FOLLOWING TO
/// CHAINS with its AND CHAINS continuations, BIOMT1-3 read as blank-separated words, so
/// serials past 99 that push the numbers right are read right) and from
/// `_pdbx_struct_assembly`, `_pdbx_struct_assembly_gen` and `_pdbx_struct_oper_list` (mmCIF:
/// generators name label_asym_ids, kept per atom in AtomTable::label_asym_ids; operator
/// expressions, products included, expanded by expand_operator_expression()). An assembly with
/// a malformed record or expression, an undefined operator, a non-finite matrix, no operators
/// or chains, a repeated name, or past max_assembly_copies copies (in one assembly or all
/// together) is left out with a warning; the atoms are read all the same. An assembly that
/// names chains the file lacks is kept, with a warning.
///
/// Throws FileError for a missing, empty, truncated or unparsable file (an ATOM/HETATM record
/// without coordinates in the standard or a consistently shifted place names its line), or one
/// without atoms; InvalidInput for non-finite coordinates.
StructureFile read_structure(const std::string& path, const StructureReadParams& params = {},
                             const ProgressCallback& progress = {});

/// Bonds and molecules for a table that has names and positions (used by every reader):
/// assigns residues and molecules, perceives bonds and merges `explicit_bonds`. When the file
/// named no elements (`elements_given` false: GRO, PDB without columns 77-78) and
/// looks_coarse_grained() says so, the particles are beads: their atomic numbers are set to 0,
/// the bead cutoff is used and the bonds are made consistent per molecule type
/// (consensus_bonds()). Returns true when the particles were treated as beads.
bool build_connectivity(AtomTable& table, const std::vector<Bond>& explicit_bonds,
                        const StructureReadParams& params, bool elements_given);

} // namespace mesolens
