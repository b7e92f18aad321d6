// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoGeodesicDisk.h"

#include "vtkMesoSurfaceConversion.h"

#include "mesolens/common/errors.h"
#include "mesolens/mapping/geodesic_disk.h"
#include "mesolens/mapping/membrane_mapper.h"

#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>

vtkStandardNewMacro(vtkMesoGeodesicDisk);

struct vtkMesoGeodesicDisk::Cache
{
  vtkMesoSurfaceConversion::SurfaceMapper Mapper;
};

vtkMesoGeodesicDisk::vtkMesoGeodesicDisk()
  : Solver(new Cache)
{
  const mesolens::GeodesicDiskParams defaults;
  this->MinimumTriangles = static_cast<int>(defaults.min_triangles);
  this->MaximumTriangles = static_cast<int>(defaults.max_triangles);
}

vtkMesoGeodesicDisk::~vtkMesoGeodesicDisk() = default;

int vtkMesoGeodesicDisk::RequestData(vtkInformation*, vtkInformationVector** inputVector,
                                     vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  output->Initialize();
  try
  {
    const mesolens::MembraneMapper& mapper = this->Solver->Mapper.For(input, input->GetMTime());
    this->UpdateProgress(0.5);
    mesolens::GeodesicDiskParams params;
    params.radius = this->Radius;
    params.min_triangles = static_cast<std::size_t>(this->MinimumTriangles);
    params.max_triangles = static_cast<std::size_t>(this->MaximumTriangles);
    const mesolens::GeodesicDisk disk = mesolens::geodesic_disk(
      mapper.surface(),
      mapper.seed_near({ this->SeedPoint[0], this->SeedPoint[1], this->SeedPoint[2] },
                       this->SeedTolerance),
      params);
    vtkMesoSurfaceConversion::FromTriangleMesh(disk.mesh, output);
    vtkMesoSurfaceConversion::AddDiskArrays(disk, this->Radius, output);
  }
  catch (const mesolens::Error& e)
  {
    vtkErrorMacro("Cannot grow the geodesic disk: " << e.what());
    output->Initialize();
    return 0;
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkMesoGeodesicDisk::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SeedPoint: (" << this->SeedPoint[0] << ", " << this->SeedPoint[1] << ", "
     << this->SeedPoint[2] << ")\n";
  os << indent << "SeedTolerance: " << this->SeedTolerance << "\n";
  os << indent << "Radius: " << this->Radius << "\n";
  os << indent << "MinimumTriangles: " << this->MinimumTriangles << "\n";
  os << indent << "MaximumTriangles: " << this->MaximumTriangles << "\n";
}
