// SPDX-License-Identifier: GPL-3.0-or-later
// The protein part of a structure reader's atoms, for tests and benchmarks that wrap a protein
// in its surface: header-only, VTK.
#pragma once

#include "vtkMesoArrayNames.h"

#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedShortArray.h>

namespace mesolens_test {

/// The atoms of ATOM records (IsHetAtm 0, or every atom without that array), with their
/// AtomicNumber array alone.
inline vtkNew<vtkPolyData> protein_atoms(vtkPolyData* atoms)
{
  vtkNew<vtkPolyData> protein;
  vtkNew<vtkPoints> points;
  vtkNew<vtkUnsignedShortArray> elements;
  elements->SetName(vtkMesoArrayNames::AtomicNumber);
  vtkDataArray* hetero = atoms->GetPointData()->GetArray(vtkMesoArrayNames::IsHetAtm);
  vtkDataArray* numbers = atoms->GetPointData()->GetArray(vtkMesoArrayNames::AtomicNumber);
  for (vtkIdType a = 0; a < atoms->GetNumberOfPoints(); ++a)
  {
    if (!hetero || hetero->GetTuple1(a) == 0)
    {
      points->InsertNextPoint(atoms->GetPoint(a));
      elements->InsertNextValue(static_cast<unsigned short>(numbers->GetTuple1(a)));
    }
  }
  protein->SetPoints(points);
  protein->GetPointData()->AddArray(elements);
  return protein;
}

} // namespace mesolens_test
