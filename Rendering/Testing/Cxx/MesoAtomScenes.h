// SPDX-License-Identifier: GPL-3.0-or-later
// Scenes of the atom-mapper tests: real molecules from Data/ with fixed windows and cameras.
#pragma once

#include "vtkMesoAtomMapper.h"
#include "vtkMesoMembraneMapping.h"
#include "vtkMesoMeshReader.h"
#include "vtkMesoStructureReader.h"
#include "vtkMesoStructuredCutaway.h"
#include "vtkMesoTrajectoryReader.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPlane.h>
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>

#include <string>

namespace mesolens_test {

/// Crambin (1CRN, 327 atoms with bonds) read from Data/.
inline vtkSmartPointer<vtkMesoStructureReader> crambin()
{
  auto reader = vtkSmartPointer<vtkMesoStructureReader>::New();
  reader->SetFileName((std::string(MESOLENS_DATA_DIR) + "/proteins/1crn.pdb").c_str());
  reader->Update();
  return reader;
}

/// An off-screen window without multisampling (the pictures must be reproducible).
inline vtkSmartPointer<vtkRenderWindow> test_window(int width, int height)
{
  auto window = vtkSmartPointer<vtkRenderWindow>::New();
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(width, height);
  return window;
}

/// Looks at the centre of `atoms` from `distance` along +z.
inline void look_at(vtkRenderer* renderer, vtkPolyData* atoms, double distance)
{
  double centre[3];
  atoms->GetCenter(centre);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetFocalPoint(centre);
  camera->SetPosition(centre[0], centre[1], centre[2] + distance);
  camera->SetViewUp(0, 1, 0);
  renderer->ResetCameraClippingRange();
}

/// A 2 x 2 tiling of the DPPC patch on the mitochondrion's outer membrane (µm; atoms at 1e-4),
/// POLYNOMIAL or MOLECULE_INSTANCING; with output_atoms off only the warp's field data.
/// `max_residual` (Å) is the polynomial's bound: a small one splits the tiles into pieces.
inline vtkSmartPointer<vtkMesoMembraneMapping> mapped_membrane(int method, bool output_atoms,
                                                               double max_residual = 1.0)
{
  auto surface = vtkSmartPointer<vtkMesoMeshReader>::New();
  surface->SetFileName(
    (std::string(MESOLENS_DATA_DIR) + "/meshes/mito5_outer_membrane.obj").c_str());
  surface->Update();
  auto membrane = vtkSmartPointer<vtkMesoTrajectoryReader>::New();
  membrane->SetTopologyFileName(
    (std::string(MESOLENS_DATA_DIR) + "/membranes/dppc128_slipids_323K.gro").c_str());
  membrane->RemoveWatersOn();
  auto mapping = vtkSmartPointer<vtkMesoMembraneMapping>::New();
  mapping->SetSurfaceConnection(surface->GetOutputPort());
  mapping->SetMembraneConnection(membrane->GetOutputPort());
  mapping->SetSeedPoint(surface->GetOutput()->GetPoint(1000));
  mapping->SetTiles(2);
  mapping->SetMembraneToMeshScale(1e-4);
  mapping->SetMappingMethod(method);
  mapping->SetOutputAtoms(output_atoms);
  mapping->SetMaximumPolynomialResidual(max_residual);
  mapping->Update();
  return mapping;
}

/// The mapped membrane (2 x 2 tiles) cut open by the structured cutaway along the mapping's
/// lattice (edges of 40 Å), the half-space beyond the surface at the seed: on the CPU path the
/// cutaway cuts the mapped atoms and the mapper draws them; on the GPU path (gpu) it cuts the
/// molecules' centres of the mapping without atoms, and the mapper warps the patch and hides
/// the molecules of each tile that the cutaway hides.
struct CutMembrane
{
  vtkSmartPointer<vtkMesoMembraneMapping> Mapping;
  vtkNew<vtkMesoStructuredCutaway> Cutaway;
  vtkNew<vtkPlane> Cut;
  vtkNew<vtkMesoAtomMapper> Mapper;

  CutMembrane(int method, bool gpu, double fraction = 0.6)
    : Mapping(mapped_membrane(method, !gpu))
  {
    this->Mapping->SetLatticeEdge(40e-4);
    this->Mapping->Update();
    const double* seed = this->Mapping->GetSeedPoint();
    double normal[3];
    this->Mapping->GetOutput()->GetFieldData()->GetArray("SeedNormal")->GetTuple(0, normal);
    // The filter cuts where the plane's function is <= 0: behind its normal.
    this->Cut->SetOrigin(seed[0], seed[1], seed[2]);
    this->Cut->SetNormal(-normal[0], -normal[1], -normal[2]);
    this->Cutaway->SetInputConnection(this->Mapping->GetOutputPort(0));
    this->Cutaway->SetStructureConnection(this->Mapping->GetOutputPort(2));
    this->Cutaway->MakeAssemblyWholeOff();
    this->Cutaway->SetCutFunction(this->Cut);
    this->Cutaway->SetFractionHidden(fraction);
    if (gpu)
    {
      this->Mapper->SetInputConnection(this->Mapping->GetInputConnection(1, 0));
      this->Mapper->SetWarpConnection(this->Cutaway->GetOutputPort());
    }
    else
    {
      this->Mapper->SetInputConnection(this->Cutaway->GetOutputPort());
    }
    this->Mapper->SetRadiusScale(1e-4);
  }
};

} // namespace mesolens_test
