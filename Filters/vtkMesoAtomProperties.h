// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * @class   vtkMesoAtomProperties
 * @brief   Adds per-atom radii from the `AtomicNumber` array of a MesoLens atom reader.
 *
 * Adds float point arrays `VanDerWaalsRadius` (Bondi 1964 / Alvarez 2013) and
 * `CovalentRadius` (Cordero 2008), in Å times LengthScale, so VTK's stock glyph and sphere
 * mappers can draw space-filling or ball-and-stick atoms. Atoms with atomic number 0
 * (unknown, coarse-grained beads) get BeadRadius. The input must carry `AtomicNumber`;
 * otherwise the filter reports an error and leaves the output empty.
 */
#ifndef vtkMesoAtomProperties_h
#define vtkMesoAtomProperties_h

#include "MesoLensFiltersModule.h"
#include "vtkPolyDataAlgorithm.h"

class MESOLENSFILTERS_EXPORT vtkMesoAtomProperties : public vtkPolyDataAlgorithm
{
public:
  static vtkMesoAtomProperties* New();
  vtkTypeMacro(vtkMesoAtomProperties, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Factor from Å to the input's length unit (0.1 for nm). Range (0, 1e6]; default 1.
  vtkSetClampMacro(LengthScale, double, 1e-12, 1e6);
  vtkGetMacro(LengthScale, double);
  ///@}

  ///@{
  /// Radius of atoms with unknown element and of coarse-grained beads, in Å (scaled by
  /// LengthScale), [0.1, 10]; default mesolens::bead_radius (a Martini bead).
  vtkSetClampMacro(BeadRadius, double, 0.1, 10.0);
  vtkGetMacro(BeadRadius, double);
  ///@}

protected:
  vtkMesoAtomProperties();
  ~vtkMesoAtomProperties() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double LengthScale = 1.0;
  double BeadRadius; // set by the constructor

private:
  vtkMesoAtomProperties(const vtkMesoAtomProperties&) = delete;
  void operator=(const vtkMesoAtomProperties&) = delete;
};

#endif
