// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * @class   vtkMesoSurfaceArea
 * @brief   The exact solvent-accessible (or van der Waals) area of every atom, and the
 *          enclosed volume.
 *
 * Each atom is a sphere of its radius plus ProbeRadius; mesolens::sphere_union_area gives the
 * exact area of each sphere's part of the union's surface (Gauss-Bonnet on the arcs that bound
 * it: no dots, no slices) and the union's exact volume. ProbeRadius 0 gives the van der Waals
 * surface.
 *
 * Radii: the point array RadiusArrayName when set (Å, > 0; e.g. the ProtOr radii of another
 * program, to compare), else the element's van der Waals radius (Bondi 1964 / Alvarez 2013)
 * from `AtomicNumber`, and BeadRadius for atoms without an element (coarse-grained beads).
 *
 * Output: the atoms (shallow copy) with the point array `AccessibleArea` (float, Å² per atom;
 * 0 for buried atoms), and field data `TotalArea` (Å²) and `Volume` (Å³).
 *
 * Errors (no atoms, a radius <= 0 or not finite, a non-finite position, a missing radius
 * array) are reported with vtkErrorMacro and give an empty output.
 */
#ifndef vtkMesoSurfaceArea_h
#define vtkMesoSurfaceArea_h

#include "MesoLensFiltersModule.h"
#include "vtkPolyDataAlgorithm.h"

class MESOLENSFILTERS_EXPORT vtkMesoSurfaceArea : public vtkPolyDataAlgorithm
{
public:
  static vtkMesoSurfaceArea* New();
  vtkTypeMacro(vtkMesoSurfaceArea, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Radius of the solvent probe, Å, [0, 10]; 0: the van der Waals surface. Default: the
  /// molecular surface's, mesolens::MolecularSurfaceParams::probe_radius (water), so both
  /// filters describe the same accessible surface.
  vtkSetClampMacro(ProbeRadius, double, 0.0, 10.0);
  vtkGetMacro(ProbeRadius, double);
  ///@}

  ///@{
  /// Point array of the atoms' radii (Å); nullptr or "" (default): radii from the elements.
  vtkSetStringMacro(RadiusArrayName);
  vtkGetStringMacro(RadiusArrayName);
  ///@}

  ///@{
  /// Radius of atoms without an element (AtomicNumber 0: beads), Å, [0.1, 10]; default
  /// mesolens::bead_radius (a Martini bead).
  vtkSetClampMacro(BeadRadius, double, 0.1, 10.0);
  vtkGetMacro(BeadRadius, double);
  ///@}

protected:
  vtkMesoSurfaceArea();
  ~vtkMesoSurfaceArea() override;

  /// Streaming one process's pieces: every piece computes on the whole input (see
  /// vtkMesoAtomPieces::GatheredInput).
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector** inputVector,
                          vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
                  vtkInformationVector* outputVector) override;

  double ProbeRadius; // set by the constructor
  char* RadiusArrayName = nullptr;
  double BeadRadius; // set by the constructor

private:
  vtkMesoSurfaceArea(const vtkMesoSurfaceArea&) = delete;
  void operator=(const vtkMesoSurfaceArea&) = delete;
};

#endif
