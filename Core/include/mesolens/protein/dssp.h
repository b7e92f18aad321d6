// SPDX-License-Identifier: GPL-3.0-or-later
// Secondary structure from the backbone (Kabsch & Sander's DSSP, as today's mkdssp assigns it),
// and from Cα atoms alone where a chain has nothing else.
#pragma once

#include "mesolens/common/point_span.h"
#include "mesolens/molecules/atom_table.h"
#include "mesolens/protein/protein_backbone.h"
#include "mesolens/common/parallel_for.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace mesolens {

/// How DSSP assigns.
struct DsspParams
{
  /// pi helices before alpha helices where both apply (DSSP 4 and mkdssp 4.x); false: the
  /// classic order (DSSP 2), alpha first. Default true.
  bool pi_helix_priority = true;
  /// Residues in a row with polyproline II angles (phi -75 +- 29 degrees, psi 145 +- 29) for a
  /// kappa (polyproline) helix; 0: none are assigned (DSSP 2). Range >= 0; default 3 (DSSP 4).
  int polyproline_stretch = 3;
  /// Join ladders across beta bulges into one strand (DSSP); false: every ladder alone, as
  /// PyDSSP and MDAnalysis' DSSP assign. Default true.
  bool bulges = true;
  /// Use the file's amide hydrogens where present; false (default): place every amide H as DSSP
  /// does, 1 Å from N opposite the previous residue's C=O, so that files with and without
  /// hydrogens give the same answer.
  bool file_hydrogens = false;
};

/// The assignment of one set of residues.
struct DsspResult
{
  std::vector<SecondaryStructure> structure; ///< per residue
  /// Per residue, 1 where the residue is the first after a chain break (a C-N gap over 2.5 Å,
  /// missing backbone atoms, a new chain).
  std::vector<std::uint8_t> break_before;
  /// Per residue, 1 where the chain's assignment came from its Cα atoms alone (the chain has
  /// no complete backbone).
  std::vector<std::uint8_t> from_ca_only;
  std::size_t hydrogen_bonds = 0; ///< backbone H-bonds found (energy < -0.5 kcal/mol)
};

/// The DSSP letter of a class: H G I E B T S P, ' ' for coil (and 'H' for OtherHelix).
char dssp_letter(SecondaryStructure structure);

/// The class of a DSSP letter; ' ', '-' and anything unknown are Coil.
SecondaryStructure from_dssp_letter(char letter);

/// Kabsch & Sander's assignment, with the details of mkdssp 4: backbone H-bond energies
/// (electrostatic, kcal/mol, the two best per donor and acceptor, Cα within 9 Å), n-turns,
/// alpha, 3-10 and pi helices, parallel and antiparallel bridges joined into ladders across
/// bulges (E; lone bridges B), turns (T), bends (S, Cα angle over 70 degrees) and polyproline
/// helices (P). A residue without N, CA, C and O takes no part in H-bonds and breaks its chain.
/// Chains in which no residue has a complete backbone (Cα-only models) are assigned from their
/// Cα geometry instead (assign_from_ca). Throws InvalidInput for a non-finite coordinate of a
/// present atom. `parallel_for` runs the energy search.
DsspResult assign_secondary_structure(const std::vector<BackboneResidue>& residues,
                                      const DsspParams& settings = {},
                                      const ParallelFor& parallel_for = {});

/// Secondary structure from Cα positions alone (Å; `chain` per residue, same length), for
/// Cα-only chains: helices where four or more residues in a row have the alpha-helix virtual
/// bond angle (89 +- 12 degrees) and dihedral (50 +- 20) with i..i+3 Cα 5.0-5.9 Å apart;
/// strands (E) where three or more in a row are extended (angle 124 +- 14, |dihedral| over
/// 120 degrees) and lie within 5.5 Å of an extended residue at least 3 apart (a paired
/// strand); the rest coil. After P-SEA (Labesse et al. 1997) with DSSP's classes.
std::vector<SecondaryStructure> assign_from_ca(PointSpan<const double> ca,
                                               const std::vector<int>& chain);

/// The assignment as DSSP letters, '-' for coil.
std::string dssp_string(const std::vector<SecondaryStructure>& structure);

/// Keeps a per-residue assignment from flickering over a trajectory: a residue shows a new
/// class only once that class has held for `frames` frames in a row (>= 1; 1: no delay).
class SecondaryStructureHysteresis
{
public:
  explicit SecondaryStructureHysteresis(int frames);

  /// The shown classes after a frame's raw assignment. The first frame is shown as it is; a
  /// new residue count starts over.
  const std::vector<SecondaryStructure>& update(const std::vector<SecondaryStructure>& frame);

private:
  int Frames;
  std::vector<SecondaryStructure> Shown;
  std::vector<SecondaryStructure> Candidate;
  std::vector<int> Held;
};

} // namespace mesolens
