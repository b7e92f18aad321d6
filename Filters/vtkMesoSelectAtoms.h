// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * @class   vtkMesoSelectAtoms
 * @brief   Selects atoms with a text expression ("chain A and within 5 of resname LIG").
 *
 * Evaluates a selection (the language of mesolens/molecules/atom_selection.h: name, resname,
 * resid, chain, element, protein, water, lipid, backbone, and/or/not, within, same residue as,
 * comparisons on x, y, z and on any one-component point array) on the atoms of any MesoLens
 * atom reader (structure or trajectory; each time step is evaluated at its own positions).
 *
 * - OutputMode Mask (default): the atoms pass through unchanged with an unsigned char point
 *   array (MaskArrayName, default "Selected"): 1 for selected atoms, 0 for the others.
 * - OutputMode Extract: only the selected atoms, with every point array and the bonds (lines)
 *   between two selected atoms, their cell data and the field data (vtkMesoAtomPieces::
 *   ExtractAtoms, as vtkMesoStructuredCutaway's ExtractVisibleAtoms).
 *
 * Distances and coordinates in the expression are in Å; LengthScale says what the input's
 * length unit is in Å (0.1 for nm), like the readers' LengthScale. A bad expression, an array
 * it names that the input lacks, or an input that is not MesoLens atoms (no `AtomName`/
 * `ResidueIndex`) gives an error naming the problem (for expressions, the character) and an
 * empty output.
 */
#ifndef vtkMesoSelectAtoms_h
#define vtkMesoSelectAtoms_h

#include "MesoLensFiltersModule.h"
#include "vtkPolyDataAlgorithm.h"

#include <string>

class MESOLENSFILTERS_EXPORT vtkMesoSelectAtoms : public vtkPolyDataAlgorithm
{
public:
  static vtkMesoSelectAtoms* New();
  vtkTypeMacro(vtkMesoSelectAtoms, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The selection expression. Default "all".
  vtkSetStdStringFromCharMacro(Selection);
  vtkGetCharFromStdStringMacro(Selection);
  ///@}

  enum OutputModes
  {
    MASK = 0,
    EXTRACT = 1,
  };

  ///@{
  /// Whether the output is every atom with a mask array (MASK, default) or the selected atoms
  /// alone (EXTRACT).
  vtkSetClampMacro(OutputMode, int, MASK, EXTRACT);
  vtkGetMacro(OutputMode, int);
  void SetOutputModeToMask()
  {
    this->SetOutputMode(MASK);
  }
  void SetOutputModeToExtract()
  {
    this->SetOutputMode(EXTRACT);
  }
  ///@}

  ///@{
  /// Name of the mask array in MASK mode. Default "Selected"; must not be empty.
  vtkSetStdStringFromCharMacro(MaskArrayName);
  vtkGetCharFromStdStringMacro(MaskArrayName);
  ///@}

  ///@{
  /// Factor from Å to the input's length unit (0.1 for nm). Range (0, 1e6]; default 1.
  vtkSetClampMacro(LengthScale, double, 1e-12, 1e6);
  vtkGetMacro(LengthScale, double);
  ///@}

protected:
  vtkMesoSelectAtoms() = default;
  ~vtkMesoSelectAtoms() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string Selection = "all";
  int OutputMode = MASK;
  std::string MaskArrayName = "Selected";
  double LengthScale = 1.0;

private:
  vtkMesoSelectAtoms(const vtkMesoSelectAtoms&) = delete;
  void operator=(const vtkMesoSelectAtoms&) = delete;
};

#endif
