// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * @class   vtkMesoStructureReader
 * @brief   Reads PDB and PDBx/mmCIF files (plain or .gz) into atoms and bonds, losing no atom.
 *
 * Parsing is done by gemmi. Unlike vtkPDBReader, every atom is kept: hydrogens, HETATM
 * records, waters and (optionally) every alternate location. PDB files written by MD programs
 * keep their true serials and residue numbers past 99999 and 9999: hybrid-36 (also in CONECT),
 * numbers written in full that shift the rest of the record, and numbers written modulo 100000
 * and 10000 as GROMACS writes them (see mesolens::read_structure()); four-letter residue names
 * (DPPC) are kept whole.
 *
 * Output: a vtkPolyData with one point and one vertex cell per atom (coordinates in Å), one
 * line cell per bond, and these point arrays:
 * - `AtomName`, `Element` (symbol, "X" when unknown or a coarse-grained bead), `ResidueName`,
 *   `ChainId` (author chain), `InsertionCode`, `AltLoc` (vtkStringArray, "" when blank);
 * - `AtomicNumber` (unsigned short, 0 = unknown/bead; the active scalars, so stock mappers colour
 *   atoms through a lookup table such as vtkMesoElementLookupTable);
 * - `ResidueNumber` (author number), `SerialNumber`, `ResidueIndex` (0-based running residue),
 *   `MoleculeId` (0-based; one per residue, except that the polymer residues of a chain form
 *   one molecule), `SecondaryStructureId` (index of the HELIX/strand span, -1 = none) (int);
 * - `Occupancy`, `BFactor` (Å²) (float); `IsHetAtm` (0/1), `FormalCharge` (signed char);
 * - `SecondaryStructure` (unsigned char: 0 coil, 1 alpha helix, 2 3-10 helix, 3 pi helix,
 *   4 strand, 8 other helix) from HELIX/SHEET records or struct_conf/struct_sheet_range.
 * Field data: `PeriodicBoxVectors` (9 doubles, Å) when CRYST1/_cell gives a crystal cell,
 * `CoarseGrained` (1 when bonds were perceived between beads), `ModelIndex`, `Title`.
 *
 * Bonds: CONECT records, LINK/SSBOND/struct_conn covalent and disulfide links, and (when
 * PerceiveBonds is on) distance-based perception inside each molecule: d < r_cov(a) + r_cov(b) +
 * BondTolerance, in O(n) with a spatial grid. Files of coarse-grained beads (detected, or forced
 * with ForceCoarseGrained) bond beads of a molecule closer than CoarseGrainedBeadCutoff.
 *
 * Biological assemblies (PDB REMARK 350, mmCIF _pdbx_struct_assembly*; see
 * mesolens::read_structure): Assembly names one (as the file does: "1", "2", "PAU"); the output
 * is then its atoms, every copy of the asymmetric unit that makes it (mesolens::expand_assembly),
 * with the int point array `AssemblyCopy` (0-based copy; copy c of chain "A" is named "A" for
 * c = 0 and "A-(c + 1)" after) and no periodic box. GetNumberOfAssemblies() and the
 * GetAssembly*() functions list what the file has. Output 1 holds the chosen assembly's copies
 * as instances (vtkMesoAssemblyInstances.h: a point per copy with its matrix and orientation;
 * empty without an assembly); with ExpandAssembly off, output 0 stays the asymmetric unit, and
 * a vtkGlyph3DMapper of output 1 (orientation `AssemblyOrientation` as a quaternion, no
 * scaling) draws one copy's ribbons or surface as the whole assembly, in one instanced call.
 *
 * Models (NMR ensembles) are time steps: TIME_STEPS = 0, 1, ..., NumberOfModels - 1, and
 * UPDATE_TIME_STEP t selects model round(t), clamped to the valid range.
 *
 * On a missing, empty, truncated or malformed file, or NaN coordinates, the reader reports the
 * file and the problem with vtkErrorMacro, leaves the output empty and the update fails.
 */
#ifndef vtkMesoStructureReader_h
#define vtkMesoStructureReader_h

#include "MesoLensFiltersModule.h"
#include "vtkMesoAtomReader.h"

#include <memory>
#include <string>

namespace mesolens {
struct Assembly;
struct AtomTable;
}

class MESOLENSFILTERS_EXPORT vtkMesoStructureReader : public vtkMesoAtomReader
{
public:
  static vtkMesoStructureReader* New();
  vtkTypeMacro(vtkMesoStructureReader, vtkMesoAtomReader);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Path of the .pdb, .ent, .cif or .mmcif file (optionally .gz). Default: none.
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  /// 1 when the file looks like PDB or mmCIF (by extension, else by content); 0 otherwise.
  static int CanReadFile(const char* fileName);

  ///@{
  /// Keep every alternate location instead of the highest-occupancy conformer of each residue;
  /// see mesolens::StructureReadParams::alt_locs (on: KeepAll).
  vtkSetMacro(KeepAllAlternateLocations, bool);
  vtkGetMacro(KeepAllAlternateLocations, bool);
  vtkBooleanMacro(KeepAllAlternateLocations, bool);
  ///@}

  ///@{
  /// Drop hydrogen (and deuterium) atoms; see mesolens::StructureReadParams::remove_hydrogens.
  vtkSetMacro(RemoveHydrogens, bool);
  vtkGetMacro(RemoveHydrogens, bool);
  vtkBooleanMacro(RemoveHydrogens, bool);
  ///@}

  ///@{
  /// The biological assembly to build, by the file's name for it ("1"); "" (default): the
  /// asymmetric unit, the atoms as the file gives them. A name the file does not define is an
  /// error naming the ones it does.
  vtkSetStdStringFromCharMacro(Assembly);
  vtkGetCharFromStdStringMacro(Assembly);
  ///@}

  ///@{
  /// Output 0 is the assembly's atoms (on, default) or the asymmetric unit's (off: draw the
  /// copies from output 1 instead). Without an Assembly, output 0 is the asymmetric unit.
  vtkSetMacro(ExpandAssembly, bool);
  vtkGetMacro(ExpandAssembly, bool);
  vtkBooleanMacro(ExpandAssembly, bool);
  ///@}

  ///@{
  /// The most atoms an assembly may have (about 175 bytes each); a larger one is an error that
  /// says how many it has. Range [1, 2^31 - 1]; default 3e7 (1m4x, a whole PBCV-1 capsid: 16.3
  /// million).
  vtkSetClampMacro(MaximumAssemblyAtoms, int, 1, 2147483647);
  vtkGetMacro(MaximumAssemblyAtoms, int);
  ///@}

  /// Number of models in the file (valid after UpdateInformation; 0 on error).
  int GetNumberOfModels();

  /// Number of biological assemblies the file defines (after UpdateInformation; 0 on error).
  int GetNumberOfAssemblies();
  /// Name (what Assembly takes), description and copies of assembly `index` in [0,
  /// GetNumberOfAssemblies()); "" and 0 out of range.
  const char* GetAssemblyName(int index);
  const char* GetAssemblyDetails(int index);
  vtkIdType GetAssemblyCopyCount(int index);
  /// Atoms of assembly `index` built from the first model with the reader's options.
  vtkIdType GetAssemblyAtomCount(int index);

  /// Title of the entry (TITLE or _struct.title), valid after UpdateInformation.
  const char* GetTitle();

  /// Warnings of the last read (e.g. CONECT records naming missing atoms), one per line.
  const char* GetWarnings();

protected:
  vtkMesoStructureReader();
  ~vtkMesoStructureReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  // Set by the constructor from mesolens::StructureReadParams' defaults.
  bool KeepAllAlternateLocations;
  bool RemoveHydrogens;
  // The reader's own.
  std::string FileName;
  std::string Assembly;
  int MaximumAssemblyAtoms = 30000000;
  bool ExpandAssembly = true;

private:
  vtkMesoStructureReader(const vtkMesoStructureReader&) = delete;
  void operator=(const vtkMesoStructureReader&) = delete;

  /// Parses the file unless the cached parse is newer than every setting.
  bool ReadIfNeeded();

  /// The assembly Assembly names, or nullptr for the asymmetric unit; false (after an error
  /// naming the file's assemblies) when the file has no such assembly.
  bool ChosenAssembly(const mesolens::Assembly*& assembly);

  /// Output 1 (the copies) and, with ExpandAssembly, output 0 (the atoms) of `assembly`; false
  /// after an error.
  bool WriteAssembly(const mesolens::AtomTable& asymmetric_unit, const mesolens::Assembly& assembly,
                     vtkPolyData* atoms, vtkPolyData* copies);

  struct Cache;
  std::unique_ptr<Cache> Parsed;
};

#endif
