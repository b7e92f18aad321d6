// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoSurfaceArea.h"

#include "vtkMesoArrayNames.h"
#include "vtkMesoAtomPieces.h"

#include "vtkMesoAtomInput.h"
#include "vtkMesoAtomTableConversion.h"
#include "vtkMesoParallelFor.h"

#include "mesolens/common/errors.h"
#include "mesolens/molecules/elements.h"
#include "mesolens/surface/molecular_surface.h"
#include "mesolens/surface/sphere_union_area.h"

#include <vtkFloatArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <string>
#include <vector>

vtkStandardNewMacro(vtkMesoSurfaceArea);

vtkMesoSurfaceArea::vtkMesoSurfaceArea()
{
  this->ProbeRadius = mesolens::MolecularSurfaceParams().probe_radius;
  this->BeadRadius = mesolens::bead_radius;
}

vtkMesoSurfaceArea::~vtkMesoSurfaceArea()
{
  this->SetRadiusArrayName(nullptr);
}

int vtkMesoSurfaceArea::RequestUpdateExtent(vtkInformation*, vtkInformationVector** inputVector,
                                            vtkInformationVector* outputVector)
{
  vtkMesoAtomPieces::RequestWholeInputsWhenStreaming(inputVector, 1, outputVector);
  return 1;
}

int vtkMesoSurfaceArea::RequestData(vtkInformation*, vtkInformationVector** inputVector,
                                    vtkInformationVector* outputVector)
{
  // On many processes: computed on every process's atoms, this process's kept.
  const vtkMesoAtomPieces::GatheredInput gathered(inputVector[0], outputVector,
                                                  vtkMesoAtomPieces::GatheredInput::KeepOwn);
  vtkPolyData* atoms = gathered.Whole();
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  output->Initialize();
  if (!atoms || atoms->GetNumberOfPoints() == 0)
  {
    vtkErrorMacro("No atoms to measure.");
    return 0;
  }
  const vtkIdType n = atoms->GetNumberOfPoints();
  try
  {
    std::vector<std::array<double, 3>> centres;
    std::vector<double> radii;
    vtkMesoAtomInput::Spheres(atoms, this->RadiusArrayName, this->BeadRadius, centres, radii);
    for (double& radius : radii)
    {
      radius += this->ProbeRadius;
    }
    const mesolens::SphereUnionArea measured =
      mesolens::sphere_union_area(centres, radii, vtkMesoParallelFor::Get());
    output->ShallowCopy(atoms);
    vtkNew<vtkFloatArray> areas;
    areas->SetName(vtkMesoArrayNames::AccessibleArea);
    areas->SetNumberOfValues(n);
    for (vtkIdType a = 0; a < n; ++a)
    {
      areas->SetValue(a, static_cast<float>(measured.per_sphere[std::size_t(a)]));
    }
    output->GetPointData()->AddArray(areas);
    vtkMesoAtomTableConversion::SetFieldValue(output, vtkMesoArrayNames::TotalArea, measured.total);
    vtkMesoAtomTableConversion::SetFieldValue(output, vtkMesoArrayNames::Volume, measured.volume);
  }
  catch (const mesolens::Error& error)
  {
    output->Initialize();
    vtkErrorMacro("Cannot measure the surface: " << error.what());
    return 0;
  }
  return 1;
}

void vtkMesoSurfaceArea::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ProbeRadius: " << this->ProbeRadius << "\n";
  os << indent
     << "RadiusArrayName: " << (this->RadiusArrayName ? this->RadiusArrayName : "(elements)")
     << "\n";
  os << indent << "BeadRadius: " << this->BeadRadius << "\n";
}
