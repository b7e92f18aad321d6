// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * @class   vtkMesoSecondaryStructure
 * @brief   Assigns every amino-acid residue its secondary structure (DSSP), per time step.
 *
 * Input: atoms as the MesoLens readers give them (point arrays `AtomName`, `ResidueIndex`,
 * `ResidueName`, `ChainId`, `MoleculeId`, `Occupancy`; any PDB, mmCIF or GRO file, trajectory
 * frames, NMR models as time steps). The residues' N, CA, C and O atoms go to
 * mesolens::assign_secondary_structure: Kabsch & Sander's DSSP with mkdssp 4's details, which
 * needs no HEADER, no chain ids and no hydrogens (the amide H is placed), takes the conformer
 * the reader kept, and assigns chains of Cα atoms alone from their Cα geometry. It never fails
 * on a real file: residues without a backbone are coil and break their chain.
 *
 * Output: the atoms (shallow copy) with the point arrays `SecondaryStructure` (unsigned char,
 * the mesolens::SecondaryStructure codes: 0 coil, 1 alpha helix, 2 3-10 helix, 3 pi helix,
 * 4 strand, 5 turn, 6 bend, 7 bridge, 9 polyproline helix; every atom of a residue carries its
 * residue's) and `SecondaryStructureId` (int: the index of the run of one class along a chain,
 * -1 for coil, turn and bend) replaced; field data `DSSP` (one string of DSSP letters per
 * chain, '-' for coil), `ResidueSecondaryStructure` (unsigned char, per amino-acid residue in
 * order), `ResidueIndexOfAssignment` (int, their `ResidueIndex`), `HydrogenBonds`.
 *
 * KeepFileRecords keeps the file's HELIX/SHEET classes (the input's `SecondaryStructure`) when
 * it has any, instead of recomputing them. HysteresisFrames > 1 keeps a trajectory's cartoon from
 * flickering: while the filter is updated for later and later time steps, a residue changes
 * class only once the new class has held for that many frames (a jump back in time starts
 * over).
 *
 * Errors (atoms without `AtomName` or `ResidueIndex`, a non-finite backbone coordinate) are
 * reported with vtkErrorMacro and give an empty output.
 */
#ifndef vtkMesoSecondaryStructure_h
#define vtkMesoSecondaryStructure_h

#include "MesoLensFiltersModule.h"
#include "vtkPolyDataAlgorithm.h"

#include <memory>

class MESOLENSFILTERS_EXPORT vtkMesoSecondaryStructure : public vtkPolyDataAlgorithm
{
public:
  static vtkMesoSecondaryStructure* New();
  vtkTypeMacro(vtkMesoSecondaryStructure, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Keep the file's HELIX/SHEET records when the input has any. Default off (recompute).
  vtkSetMacro(KeepFileRecords, bool);
  vtkGetMacro(KeepFileRecords, bool);
  vtkBooleanMacro(KeepFileRecords, bool);
  ///@}

  ///@{
  /// pi helices before alpha helices (DSSP 4, mkdssp 4.x). Off: the classic order (DSSP 2).
  /// See mesolens::DsspParams::pi_helix_priority.
  vtkSetMacro(PiHelixPriority, bool);
  vtkGetMacro(PiHelixPriority, bool);
  vtkBooleanMacro(PiHelixPriority, bool);
  ///@}

  ///@{
  /// Residues in a row with polyproline II angles for a polyproline helix; 0: none (DSSP 2).
  /// See mesolens::DsspParams::polyproline_stretch (the filter takes at most 10).
  vtkSetClampMacro(PolyprolineStretch, int, 0, 10);
  vtkGetMacro(PolyprolineStretch, int);
  ///@}

  ///@{
  /// Join ladders across beta bulges (DSSP). Off: each ladder alone (PyDSSP, MDAnalysis).
  /// See mesolens::DsspParams::bulges.
  vtkSetMacro(Bulges, bool);
  vtkGetMacro(Bulges, bool);
  vtkBooleanMacro(Bulges, bool);
  ///@}

  ///@{
  /// Use the file's amide hydrogens where present; off: placed as DSSP does, so files with and
  /// without hydrogens agree. See mesolens::DsspParams::file_hydrogens.
  vtkSetMacro(UseFileHydrogens, bool);
  vtkGetMacro(UseFileHydrogens, bool);
  vtkBooleanMacro(UseFileHydrogens, bool);
  ///@}

  ///@{
  /// Frames a new class must hold before a residue shows it; range [1, 100], default 1 (no
  /// delay).
  vtkSetClampMacro(HysteresisFrames, int, 1, 100);
  vtkGetMacro(HysteresisFrames, int);
  ///@}

protected:
  vtkMesoSecondaryStructure();
  ~vtkMesoSecondaryStructure() override;

  /// Streaming one process's pieces: every piece computes on the whole input (see
  /// vtkMesoAtomPieces::GatheredInput).
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector** inputVector,
                          vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
                  vtkInformationVector* outputVector) override;

  // Set by the constructor from mesolens::DsspParams' defaults.
  bool PiHelixPriority;
  int PolyprolineStretch;
  bool Bulges;
  bool UseFileHydrogens;
  // The filter's own.
  bool KeepFileRecords = false;
  int HysteresisFrames = 1;

private:
  vtkMesoSecondaryStructure(const vtkMesoSecondaryStructure&) = delete;
  void operator=(const vtkMesoSecondaryStructure&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
