// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * @class   vtkMesoAtomReader
 * @brief   Base of the MesoLens atom readers: the options they share (waters, bonds).
 *
 * vtkMesoStructureReader and vtkMesoTrajectoryReader derive from it. Bonds come from the
 * file's records where it has them, and, with PerceiveBonds, from distances inside each
 * molecule: atoms bond when closer than r_cov(a) + r_cov(b) + BondTolerance (covalent radii of
 * Cordero 2008). Files of coarse-grained beads (Martini) are recognised when they name no
 * elements and covalent radii bond almost nothing; their beads bond when closer than
 * CoarseGrainedBeadCutoff, and the bonds are then made identical across all copies of each
 * molecule type (a pair is kept when at least half of the copies have it).
 */
#ifndef vtkMesoAtomReader_h
#define vtkMesoAtomReader_h

#include "MesoLensFiltersModule.h"
#include "vtkPolyDataAlgorithm.h"

class MESOLENSFILTERS_EXPORT vtkMesoAtomReader : public vtkPolyDataAlgorithm
{
public:
  vtkTypeMacro(vtkMesoAtomReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Drop water molecules (HOH, WAT, SOL, TIP3, ...) from the output; see
  /// mesolens::StructureReadParams::remove_waters.
  vtkSetMacro(RemoveWaters, bool);
  vtkGetMacro(RemoveWaters, bool);
  vtkBooleanMacro(RemoveWaters, bool);
  ///@}

  ///@{
  /// Perceive covalent bonds from distances (explicit records are always used); see
  /// mesolens::StructureReadParams::perceive_bonds.
  vtkSetMacro(PerceiveBonds, bool);
  vtkGetMacro(PerceiveBonds, bool);
  vtkBooleanMacro(PerceiveBonds, bool);
  ///@}

  ///@{
  /// Tolerance added to the sum of covalent radii; see
  /// mesolens::BondPerceptionParams::tolerance.
  vtkSetClampMacro(BondTolerance, double, 0.0, 1.0);
  vtkGetMacro(BondTolerance, double);
  ///@}

  ///@{
  /// Bond cutoff between coarse-grained beads of one molecule; see
  /// mesolens::BondPerceptionParams::bead_cutoff (the filter takes at least 0.5).
  vtkSetClampMacro(CoarseGrainedBeadCutoff, double, 0.5, 10.0);
  vtkGetMacro(CoarseGrainedBeadCutoff, double);
  ///@}

  ///@{
  /// Treat the particles as coarse-grained beads even when they do not look so; see
  /// mesolens::StructureReadParams::force_coarse_grained.
  vtkSetMacro(ForceCoarseGrained, bool);
  vtkGetMacro(ForceCoarseGrained, bool);
  vtkBooleanMacro(ForceCoarseGrained, bool);
  ///@}

protected:
  vtkMesoAtomReader();
  ~vtkMesoAtomReader() override = default;

  // Set by the constructor from mesolens::StructureReadParams' defaults.
  bool RemoveWaters;
  bool PerceiveBonds;
  double BondTolerance;
  double CoarseGrainedBeadCutoff;
  bool ForceCoarseGrained;

private:
  vtkMesoAtomReader(const vtkMesoAtomReader&) = delete;
  void operator=(const vtkMesoAtomReader&) = delete;
};

#endif
