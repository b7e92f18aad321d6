// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoDiskParameterization.h"

#include "vtkMesoArrayNames.h"

#include "vtkMesoSurfaceConversion.h"

#include "mesolens/common/errors.h"
#include "mesolens/mapping/harmonic_parameterization.h"

#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>

vtkStandardNewMacro(vtkMesoDiskParameterization);

int vtkMesoDiskParameterization::RequestData(vtkInformation*, vtkInformationVector** inputVector,
                                             vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  output->Initialize();
  double radius = this->Radius;
  if (radius <= 0)
  {
    vtkDataArray* stored = input->GetFieldData()->GetArray(vtkMesoArrayNames::GeodesicRadius);
    radius = stored ? stored->GetComponent(0, 0) : 0;
  }
  try
  {
    const mesolens::DiskParameterization map =
      mesolens::harmonic_parameterization(vtkMesoSurfaceConversion::ToTriangleMesh(input), radius);
    output->ShallowCopy(input);
    vtkMesoSurfaceConversion::AddParameterizationArrays(map, radius, output);
    if (!map.bijective())
    {
      vtkWarningMacro(<< map.flipped_triangles << " triangles are flipped in the parameterization");
    }
  }
  catch (const mesolens::Error& e)
  {
    vtkErrorMacro("Cannot parameterize the disk: " << e.what());
    output->Initialize();
    return 0;
  }
  return 1;
}

void vtkMesoDiskParameterization::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Radius: " << this->Radius << "\n";
}
