// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * @class   vtkMesoTrajectoryReader
 * @brief   Reads GROMACS trajectories (.xtc, .trr, multi-frame .gro) over a topology (.gro,
 *          .pdb or .cif) as a temporal source of atoms and bonds.
 *
 * The topology gives names, residues, elements, molecules and bonds (computed once, on whole
 * molecules); the trajectory gives coordinates. Decoding is done by GROMACS' own library.
 * The reader reports TIME_STEPS (frame times in ps) and, on each request, decodes the one frame
 * whose time is the latest not after UPDATE_TIME_STEP (clamped to the first/last frame), through
 * an offset index built once from the frame headers: memory stays O(atoms) however long the
 * trajectory. Without TrajectoryFileName, the frames of the topology file itself are read
 * (a .gro may hold several; a .pdb gives one).
 *
 * The output has the arrays of vtkMesoStructureReader (see there), plus field data `TimePs`,
 * `FrameIndex`, `Step` and `PeriodicBoxVectors` (9 doubles in the output length unit, rows a, b,
 * c; orthorhombic or triclinic).
 *
 * Periodic boundaries: with MakeMoleculesWhole, atoms split across the box are moved by box
 * vectors so every molecule is whole; with KeepMoleculesContinuous, a molecule is additionally
 * kept from jumping across the box between frames (its centroid stays at the image closest to
 * that of the previous frame; frames up to the requested one are visited once, in order, the
 * first time they are needed).
 *
 * Errors (missing/empty/garbage file, truncated trajectory, atom-count mismatch between
 * topology and trajectory, non-finite coordinates) are reported with vtkErrorMacro naming the
 * file; the output is then empty and the update fails.
 */
#ifndef vtkMesoTrajectoryReader_h
#define vtkMesoTrajectoryReader_h

#include "MesoLensFiltersModule.h"
#include "vtkMesoAtomReader.h"

#include <memory>
#include <string>

class MESOLENSFILTERS_EXPORT vtkMesoTrajectoryReader : public vtkMesoAtomReader
{
public:
  static vtkMesoTrajectoryReader* New();
  vtkTypeMacro(vtkMesoTrajectoryReader, vtkMesoAtomReader);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Topology: a .gro, .pdb or .cif file whose atoms match the trajectory's. Default: none,
  /// which takes the topology beside the trajectory (mesolens::topology_beside: the same name
  /// with a topology extension, or the only topology file in its folder).
  vtkSetStdStringFromCharMacro(TopologyFileName);
  vtkGetCharFromStdStringMacro(TopologyFileName);
  ///@}

  ///@{
  /// Trajectory: .xtc, .trr or .gro. Optional (see the class description). Default: none.
  vtkSetStdStringFromCharMacro(TrajectoryFileName);
  vtkGetCharFromStdStringMacro(TrajectoryFileName);
  ///@}

  /// 1 when the extension is one this reader handles as a trajectory (.xtc, .trr, .gro).
  static int CanReadFile(const char* fileName);

  /// Length unit of the output coordinates and box.
  enum LengthUnits
  {
    ANGSTROM = 0,
    NANOMETER = 1
  };

  ///@{
  /// Output length unit. Default: ANGSTROM (GROMACS' nm are multiplied by 10).
  vtkSetClampMacro(LengthUnit, int, ANGSTROM, NANOMETER);
  vtkGetMacro(LengthUnit, int);
  void SetLengthUnitToAngstrom()
  {
    this->SetLengthUnit(ANGSTROM);
  }
  void SetLengthUnitToNanometer()
  {
    this->SetLengthUnit(NANOMETER);
  }
  ///@}

  ///@{
  /// Make molecules whole across periodic boundaries. Default: true.
  vtkSetMacro(MakeMoleculesWhole, bool);
  vtkGetMacro(MakeMoleculesWhole, bool);
  vtkBooleanMacro(MakeMoleculesWhole, bool);
  ///@}

  ///@{
  /// Keep molecules from jumping across the box between frames (needs MakeMoleculesWhole).
  /// Default: true.
  vtkSetMacro(KeepMoleculesContinuous, bool);
  vtkGetMacro(KeepMoleculesContinuous, bool);
  vtkBooleanMacro(KeepMoleculesContinuous, bool);
  ///@}

  ///@{
  /// Index the complete frames of a trajectory whose last frame is cut short (a run still
  /// being written) instead of failing. Default: false.
  vtkSetMacro(SkipIncompleteFrames, bool);
  vtkGetMacro(SkipIncompleteFrames, bool);
  vtkBooleanMacro(SkipIncompleteFrames, bool);
  ///@}

  /// Number of frames (valid after UpdateInformation; 0 on error).
  int GetNumberOfFrames();

  /// Number of atoms in the topology (valid after UpdateInformation; 0 on error).
  vtkIdType GetNumberOfTopologyAtoms();

protected:
  vtkMesoTrajectoryReader();
  ~vtkMesoTrajectoryReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string TopologyFileName;
  std::string TrajectoryFileName;
  int LengthUnit = ANGSTROM;
  bool MakeMoleculesWhole = true;
  bool KeepMoleculesContinuous = true;
  bool SkipIncompleteFrames = false;

private:
  vtkMesoTrajectoryReader(const vtkMesoTrajectoryReader&) = delete;
  void operator=(const vtkMesoTrajectoryReader&) = delete;

  bool OpenIfNeeded();
  std::size_t FrameForTime(double time) const;

  struct State;
  std::unique_ptr<State> Internal;
};

#endif
