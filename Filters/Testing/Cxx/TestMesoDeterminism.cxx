// SPDX-License-Identifier: GPL-3.0-or-later
// Every filter's output is bitwise the same on 1 and 2 threads of VTK's SMP tools and on 8 of
// MesoLens' own (MESOLENS_THREADS: VTK takes no more threads than cores), from one run to the next,
// and when two pipelines update in two threads at once (run under ThreadSanitizer with
// -DMESOLENS_ENABLE_THREAD_SANITIZER=ON, this last test is the race check).
#include "vtkMesoDiskParameterization.h"
#include "vtkMesoGeodesicDisk.h"
#include "vtkMesoMembraneMapping.h"
#include "vtkMesoMeshReader.h"
#include "vtkMesoMeshReport.h"
#include "vtkMesoMolecularSurface.h"
#include "vtkMesoRibbons.h"
#include "vtkMesoSecondaryStructure.h"
#include "vtkMesoStructureReader.h"
#include "vtkMesoStructuredCutaway.h"
#include "vtkMesoSurfaceArea.h"
#include "vtkMesoTrajectoryReader.h"
#include "vtkMesoTrajectoryRefinement.h"

#include "mesolens_test_data.h"

#include <vtkAlgorithm.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDataSet.h>
#include <vtkExecutive.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
#include <vtkInformation.h>
#include <vtkNew.h>
#include <vtkPlane.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSMPTools.h>
#include <vtkSmartPointer.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkStringArray.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <functional>
#include <string>
#include <thread>
#include <vector>

namespace {

using mesolens_test::data_file;

/// The bytes of every array of the field data `fields`, in order, with their names.
void append_arrays(vtkFieldData* fields, std::string& bytes)
{
  for (int a = 0; a < fields->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* array = fields->GetAbstractArray(a);
    bytes += array->GetName() ? array->GetName() : "(unnamed)";
    if (auto* strings = vtkStringArray::SafeDownCast(array))
    {
      for (vtkIdType v = 0; v < strings->GetNumberOfValues(); ++v)
      {
        bytes += strings->GetValue(v) + '\n';
      }
    }
    else if (array->GetNumberOfValues() > 0)
    {
      bytes.append(static_cast<const char*>(array->GetVoidPointer(0)),
                   std::size_t(array->GetNumberOfValues()) * std::size_t(array->GetDataTypeSize()));
    }
  }
}

/// Everything a filter put out, as bytes: points, polygons and lines, and every array.
std::string output_bytes(vtkAlgorithm* filter, int port = 0)
{
  auto* data = vtkDataSet::SafeDownCast(filter->GetOutputDataObject(port));
  std::string bytes;
  if (!data)
  {
    return bytes;
  }
  if (auto* poly = vtkPolyData::SafeDownCast(data))
  {
    if (poly->GetPoints())
    {
      vtkDataArray* points = poly->GetPoints()->GetData();
      bytes.append(static_cast<const char*>(points->GetVoidPointer(0)),
                   std::size_t(points->GetNumberOfValues()) *
                     std::size_t(points->GetDataTypeSize()));
    }
    for (vtkCellArray* cells : { poly->GetVerts(), poly->GetLines(), poly->GetPolys() })
    {
      vtkNew<vtkIdTypeArray> legacy;
      cells->ExportLegacyFormat(legacy);
      bytes.append(reinterpret_cast<const char*>(legacy->GetPointer(0)),
                   std::size_t(legacy->GetNumberOfValues()) * sizeof(vtkIdType));
    }
  }
  append_arrays(data->GetPointData(), bytes);
  append_arrays(data->GetCellData(), bytes);
  append_arrays(data->GetFieldData(), bytes);
  return bytes;
}

/// One pipeline per filter (built fresh each time), returning the bytes of its last filter's
/// outputs.
struct Pipeline
{
  const char* name;
  std::function<std::string()> run;
};

std::string ribbons()
{
  vtkNew<vtkMesoStructureReader> reader;
  reader->SetFileName(data_file("proteins/1tii.pdb").c_str());
  vtkNew<vtkMesoSecondaryStructure> dssp;
  dssp->SetInputConnection(reader->GetOutputPort());
  vtkNew<vtkMesoRibbons> ribbons;
  ribbons->SetInputConnection(dssp->GetOutputPort());
  EXPECT_EQ(ribbons->GetExecutive()->Update(), 1);
  return output_bytes(reader) + output_bytes(dssp) + output_bytes(ribbons);
}

std::string surfaces()
{
  vtkNew<vtkMesoStructureReader> reader;
  reader->SetFileName(data_file("proteins/1crn.pdb").c_str());
  vtkNew<vtkMesoMolecularSurface> surface;
  surface->SetInputConnection(reader->GetOutputPort());
  surface->SetTolerance(0.2);
  vtkNew<vtkMesoSurfaceArea> area;
  area->SetInputConnection(reader->GetOutputPort());
  EXPECT_EQ(surface->GetExecutive()->Update(), 1);
  EXPECT_EQ(area->GetExecutive()->Update(), 1);
  return output_bytes(surface) + output_bytes(area);
}

std::string mapping()
{
  vtkNew<vtkMesoMeshReader> mesh;
  mesh->SetFileName(data_file("meshes/mito5_outer_membrane.obj").c_str());
  vtkNew<vtkMesoMeshReport> report;
  report->SetInputConnection(mesh->GetOutputPort());
  report->Update();
  double seed[3];
  mesh->GetOutput()->GetPoint(1000, seed);
  vtkNew<vtkMesoGeodesicDisk> disk;
  disk->SetInputConnection(mesh->GetOutputPort());
  disk->SetSeedPoint(seed);
  disk->SetRadius(0.05);
  disk->SetMinimumTriangles(1000);
  vtkNew<vtkMesoDiskParameterization> parameterization;
  parameterization->SetInputConnection(disk->GetOutputPort());
  EXPECT_EQ(parameterization->GetExecutive()->Update(), 1);
  vtkNew<vtkMesoTrajectoryReader> membrane;
  membrane->SetTopologyFileName(data_file("membranes/dppc128_slipids_323K.gro").c_str());
  membrane->RemoveWatersOn();
  vtkNew<vtkMesoMembraneMapping> mapping;
  mapping->SetSurfaceConnection(mesh->GetOutputPort());
  mapping->SetMembraneConnection(membrane->GetOutputPort());
  mapping->SetSeedPoint(seed);
  mapping->SetTiles(2);
  mapping->SetMembraneToMeshScale(1e-4); // Å onto µm
  EXPECT_EQ(mapping->GetExecutive()->Update(), 1);
  return output_bytes(report) + output_bytes(parameterization) + output_bytes(mapping, 0) +
    output_bytes(mapping, 1) + output_bytes(mapping, 2);
}

std::string trajectory_and_cutaway()
{
  vtkNew<vtkMesoTrajectoryReader> reader;
  reader->SetTopologyFileName(data_file("membranes/martini_dppc_vesicle.gro").c_str());
  reader->SetTrajectoryFileName(data_file("membranes/martini_dppc_vesicle.xtc").c_str());
  vtkNew<vtkMesoTrajectoryRefinement> refinement;
  refinement->SetInputConnection(reader->GetOutputPort());
  refinement->SetRefinementLevels(1);
  refinement->UpdateInformation();
  const double* times =
    refinement->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  refinement->UpdateTimeStep(0.5 * (times[0] + times[1])); // between two frames
  vtkNew<vtkMesoStructuredCutaway> cutaway;
  cutaway->SetInputConnection(reader->GetOutputPort());
  vtkNew<vtkPlane> plane;
  plane->SetNormal(0, 0, 1);
  cutaway->SetCutFunction(plane);
  cutaway->SetFractionHidden(0.7);
  EXPECT_EQ(cutaway->GetExecutive()->Update(), 1);
  return output_bytes(refinement) + output_bytes(cutaway);
}

const Pipeline pipelines[] = {
  { "ribbons", ribbons },
  { "surfaces", surfaces },
  { "mapping", mapping },
  { "trajectory and cutaway", trajectory_and_cutaway },
};

} // namespace

TEST(Determinism, OneTwoAndEightThreadsGiveTheSameBytes)
{
  vtkSMPTools::SetBackend("STDThread");
  for (const Pipeline& pipeline : pipelines)
  {
    SCOPED_TRACE(pipeline.name);
    vtkSMPTools::Initialize(1);
    const std::string one = pipeline.run();
    ASSERT_GT(one.size(), 1000u);
    EXPECT_EQ(pipeline.run(), one) << "a second run on 1 thread differs";
    vtkSMPTools::Initialize(2);
    ASSERT_EQ(vtkSMPTools::GetEstimatedNumberOfThreads(), 2);
    EXPECT_EQ(pipeline.run(), one) << "2 threads differ from 1";
    // VTK's STDThread backend takes no more threads than cores: 8 threads of MesoLens' own.
    setenv("MESOLENS_THREADS", "8", 1);
    EXPECT_EQ(pipeline.run(), one) << "8 threads differ from 1";
    unsetenv("MESOLENS_THREADS");
  }
}

TEST(Determinism, TwoPipelinesInTwoThreadsGiveWhatEachGivesAlone)
{
  vtkSMPTools::SetBackend("STDThread");
  vtkSMPTools::Initialize(2);
  const std::string ribbons_alone = ribbons();
  const std::string mapping_alone = mapping();
  std::string ribbons_together, mapping_together;
  std::thread first([&] { ribbons_together = ribbons(); });
  std::thread second([&] { mapping_together = mapping(); });
  first.join();
  second.join();
  EXPECT_EQ(ribbons_together, ribbons_alone);
  EXPECT_EQ(mapping_together, mapping_alone);
}
