// SPDX-License-Identifier: GPL-3.0-or-later
// Render tests of vtkMesoAtomMapper: draws one scene to a PNG that the test compares with its
// baseline (mesolens_compare_images).
//
//   TestMesoAtomMapperImage SCENE OUTPUT.png [--radius-factor F] [--cells N] [--no-culling]
//                           [--cell-padding F]
//
// Scenes: space_filling, ball_and_stick, sticks, vtk_sphere_mapper (VTK's own impostors for
// the same atoms), ssao, shadows, translucent, parallel_viewports, scalar_colors,
// warp_polynomial_cpu, warp_polynomial_gpu, warp_instancing_cpu, warp_instancing_gpu,
// warp_polynomial_spheres_cpu, warp_polynomial_spheres_gpu, warp_instancing_spheres_gpu
// (space-filling), cutaway_polynomial_cpu, cutaway_polynomial_gpu, cutaway_instancing_cpu,
// cutaway_instancing_gpu (the structured cutaway on the atoms mapped on the CPU, or as a mask of
// the molecules of each tile on the GPU path).
// --radius-factor scales every radius (a test breaks the picture on purpose with 1.1); --cells
// sets the atom mappers' AtomsPerCell (and renders twice), --no-culling turns their culling
// off, --cell-padding sets their CellPaddingFactor (0 breaks culling on purpose).
#include "vtkMesoArrayNames.h"
#include "MesoAtomScenes.h"

#include "vtkMesoAtomProperties.h"
#include "vtkMesoElementLookupTable.h"
#include "vtkMesoRenderPasses.h"

#include <vtkLight.h>
#include <vtkLookupTable.h>
#include <vtkOpenGLSphereMapper.h>
#include <vtkPNGWriter.h>
#include <vtkPlaneSource.h>
#include <vtkPointData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRendererCollection.h>
#include <vtkActorCollection.h>
#include <vtkWindowToImageFilter.h>

#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <map>
#include <memory>

namespace {
using mesolens_test::crambin;
using mesolens_test::look_at;

double radius_factor = 1.0;

vtkSmartPointer<vtkMesoAtomMapper> atom_mapper(vtkAlgorithm* source, int style)
{
  auto mapper = vtkSmartPointer<vtkMesoAtomMapper>::New();
  mapper->SetInputConnection(source->GetOutputPort());
  mapper->SetStyle(style);
  mapper->SetRadiusScale(radius_factor);
  return mapper;
}

vtkSmartPointer<vtkRenderer> protein_renderer(vtkMapper* mapper, vtkMesoStructureReader* reader)
{
  auto renderer = vtkSmartPointer<vtkRenderer>::New();
  renderer->SetBackground(0.1, 0.1, 0.15);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  renderer->AddActor(actor);
  look_at(renderer, reader->GetOutput(), 55.0);
  return renderer;
}

/// A window with one renderer showing crambin in a style.
vtkSmartPointer<vtkRenderWindow> protein(int style)
{
  auto reader = crambin();
  auto window = mesolens_test::test_window(300, 300);
  window->AddRenderer(protein_renderer(atom_mapper(reader, style), reader));
  return window;
}

vtkSmartPointer<vtkRenderWindow> vtk_sphere_mapper()
{
  auto reader = crambin();
  vtkNew<vtkMesoAtomProperties> radii;
  radii->SetInputConnection(reader->GetOutputPort());
  radii->SetLengthScale(radius_factor);
  vtkNew<vtkOpenGLSphereMapper> mapper;
  mapper->SetInputConnection(radii->GetOutputPort());
  mapper->SetScaleArray(vtkMesoArrayNames::VanDerWaalsRadius);
  vtkNew<vtkMesoElementLookupTable> elements;
  mapper->SetLookupTable(elements);
  mapper->UseLookupTableScalarRangeOn();
  mapper->SetScalarModeToUsePointFieldData();
  mapper->SelectColorArray(vtkMesoArrayNames::AtomicNumber);
  mapper->SetColorModeToMapScalars();
  auto window = mesolens_test::test_window(300, 300);
  window->AddRenderer(protein_renderer(mapper, reader));
  return window;
}

vtkSmartPointer<vtkRenderWindow> ssao()
{
  auto window = protein(vtkMesoAtomMapper::SPACE_FILLING);
  vtkNew<vtkMesoRenderPasses> passes;
  passes->SSAOOn();
  passes->SetSSAORadius(3.0);
  passes->SetSSAOBias(0.05);
  passes->SetSSAOKernelSize(64);
  passes->SSAOBlurOn();
  passes->Apply(window->GetRenderers()->GetFirstRenderer());
  return window;
}

/// Ball-and-stick crambin over a floor, lit from above: the atoms cast shadows on it and on
/// each other.
vtkSmartPointer<vtkRenderWindow> shadows()
{
  auto window = protein(vtkMesoAtomMapper::BALL_AND_STICK);
  vtkRenderer* renderer = window->GetRenderers()->GetFirstRenderer();
  double bounds[6];
  renderer->ComputeVisiblePropBounds(bounds);
  vtkNew<vtkPlaneSource> floor;
  floor->SetOrigin(bounds[0] - 10, bounds[2] - 10, bounds[4] - 3);
  floor->SetPoint1(bounds[1] + 10, bounds[2] - 10, bounds[4] - 3);
  floor->SetPoint2(bounds[0] - 10, bounds[3] + 10, bounds[4] - 3);
  vtkNew<vtkPolyDataMapper> floor_mapper;
  floor_mapper->SetInputConnection(floor->GetOutputPort());
  vtkNew<vtkActor> floor_actor;
  floor_actor->SetMapper(floor_mapper);
  floor_actor->GetProperty()->SetColor(0.8, 0.8, 0.75);
  renderer->AddActor(floor_actor);
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPosition((bounds[0] + bounds[1]) / 2 + 15, (bounds[2] + bounds[3]) / 2 + 10,
                     bounds[5] + 40);
  light->SetFocalPoint((bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2, bounds[4]);
  light->PositionalOn();
  light->SetConeAngle(60);
  renderer->AddLight(light);
  vtkNew<vtkMesoRenderPasses> passes;
  passes->ShadowsOn();
  passes->Apply(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->Elevation(-35);
  renderer->ResetCameraClippingRange();
  return window;
}

/// Translucent space-filling atoms cut by an opaque plane, with depth peeling.
vtkSmartPointer<vtkRenderWindow> translucent()
{
  auto window = protein(vtkMesoAtomMapper::SPACE_FILLING);
  window->SetAlphaBitPlanes(1);
  vtkRenderer* renderer = window->GetRenderers()->GetFirstRenderer();
  vtkNew<vtkMesoRenderPasses> passes;
  passes->DepthPeelingOn();
  passes->SetMaximumNumberOfPeels(16);
  passes->Apply(renderer);
  renderer->GetActors()->GetLastActor()->GetProperty()->SetOpacity(0.4);
  double bounds[6];
  renderer->ComputeVisiblePropBounds(bounds);
  const double y = (bounds[2] + bounds[3]) / 2;
  const double z = (bounds[4] + bounds[5]) / 2;
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(bounds[0], y, bounds[4]);
  plane->SetPoint1(bounds[1], y, bounds[4]);
  plane->SetPoint2(bounds[0], y + 20, bounds[5]);
  plane->SetCenter((bounds[0] + bounds[1]) / 2, y, z);
  vtkNew<vtkPolyDataMapper> plane_mapper;
  plane_mapper->SetInputConnection(plane->GetOutputPort());
  vtkNew<vtkActor> plane_actor;
  plane_actor->SetMapper(plane_mapper);
  plane_actor->GetProperty()->SetColor(0.9, 0.8, 0.3);
  renderer->AddActor(plane_actor);
  return window;
}

/// Two viewports: balls and sticks in a parallel projection, sticks in perspective.
vtkSmartPointer<vtkRenderWindow> parallel_viewports()
{
  auto reader = crambin();
  auto window = mesolens_test::test_window(400, 200);
  auto left = protein_renderer(atom_mapper(reader, vtkMesoAtomMapper::BALL_AND_STICK), reader);
  left->SetViewport(0, 0, 0.5, 1);
  left->GetActiveCamera()->ParallelProjectionOn();
  left->GetActiveCamera()->SetParallelScale(18);
  auto right = protein_renderer(atom_mapper(reader, vtkMesoAtomMapper::STICKS), reader);
  right->SetViewport(0.5, 0, 1, 1);
  right->SetBackground(0.15, 0.1, 0.1);
  window->AddRenderer(left);
  window->AddRenderer(right);
  return window;
}

/// Balls and sticks coloured by B-factor through a blue-to-red table over the B-factors' range.
vtkSmartPointer<vtkRenderWindow> scalar_colors()
{
  auto reader = crambin();
  auto mapper = atom_mapper(reader, vtkMesoAtomMapper::BALL_AND_STICK);
  vtkNew<vtkLookupTable> table;
  table->SetHueRange(0.667, 0.0);
  table->Build();
  mapper->SetLookupTable(table);
  mapper->SetScalarModeToUsePointFieldData();
  mapper->SelectColorArray(vtkMesoArrayNames::BFactor);
  mapper->SetScalarRange(
    reader->GetOutput()->GetPointData()->GetArray(vtkMesoArrayNames::BFactor)->GetRange());
  auto window = mesolens_test::test_window(300, 300);
  window->AddRenderer(protein_renderer(mapper, reader));
  return window;
}

/// The mapped membrane, balls and sticks, seen from outside the organelle: the atoms mapped on
/// the CPU (gpu false) or the patch warped by the mapper (gpu true).
vtkSmartPointer<vtkRenderWindow> warped(int method, bool gpu, double max_residual = 1.0,
                                        int style = vtkMesoAtomMapper::BALL_AND_STICK,
                                        bool cut = false)
{
  auto cpu_mapping = mesolens_test::mapped_membrane(method, true, max_residual);
  vtkPolyData* cpu_atoms = cpu_mapping->GetOutput();
  vtkSmartPointer<vtkMesoAtomMapper> mapper = vtkSmartPointer<vtkMesoAtomMapper>::New();
  vtkSmartPointer<vtkMesoMembraneMapping> gpu_mapping;
  // The cutaway and the mapping stay alive as the mapper's upstream pipeline.
  std::unique_ptr<mesolens_test::CutMembrane> cut_membrane;
  if (cut)
  {
    cut_membrane = std::make_unique<mesolens_test::CutMembrane>(method, gpu);
    mapper = cut_membrane->Mapper.Get();
  }
  else if (gpu)
  {
    gpu_mapping = mesolens_test::mapped_membrane(method, false, max_residual);
    mapper->SetInputConnection(gpu_mapping->GetInputConnection(1, 0));
    mapper->SetWarpConnection(gpu_mapping->GetOutputPort());
  }
  else
  {
    mapper->SetInputConnection(cpu_mapping->GetOutputPort());
  }
  mapper->SetStyle(style);
  mapper->SetRadiusScale(1e-4 * radius_factor);
  auto renderer = vtkSmartPointer<vtkRenderer>::New();
  renderer->SetBackground(0.1, 0.1, 0.15);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  renderer->AddActor(actor);
  // Along the outward normal at the mapped region: from the organelle's centre through it.
  double centre[3];
  cpu_atoms->GetCenter(centre);
  double organelle[3];
  vtkPolyData::SafeDownCast(cpu_mapping->GetInputDataObject(0, 0))->GetCenter(organelle);
  double normal[3] = { centre[0] - organelle[0], centre[1] - organelle[1],
                       centre[2] - organelle[2] };
  const double length =
    std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetFocalPoint(centre);
  camera->SetPosition(centre[0] + 0.025 * normal[0] / length,
                      centre[1] + 0.025 * normal[1] / length,
                      centre[2] + 0.025 * normal[2] / length);
  camera->SetViewUp(0, 0, 1);
  auto window = mesolens_test::test_window(300, 300);
  window->AddRenderer(renderer);
  renderer->ResetCameraClippingRange();
  return window;
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc < 3)
  {
    std::cerr << "usage: TestMesoAtomMapperImage SCENE OUTPUT.png [--radius-factor F] "
                 "[--cells N] [--no-culling] [--cell-padding F]\n";
    return 2;
  }
  const std::string scene = argv[1];
  const std::string output = argv[2];
  int atoms_per_cell = 0;
  bool culling = true;
  double cell_padding = 1.0;
  for (int i = 3; i < argc; ++i)
  {
    const std::string option = argv[i];
    if (option == "--radius-factor" && i + 1 < argc)
    {
      radius_factor = std::atof(argv[++i]);
    }
    else if (option == "--cells" && i + 1 < argc)
    {
      atoms_per_cell = std::atoi(argv[++i]);
    }
    else if (option == "--cell-padding" && i + 1 < argc)
    {
      cell_padding = std::atof(argv[++i]);
    }
    else if (option == "--no-culling")
    {
      culling = false;
    }
    else
    {
      std::cerr << "unknown option " << option << "\n";
      return 2;
    }
  }
  const std::map<std::string, std::function<vtkSmartPointer<vtkRenderWindow>()>> scenes{
    { "space_filling", [] { return protein(vtkMesoAtomMapper::SPACE_FILLING); } },
    { "ball_and_stick", [] { return protein(vtkMesoAtomMapper::BALL_AND_STICK); } },
    { "sticks", [] { return protein(vtkMesoAtomMapper::STICKS); } },
    { "vtk_sphere_mapper", vtk_sphere_mapper },
    { "ssao", ssao },
    { "shadows", shadows },
    { "translucent", translucent },
    { "parallel_viewports", parallel_viewports },
    { "scalar_colors", scalar_colors },
    { "warp_polynomial_cpu", [] { return warped(vtkMesoMembraneMapping::POLYNOMIAL, false); } },
    { "warp_polynomial_gpu", [] { return warped(vtkMesoMembraneMapping::POLYNOMIAL, true); } },
    // Tiles split into pieces (a bound of 0.2 Å splits them 4 x 4).
    { "warp_polynomial_split_cpu",
      [] { return warped(vtkMesoMembraneMapping::POLYNOMIAL, false, 0.2); } },
    { "warp_polynomial_split_gpu",
      [] { return warped(vtkMesoMembraneMapping::POLYNOMIAL, true, 0.2); } },
    { "warp_instancing_cpu",
      [] { return warped(vtkMesoMembraneMapping::MOLECULE_INSTANCING, false); } },
    { "warp_instancing_gpu",
      [] { return warped(vtkMesoMembraneMapping::MOLECULE_INSTANCING, true); } },
    // Space-filling, where culling leaves most atoms out.
    { "warp_polynomial_spheres_cpu",
      [] {
        return warped(vtkMesoMembraneMapping::POLYNOMIAL, false, 1.0,
                      vtkMesoAtomMapper::SPACE_FILLING);
      } },
    { "warp_polynomial_spheres_gpu",
      [] {
        return warped(vtkMesoMembraneMapping::POLYNOMIAL, true, 1.0,
                      vtkMesoAtomMapper::SPACE_FILLING);
      } },
    // The structured cutaway: on the mapped atoms, and on the GPU path (molecule masks).
    { "cutaway_polynomial_cpu",
      [] {
        return warped(vtkMesoMembraneMapping::POLYNOMIAL, false, 1.0,
                      vtkMesoAtomMapper::SPACE_FILLING, true);
      } },
    { "cutaway_polynomial_gpu",
      [] {
        return warped(vtkMesoMembraneMapping::POLYNOMIAL, true, 1.0,
                      vtkMesoAtomMapper::SPACE_FILLING, true);
      } },
    { "cutaway_instancing_cpu",
      [] {
        return warped(vtkMesoMembraneMapping::MOLECULE_INSTANCING, false, 1.0,
                      vtkMesoAtomMapper::BALL_AND_STICK, true);
      } },
    { "cutaway_instancing_gpu",
      [] {
        return warped(vtkMesoMembraneMapping::MOLECULE_INSTANCING, true, 1.0,
                      vtkMesoAtomMapper::BALL_AND_STICK, true);
      } },
    { "warp_instancing_spheres_gpu",
      [] {
        return warped(vtkMesoMembraneMapping::MOLECULE_INSTANCING, true, 1.0,
                      vtkMesoAtomMapper::SPACE_FILLING);
      } },
  };
  const auto found = scenes.find(scene);
  if (found == scenes.end())
  {
    std::cerr << "unknown scene " << scene << "\n";
    return 2;
  }
  vtkSmartPointer<vtkRenderWindow> window = found->second();
  // The culling settings of every atom mapper; with cells, two frames: the first learns what
  // shows, the second draws from what it learnt.
  vtkRenderer* renderer = nullptr;
  auto renderers = window->GetRenderers();
  for (renderers->InitTraversal(); (renderer = renderers->GetNextItem());)
  {
    vtkActor* actor = nullptr;
    auto actors = renderer->GetActors();
    for (actors->InitTraversal(); (actor = actors->GetNextActor());)
    {
      if (auto* atoms = vtkMesoAtomMapper::SafeDownCast(actor->GetMapper()))
      {
        atoms->SetAtomsPerCell(atoms_per_cell);
        atoms->SetOcclusionCulling(culling);
        atoms->SetCellPaddingFactor(cell_padding);
      }
    }
  }
  if (atoms_per_cell > 0)
  {
    window->Render();
  }
  window->Render();
  vtkNew<vtkWindowToImageFilter> capture;
  capture->SetInput(window);
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(output.c_str());
  writer->SetInputConnection(capture->GetOutputPort());
  writer->Write();
  return 0;
}
