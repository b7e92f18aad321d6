// SPDX-License-Identifier: GPL-3.0-or-later
// The MesoLens demo: real molecules from Data/ read by MesoLens and drawn with VTK's stock
// mappers. Left: ubiquitin (1UBQ) as balls and sticks coloured by element; right: an all-atom
// DPPC bilayer patch (Slipids, 128 lipids, waters removed) space-filling.
//
//   MesoLensDemo [--data DIR] [--output FILE.png] [--size WIDTHxHEIGHT] [--atom-scale S]
//                [--interactive]
//
// Writes the PNG; with --interactive (and a display) it then opens the window.
#include "vtkMesoAtomProperties.h"
#include "vtkMesoElementLookupTable.h"
#include "vtkMesoStructureReader.h"
#include "vtkMesoTrajectoryReader.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkExecutive.h>
#include <vtkGlyph3DMapper.h>
#include <vtkNew.h>
#include <vtkOpenGLSphereMapper.h>
#include <vtkPNGWriter.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkSphereSource.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkTubeFilter.h>
#include <vtkWindowToImageFilter.h>

#include <cstdlib>
#include <iostream>
#include <string>

namespace {
struct Options
{
  std::string data = MESOLENS_DATA_DIR;
  std::string output = "mesolens-demo.png";
  int width = 1200;
  int height = 600;
  double atom_scale = 1.0;
  bool interactive = false;
};

bool parse(int argc, char* argv[], Options& options)
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--data" && has_value)
      options.data = argv[++i];
    else if (arg == "--output" && has_value)
      options.output = argv[++i];
    else if (arg == "--size" && has_value)
    {
      const std::string size = argv[++i];
      const auto x = size.find('x');
      if (x == std::string::npos)
        return false;
      options.width = std::atoi(size.substr(0, x).c_str());
      options.height = std::atoi(size.substr(x + 1).c_str());
    }
    else if (arg == "--atom-scale" && has_value)
      options.atom_scale = std::atof(argv[++i]);
    else if (arg == "--interactive")
      options.interactive = true;
    else
      return false;
  }
  return options.width > 0 && options.height > 0 && options.atom_scale > 0;
}

void colour_by_element(vtkMapper* mapper, vtkLookupTable* elements)
{
  mapper->SetLookupTable(elements);
  mapper->UseLookupTableScalarRangeOn();
  mapper->SetScalarModeToUsePointFieldData();
  mapper->SelectColorArray("AtomicNumber");
  mapper->SetColorModeToMapScalars();
  mapper->ScalarVisibilityOn();
}

void add_title(vtkRenderer* renderer, const std::string& text, int font_size)
{
  vtkNew<vtkTextActor> title;
  title->SetInput(text.c_str());
  title->GetTextProperty()->SetFontSize(font_size);
  title->GetTextProperty()->SetColor(0.9, 0.9, 0.9);
  title->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  title->GetPositionCoordinate()->SetValue(0.02, 0.02);
  renderer->AddActor2D(title);
}

std::string counts(vtkPolyData* atoms)
{
  return std::to_string(atoms->GetNumberOfPoints()) + " atoms, " +
    std::to_string(atoms->GetNumberOfLines()) + " bonds";
}

/// Ubiquitin, balls (0.25 x van der Waals radius) and sticks.
bool add_protein(vtkRenderer* renderer, const Options& options, vtkLookupTable* elements)
{
  vtkNew<vtkMesoStructureReader> reader;
  reader->SetFileName((options.data + "/proteins/1ubq.pdb").c_str());
  reader->RemoveWatersOn();
  vtkNew<vtkMesoAtomProperties> properties;
  properties->SetInputConnection(reader->GetOutputPort());
  if (!properties->GetExecutive()->Update())
    return false;

  vtkNew<vtkSphereSource> ball;
  ball->SetThetaResolution(16);
  ball->SetPhiResolution(16);
  vtkNew<vtkGlyph3DMapper> balls;
  balls->SetInputConnection(properties->GetOutputPort());
  balls->SetSourceConnection(ball->GetOutputPort());
  balls->SetScaleArray("VanDerWaalsRadius");
  balls->SetScaleModeToScaleByMagnitude();
  balls->SetScaleFactor(2.0 * 0.25 * options.atom_scale); // the source sphere has diameter 1
  colour_by_element(balls, elements);
  vtkNew<vtkActor> ball_actor;
  ball_actor->SetMapper(balls);
  renderer->AddActor(ball_actor);

  vtkNew<vtkTubeFilter> sticks;
  sticks->SetInputConnection(reader->GetOutputPort());
  sticks->SetRadius(0.15);
  sticks->SetNumberOfSides(10);
  vtkNew<vtkPolyDataMapper> stick_mapper;
  stick_mapper->SetInputConnection(sticks->GetOutputPort());
  colour_by_element(stick_mapper, elements);
  vtkNew<vtkActor> stick_actor;
  stick_actor->SetMapper(stick_mapper);
  renderer->AddActor(stick_actor);
  add_title(renderer, "ubiquitin (1UBQ): " + counts(properties->GetOutput()), options.width / 60);
  return true;
}

/// The Slipids DPPC bilayer, space-filling with VTK's sphere impostors.
bool add_membrane(vtkRenderer* renderer, const Options& options, vtkLookupTable* elements)
{
  vtkNew<vtkMesoTrajectoryReader> reader;
  reader->SetTopologyFileName((options.data + "/membranes/dppc128_slipids_323K.gro").c_str());
  reader->RemoveWatersOn();
  vtkNew<vtkMesoAtomProperties> properties;
  properties->SetInputConnection(reader->GetOutputPort());
  if (!properties->GetExecutive()->Update())
    return false;
  vtkNew<vtkOpenGLSphereMapper> spheres;
  spheres->SetInputConnection(properties->GetOutputPort());
  spheres->SetScaleArray("VanDerWaalsRadius");
  spheres->SetRadius(static_cast<float>(options.atom_scale));
  colour_by_element(spheres, elements);
  vtkNew<vtkActor> actor;
  actor->SetMapper(spheres);
  renderer->AddActor(actor);
  add_title(renderer, "DPPC bilayer, 128 lipids: " + counts(properties->GetOutput()),
            options.width / 60);
  return true;
}
} // namespace

int main(int argc, char* argv[])
{
  Options options;
  if (!parse(argc, argv, options))
  {
    std::cerr << "usage: MesoLensDemo [--data DIR] [--output FILE.png] [--size WxH] "
                 "[--atom-scale S] [--interactive]\n";
    return 2;
  }
  vtkNew<vtkMesoElementLookupTable> elements;
  vtkNew<vtkRenderer> protein;
  protein->SetViewport(0.0, 0.0, 0.5, 1.0);
  protein->SetBackground(0.10, 0.11, 0.14);
  vtkNew<vtkRenderer> membrane;
  membrane->SetViewport(0.5, 0.0, 1.0, 1.0);
  membrane->SetBackground(0.12, 0.13, 0.17);
  if (!add_protein(protein, options, elements) || !add_membrane(membrane, options, elements))
  {
    std::cerr << "MesoLensDemo: cannot read the data in " << options.data << "\n";
    return 1;
  }
  // Fixed cameras, so the picture is the same on every run.
  protein->GetActiveCamera()->SetPosition(60, 40, 80);
  protein->GetActiveCamera()->SetFocalPoint(30, 28, 15);
  protein->GetActiveCamera()->SetViewUp(0, 1, 0);
  protein->ResetCamera();
  protein->GetActiveCamera()->Zoom(1.3);
  membrane->GetActiveCamera()->SetPosition(200, -60, 60);
  membrane->GetActiveCamera()->SetFocalPoint(30, 30, 30);
  membrane->GetActiveCamera()->SetViewUp(0, 0, 1);
  membrane->ResetCamera();
  membrane->GetActiveCamera()->Zoom(1.2);

  vtkNew<vtkRenderWindow> window;
  window->SetSize(options.width, options.height);
  window->SetMultiSamples(0);
  window->SetWindowName("MesoLens demo");
  window->AddRenderer(protein);
  window->AddRenderer(membrane);
  if (!options.interactive)
  {
    window->OffScreenRenderingOn();
  }
  window->Render();

  vtkNew<vtkWindowToImageFilter> capture;
  capture->SetInput(window);
  capture->ReadFrontBufferOff();
  vtkNew<vtkPNGWriter> png;
  png->SetFileName(options.output.c_str());
  png->SetInputConnection(capture->GetOutputPort());
  png->Write();
  std::cout << "MesoLensDemo: wrote " << options.output << "\n";

  if (options.interactive)
  {
    vtkNew<vtkRenderWindowInteractor> interactor;
    interactor->SetRenderWindow(window);
    interactor->Initialize();
    interactor->Start();
  }
  return 0;
}
