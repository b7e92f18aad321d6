// SPDX-License-Identifier: GPL-3.0-or-later
// What the atom-drawing benchmarks share: an offscreen window with one actor and MesoLens' render
// passes (plain or SSAO), frame timing, VTK's sphere mapper set up as the demo does, and a
// membrane mapped onto the mitochondrion of Data/.
#pragma once

#include "vtkMesoArrayNames.h"
#include "vtkMesoAtomProperties.h"
#include "vtkMesoElementLookupTable.h"
#include "vtkMesoMembraneMapping.h"
#include "vtkMesoMeshReader.h"
#include "vtkMesoRenderPasses.h"
#include "vtkMesoTrajectoryReader.h"

#include "mesolens_benchmark_timing.h"
#include "mesolens_test_data.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLRenderer.h>
#include <vtkOpenGLSphereMapper.h>
#include <vtkOpenGLVertexBufferObject.h>
#include <vtkOpenGLVertexBufferObjectGroup.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace mesolens_bench {

using mesolens_test::median;

/// VTK's sphere mapper set up as the MesoLens demo does: van der Waals radii, element colours.
struct VTKSpheres
{
  vtkNew<vtkMesoAtomProperties> Radii;
  vtkNew<vtkOpenGLSphereMapper> Mapper;
  vtkNew<vtkMesoElementLookupTable> Elements;

  explicit VTKSpheres(vtkPolyData* atoms)
  {
    this->Radii->SetInputData(atoms);
    this->Radii->Update();
    this->Mapper->SetInputConnection(this->Radii->GetOutputPort());
    this->Mapper->SetScaleArray(vtkMesoArrayNames::VanDerWaalsRadius);
    this->Mapper->SetLookupTable(this->Elements);
    this->Mapper->UseLookupTableScalarRangeOn();
    this->Mapper->SetScalarModeToUsePointFieldData();
    this->Mapper->SelectColorArray(vtkMesoArrayNames::AtomicNumber);
    this->Mapper->SetColorModeToMapScalars();
  }

  /// Bytes of all its vertex buffers per atom.
  double BytesPerAtom(vtkIdType atoms)
  {
    double bytes = 0;
    for (const char* name : { "vertexMC", "offsetMC", "radiusMC", "scalarColor", "normalMC" })
    {
      if (vtkOpenGLVertexBufferObject* vbo = this->Mapper->GetVBOs()->GetVBO(name))
      {
        bytes += double(vbo->GetStride()) * vbo->GetNumberOfTuples();
      }
    }
    return bytes / double(atoms);
  }
};

/// A membrane of Data/ (`topology`, waters removed) mapped onto the mitochondrion's outer
/// membrane by the polynomial method, `tiles` x `tiles`, in a µm scene (1e-4 per Å), from the
/// surface's vertex 1000; not updated.
struct MitochondrionMapping
{
  vtkNew<vtkMesoMeshReader> Surface;
  vtkNew<vtkMesoTrajectoryReader> Membrane;
  vtkNew<vtkMesoMembraneMapping> Mapping;

  MitochondrionMapping(const std::string& topology, int tiles)
  {
    this->Surface->SetFileName(mesolens_test::data_file("meshes/mito5_outer_membrane.obj").c_str());
    this->Surface->Update();
    this->Membrane->SetTopologyFileName(topology.c_str());
    this->Membrane->RemoveWatersOn();
    this->Mapping->SetSurfaceConnection(this->Surface->GetOutputPort());
    this->Mapping->SetMembraneConnection(this->Membrane->GetOutputPort());
    this->Mapping->SetSeedPoint(this->Surface->GetOutput()->GetPoint(1000));
    this->Mapping->SetTiles(tiles);
    this->Mapping->SetMembraneToMeshScale(1e-4);
    this->Mapping->SetMappingMethodToPolynomial();
  }
};

/// A window with one renderer and one actor; the renderer's passes are plain or SSAO.
struct Stage
{
  vtkSmartPointer<vtkOpenGLRenderWindow> Window =
    vtkOpenGLRenderWindow::SafeDownCast(vtkSmartPointer<vtkRenderWindow>::New());
  vtkSmartPointer<vtkOpenGLRenderer> Renderer =
    vtkOpenGLRenderer::SafeDownCast(vtkSmartPointer<vtkRenderer>::New());
  vtkNew<vtkActor> Actor;
  vtkNew<vtkMesoRenderPasses> Effects;

  explicit Stage(int width = 1024, int height = 768)
  {
    this->Window->SetOffScreenRendering(1);
    this->Window->SetMultiSamples(0);
    this->Window->SetSize(width, height);
    this->Window->AddRenderer(this->Renderer);
    this->Renderer->AddActor(this->Actor);
    this->Renderer->SetBackground(0.1, 0.1, 0.15);
    this->Effects->SetSSAORadius(4.0);
    this->Effects->SetSSAOBias(0.05);
    this->Effects->SetSSAOKernelSize(32);
  }

  void Show(vtkMapper* mapper, bool ssao)
  {
    this->Actor->SetMapper(mapper);
    this->Effects->SetSSAO(ssao);
    this->Effects->Apply(this->Renderer);
    // The same view every time: down the membrane normal, then 40 degrees off it.
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    camera->SetFocalPoint(0, 0, 0);
    camera->SetPosition(0, 0, 1);
    camera->SetViewUp(0, 1, 0);
    this->Renderer->ResetCamera();
    camera->Elevation(-40);
    camera->Zoom(1.6);
    this->Renderer->ResetCameraClippingRange();
  }

  /// The same as Show, but from the camera `start` (the view another mapper was shown with):
  /// the same pictures for the same atoms, whatever each mapper's bounds.
  void ShowFrom(vtkMapper* mapper, bool ssao, vtkCamera* start)
  {
    this->Actor->SetMapper(mapper);
    this->Effects->SetSSAO(ssao);
    this->Effects->Apply(this->Renderer);
    this->Renderer->GetActiveCamera()->DeepCopy(start);
  }

  double Frame()
  {
    const auto start = std::chrono::steady_clock::now();
    this->Window->Render();
    this->Window->WaitForCompletion();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  /// The first frame (buffers built and uploaded), then the median of `frames` turning ones.
  std::pair<double, double> Time(int frames)
  {
    const double first = this->Frame();
    std::vector<double> times;
    for (int f = 0; f < frames; ++f)
    {
      this->Renderer->GetActiveCamera()->Azimuth(2.0);
      times.push_back(this->Frame());
    }
    return { first, median(times) };
  }

  /// The last frame's colours (RGB, rows bottom to top).
  std::vector<unsigned char> Pixels()
  {
    const int* size = this->Window->GetSize();
    vtkNew<vtkUnsignedCharArray> data;
    this->Window->GetPixelData(0, 0, size[0] - 1, size[1] - 1, 0, data, 0);
    return { data->GetPointer(0), data->GetPointer(0) + data->GetNumberOfValues() };
  }

  /// One animation step: the same atoms at new positions (a copy of the points, shifted).
  double AnimationStep(vtkPolyData* atoms)
  {
    vtkNew<vtkPoints> moved;
    moved->DeepCopy(atoms->GetPoints());
    auto* values = vtkFloatArray::SafeDownCast(moved->GetData())->GetPointer(0);
    for (vtkIdType i = 0; i < 3 * moved->GetNumberOfPoints(); i += 3)
    {
      values[i] += 0.01f;
    }
    atoms->SetPoints(moved);
    return this->Frame();
  }
};

} // namespace mesolens_bench
