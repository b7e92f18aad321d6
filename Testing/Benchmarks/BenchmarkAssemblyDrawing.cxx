// SPDX-License-Identifier: GPL-3.0-or-later
// Biological assemblies drawn by instancing: vtkMesoAtomMapper with the asymmetric unit as its
// input and the structure reader's copies (output 1) as its assembly input, against the same
// mapper on the expanded atoms and VTK's vtkOpenGLSphereMapper on the expanded atoms, space-
// filling, in one process and one 1024 x 768 window: GPU bytes, the first frame (buffers built
// and uploaded) and the median turning frame (2 degrees a frame), and how much of the picture
// differs between instanced and expanded.
//
//   BenchmarkAssemblyDrawing [--files 1rb8.pdb,1m4x.pdb] [--frames 3] [--ssao]
//                            [--max-expanded 20000000] [--atoms-per-cell 0]
//   BenchmarkAssemblyDrawing --smoke      (CI: crambin in 60 copies, Data/ only)
//
// Files are looked up in ../shared/data/proteins; assemblies of more atoms than --max-expanded
// are drawn instanced only (no baseline then). The camera frames the whole assembly.
#include "vtkMesoAtomMapper.h"
#include "vtkMesoStructureReader.h"

#include "atom_stage.h"
#include "mesolens_benchmark_timing.h"
#include "mesolens_test_data.h"

#include <vtkCamera.h>
#include <vtkNew.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

namespace {
using mesolens_bench::Stage;
using mesolens_bench::VTKSpheres;

double seconds_since(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Crambin (Data/) as the asymmetric unit of 60 copies on a ring 120 Å wide, written as
/// REMARK 350 BIOMT records (the smoke run's small assembly).
std::string crambin_ring()
{
  std::ostringstream remarks;
  remarks << "REMARK 350 BIOMOLECULE: 1\nREMARK 350 APPLY THE FOLLOWING TO CHAINS: A\n";
  for (int k = 0; k < 60; ++k)
  {
    const double angle = 2.0 * 3.14159265358979 * k / 60.0;
    const double c = std::cos(angle), s = std::sin(angle);
    const double rows[3][4] = { { c, -s, 0, 120 * c }, { s, c, 0, 120 * s }, { 0, 0, 1, 0 } };
    for (int r = 0; r < 3; ++r)
    {
      char line[96];
      std::snprintf(line, sizeof line, "REMARK 350   BIOMT%d %3d %9.6f %9.6f %9.6f %14.5f\n", r + 1,
                    k + 1, rows[r][0], rows[r][1], rows[r][2], rows[r][3]);
      remarks << line;
    }
  }
  std::ifstream crambin(mesolens_test::data_file("proteins/1crn.pdb"));
  std::string line;
  while (std::getline(crambin, line))
  {
    if (line.rfind("REMARK 350", 0) != 0)
    {
      remarks << line << "\n";
    }
  }
  return mesolens_test::write_bytes("crambin_ring_60.pdb", remarks.str());
}

/// Share of pixels whose colour differs by more than 16 levels in some channel.
double differing_pixels(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b)
{
  if (a.size() != b.size() || a.empty())
  {
    return 1.0;
  }
  std::size_t differing = 0;
  for (std::size_t i = 0; i + 2 < a.size(); i += 3)
  {
    for (std::size_t c = 0; c < 3; ++c)
    {
      if (std::abs(int(a[i + c]) - int(b[i + c])) > 16)
      {
        ++differing;
        break;
      }
    }
  }
  return double(differing) / double(a.size() / 3);
}

void compare(Stage& stage, const std::string& path, int frames, bool ssao, double max_expanded,
             int atoms_per_cell)
{
  const std::string name = path.substr(path.find_last_of('/') + 1);
  vtkNew<vtkMesoStructureReader> unit;
  unit->SetFileName(path.c_str());
  unit->UpdateInformation();
  if (unit->GetNumberOfAssemblies() == 0)
  {
    std::printf("BENCH assembly %s: the file defines no assembly\n", name.c_str());
    return;
  }
  const std::string assembly = unit->GetAssemblyName(0); // the first, as in the file
  unit->SetAssembly(assembly.c_str());
  unit->ExpandAssemblyOff();
  auto start = std::chrono::steady_clock::now();
  unit->Update();
  const double unit_read = seconds_since(start);
  const vtkIdType unit_atoms = unit->GetOutput(0)->GetNumberOfPoints();
  const vtkIdType copies = unit->GetOutput(1)->GetNumberOfPoints();
  const auto total = static_cast<vtkIdType>(unit->GetAssemblyAtomCount(0));
  if (copies == 0 || unit_atoms == 0)
  {
    std::printf("BENCH assembly %s: no assembly read\n", name.c_str());
    return;
  }
  const char* effects = ssao ? " with SSAO" : "";

  vtkNew<vtkMesoAtomMapper> instanced;
  instanced->SetInputConnection(unit->GetOutputPort(0));
  instanced->SetAssemblyConnection(unit->GetOutputPort(1));
  instanced->SetAtomsPerCell(atoms_per_cell);
  stage.Show(instanced, ssao);
  vtkNew<vtkCamera> view;
  view->DeepCopy(stage.Renderer->GetActiveCamera());
  const auto instanced_times = stage.Time(frames);
  const double instanced_drawn = 100.0 * double(instanced->GetLastDrawnAtomCount()) / double(total);
  stage.ShowFrom(instanced, ssao, view);
  stage.Frame();
  const std::vector<unsigned char> instanced_picture = stage.Pixels();
  const double instanced_bytes =
    (instanced->GetBufferBytesPerAtom() + instanced->GetLastDrawListBytesPerAtom()) *
      double(unit_atoms) +
    double(instanced->GetWarpBufferBytes());
  std::printf("BENCH assembly %s: %lld copies of %lld atoms (%lld atoms), unit read in %.2f s; "
              "instanced%s: first frame %.3f s, turning %.3f s (%.1f %% of the atoms drawn), "
              "GPU %.2f MB (%.1f bytes per assembly atom)\n",
              name.c_str(), static_cast<long long>(copies), static_cast<long long>(unit_atoms),
              static_cast<long long>(total), unit_read, effects, instanced_times.first,
              instanced_times.second, instanced_drawn, instanced_bytes / 1e6,
              instanced_bytes / double(total));
  if (double(total) > max_expanded)
  {
    std::printf("BENCH assembly %s: %lld atoms, more than --max-expanded %.0f: not expanded, no "
                "baseline\n",
                name.c_str(), static_cast<long long>(total), max_expanded);
    return;
  }

  vtkNew<vtkMesoStructureReader> expanded;
  expanded->SetFileName(path.c_str());
  expanded->SetAssembly(assembly.c_str());
  start = std::chrono::steady_clock::now();
  expanded->Update();
  const double expanded_read = seconds_since(start);
  vtkPolyData* atoms = expanded->GetOutput(0);
  vtkNew<vtkMesoAtomMapper> ours;
  ours->SetInputData(atoms);
  ours->SetAtomsPerCell(atoms_per_cell);
  stage.ShowFrom(ours, ssao, view);
  const auto ours_times = stage.Time(frames);
  stage.ShowFrom(ours, ssao, view);
  stage.Frame();
  const double differing = differing_pixels(instanced_picture, stage.Pixels());
  const double ours_bytes =
    (ours->GetBufferBytesPerAtom() + ours->GetLastDrawListBytesPerAtom()) * double(total);
  ours->ReleaseGraphicsResources(stage.Window);

  VTKSpheres theirs(atoms);
  stage.ShowFrom(theirs.Mapper, ssao, view);
  const auto vtk_times = stage.Time(frames);
  const double vtk_bytes = theirs.BytesPerAtom(total) * double(total);
  theirs.Mapper->ReleaseGraphicsResources(stage.Window);
  std::printf("BENCH assembly %s: expanded (read in %.2f s)%s: vtkMesoAtomMapper first %.3f s, "
              "turning %.3f s, GPU %.1f MB; vtkOpenGLSphereMapper first %.3f s, turning %.3f s, "
              "GPU %.1f MB; instanced and expanded pictures differ in %.3f %% of the pixels\n",
              name.c_str(), expanded_read, effects, ours_times.first, ours_times.second,
              ours_bytes / 1e6, vtk_times.first, vtk_times.second, vtk_bytes / 1e6,
              100.0 * differing);
  std::printf("BENCH assembly %s ratios instanced / vtkOpenGLSphereMapper%s: GPU bytes %.4f "
              "(goal <= 0.1), first frame %.3f, turning frame %.3f (goal <= 0.333)\n",
              name.c_str(), effects, instanced_bytes / vtk_bytes,
              instanced_times.first / vtk_times.first, instanced_times.second / vtk_times.second);
}
} // namespace

int main(int argc, char* argv[])
{
  std::vector<std::string> files{ "1rb8.pdb", "1m4x.pdb" };
  int frames = 3;
  bool ssao = false;
  bool smoke = false;
  double max_expanded = 2e7;
  int atoms_per_cell = 0;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--files" && i + 1 < argc)
    {
      files = mesolens_test::comma_list(argv[++i]);
    }
    else if (arg == "--frames" && i + 1 < argc)
    {
      frames = std::max(1, std::atoi(argv[++i]));
    }
    else if (arg == "--max-expanded" && i + 1 < argc)
    {
      max_expanded = std::atof(argv[++i]);
    }
    else if (arg == "--atoms-per-cell" && i + 1 < argc)
    {
      atoms_per_cell = std::max(0, std::atoi(argv[++i]));
    }
    else if (arg == "--ssao")
    {
      ssao = true;
    }
    else if (arg == "--smoke")
    {
      smoke = true;
    }
  }
  // The window's first render (the context, the passes) is paid before any mapper's frame.
  Stage stage(smoke ? 256 : 1024, smoke ? 192 : 768);
  stage.Window->Render();
  if (smoke)
  {
    compare(stage, crambin_ring(), 1, false, max_expanded, atoms_per_cell);
    return 0;
  }
  for (const std::string& file : files)
  {
    const std::string path = mesolens_test::shared_file("proteins/" + file);
    if (!mesolens_test::exists(path))
    {
      std::printf("BENCH assembly %s: skipped, %s not found\n", file.c_str(), path.c_str());
      continue;
    }
    compare(stage, path, frames, ssao, max_expanded, atoms_per_cell);
  }
  return 0;
}
