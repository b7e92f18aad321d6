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
  /// LengthScale). Martini beads are about 2.35 Å (van der Waals radius of a 0.47 nm bead).
  /// Range [0.1, 10]; default 2.35.
  vtkSetClampMacro(BeadRadius, double, 0.1, 10.0);
  vtkGetMacro(BeadRadius, double);
  ///@}

protected:
  vtkMesoAtomProperties() = default;
  ~vtkMesoAtomProperties() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double LengthScale = 1.0;
  double BeadRadius = 2.35;

private:
  vtkMesoAtomProperties(const vtkMesoAtomProperties&) = delete;
  void operator=(const vtkMesoAtomProperties&) = delete;
};

#endif
