// SPDX-License-Identifier: GPL-3.0-or-later
// The MesoLens demo: real molecules from Data/ read by MesoLens and drawn by its ray-cast atom
// impostors. Left: ubiquitin (1UBQ) as balls and sticks coloured by element; right: an all-atom
// DPPC bilayer patch (Slipids, 128 lipids, waters removed) space-filling.
//
//   MesoLensDemo [--data DIR] [--output FILE.png] [--size WIDTHxHEIGHT] [--atom-scale S]
//                [--interactive]
//
// Writes the PNG; with --interactive (and a display) it then opens the window.
#include "vtkMesoAtomMapper.h"
#include "vtkMesoStructureReader.h"
#include "vtkMesoTrajectoryReader.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkExecutive.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
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

/// Ubiquitin, balls (0.25 x van der Waals radius) and sticks, ray-cast impostors.
bool add_protein(vtkRenderer* renderer, const Options& options)
{
  vtkNew<vtkMesoStructureReader> reader;
  reader->SetFileName((options.data + "/proteins/1ubq.pdb").c_str());
  reader->RemoveWatersOn();
  if (!reader->GetExecutive()->Update())
    return false;
  vtkNew<vtkMesoAtomMapper> atoms;
  atoms->SetInputConnection(reader->GetOutputPort());
  atoms->SetStyleToBallAndStick();
  atoms->SetRadiusScale(options.atom_scale);
  vtkNew<vtkActor> actor;
  actor->SetMapper(atoms);
  renderer->AddActor(actor);
  add_title(renderer, "ubiquitin (1UBQ): " + counts(reader->GetOutput()), options.width / 60);
  return true;
}

/// The Slipids DPPC bilayer, space-filling.
bool add_membrane(vtkRenderer* renderer, const Options& options)
{
  vtkNew<vtkMesoTrajectoryReader> reader;
  reader->SetTopologyFileName((options.data + "/membranes/dppc128_slipids_323K.gro").c_str());
  reader->RemoveWatersOn();
  if (!reader->GetExecutive()->Update())
    return false;
  vtkNew<vtkMesoAtomMapper> atoms;
  atoms->SetInputConnection(reader->GetOutputPort());
  atoms->SetRadiusScale(options.atom_scale);
  vtkNew<vtkActor> actor;
  actor->SetMapper(atoms);
  renderer->AddActor(actor);
  add_title(renderer, "DPPC bilayer, 128 lipids: " + counts(reader->GetOutput()),
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
  vtkNew<vtkRenderer> protein;
  protein->SetViewport(0.0, 0.0, 0.5, 1.0);
  protein->SetBackground(0.10, 0.11, 0.14);
  vtkNew<vtkRenderer> membrane;
  membrane->SetViewport(0.5, 0.0, 1.0, 1.0);
  membrane->SetBackground(0.12, 0.13, 0.17);
  if (!add_protein(protein, options) || !add_membrane(membrane, options))
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
