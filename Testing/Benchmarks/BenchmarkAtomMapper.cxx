// SPDX-License-Identifier: GPL-3.0-or-later
// Atom impostor benchmark: frame time of vtkMesoAtomMapper (occlusion culling on, and off)
// against VTK's vtkOpenGLSphereMapper for the same atoms, space-filling, in one process and one
// 1024 x 768 window, with and without SSAO, and the share of atoms culling draws; bytes of GPU
// buffer per atom of both (ours with its draw lists); the cost of one animation step (new
// positions of the same atoms); and the GPU membrane warp against drawing the same atoms mapped
// on the CPU.
//
//   BenchmarkAtomMapper [--atoms 100000,1000000,4000000] [--frames 5] [--atoms-per-cell 0]
//                       [--warp-tiles 8] [--no-warp]      (--warp-tiles 8,15: issue 31's pair)
//
// --atoms-per-cell applies to the warped patch too (0: each case's automatic size).
//
// The atoms are copies of the all-atom DPPC patch of Data/ (16640 atoms, waters removed), one
// periodic cell apart: a continuous membrane of a real membrane's density, seen 40 degrees off
// its normal. Each frame turns the camera 2 degrees; times are medians.
#include "vtkMesoArrayNames.h"
#include "vtkMesoAtomMapper.h"
#include "vtkMesoAtomTableConversion.h"
#include "vtkMesoMembraneMapping.h"
#include "vtkMesoTrajectoryReader.h"

#include "atom_stage.h"
#include "mesolens_benchmark_timing.h"
#include "mesolens_test_data.h"

#include <vtkCamera.h>
#include <vtkExecutive.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedShortArray.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {
using mesolens_bench::median;
using mesolens_bench::Stage;
using mesolens_bench::VTKSpheres;

/// Copies of the patch on a grid in x and y, one periodic cell apart (a continuous membrane, as
/// the periodic system it was simulated as), until `count` atoms; atoms as vertices, with
/// AtomicNumber.
vtkSmartPointer<vtkPolyData> membrane_atoms(vtkPolyData* patch, vtkIdType count)
{
  const vtkIdType n = patch->GetNumberOfPoints();
  vtkDataArray* box = patch->GetFieldData()->GetArray(vtkMesoArrayNames::PeriodicBoxVectors);
  if (!box || box->GetNumberOfComponents() != 9)
  {
    std::fprintf(stderr, "The membrane patch has no periodic box\n");
    std::exit(1);
  }
  const double step_x = box->GetComponent(0, 0);
  const double step_y = box->GetComponent(0, 4);
  const vtkIdType copies = (count + n - 1) / n;
  const vtkIdType columns = static_cast<vtkIdType>(std::ceil(std::sqrt(double(copies))));
  vtkNew<vtkFloatArray> coordinates;
  coordinates->SetNumberOfComponents(3);
  coordinates->SetNumberOfTuples(count);
  vtkNew<vtkUnsignedShortArray> numbers;
  numbers->SetName(vtkMesoArrayNames::AtomicNumber);
  numbers->SetNumberOfValues(count);
  vtkDataArray* patch_numbers = patch->GetPointData()->GetArray(vtkMesoArrayNames::AtomicNumber);
  for (vtkIdType i = 0; i < count; ++i)
  {
    const vtkIdType copy = i / n;
    const vtkIdType atom = i % n;
    double p[3];
    patch->GetPoint(atom, p);
    coordinates->SetTuple3(i, p[0] + step_x * double(copy % columns),
                           p[1] + step_y * double(copy / columns), p[2]);
    numbers->SetValue(i, static_cast<unsigned short>(patch_numbers->GetComponent(atom, 0)));
  }
  auto atoms = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetData(coordinates);
  atoms->SetPoints(points);
  vtkMesoAtomTableConversion::SetAtomVertices(atoms);
  atoms->GetPointData()->AddArray(numbers);
  return atoms;
}

void compare_mappers(Stage& stage, Stage& small, vtkPolyData* patch, vtkIdType count, int frames,
                     int atoms_per_cell)
{
  vtkSmartPointer<vtkPolyData> atoms = membrane_atoms(patch, count);
  vtkNew<vtkMesoAtomMapper> ours;
  ours->SetInputData(atoms);
  ours->SetAtomsPerCell(atoms_per_cell);
  VTKSpheres theirs(atoms);
  for (bool ssao : { false, true })
  {
    stage.Show(ours, ssao);
    const auto mine = stage.Time(frames);
    const vtkIdType drawn = ours->GetLastDrawnAtomCount();
    ours->OcclusionCullingOff();
    const auto whole = stage.Time(frames);
    ours->OcclusionCullingOn();
    std::printf("BENCH atom-mapper culling: %lld atoms%s: %lld drawn (%.1f %%), frame %.3f s "
                "culled vs %.3f s all drawn, ratio %.3f\n",
                static_cast<long long>(count), ssao ? " with SSAO" : "",
                static_cast<long long>(drawn), 100.0 * double(drawn) / double(count), mine.second,
                whole.second, mine.second / whole.second);
    stage.Show(theirs.Mapper, ssao);
    const auto vtk = stage.Time(frames);
    std::printf("BENCH atom-mapper frame: %lld atoms space-filling%s, 1024x768: "
                "vtkMesoAtomMapper %.3f s, vtkOpenGLSphereMapper %.3f s, ratio %.3f (goal <= "
                "0.333 at 1 M); first frame with upload %.3f s vs %.3f s\n",
                static_cast<long long>(count), ssao ? " with SSAO" : "", mine.second, vtk.second,
                mine.second / vtk.second, mine.first, vtk.first);
  }
  const double our_bytes = ours->GetBufferBytesPerAtom() + ours->GetLastDrawListBytesPerAtom();
  std::printf("BENCH atom-mapper GPU bytes per atom: %lld atoms: vtkMesoAtomMapper %.1f (%.1f "
              "per atom + %.1f of draw lists), vtkOpenGLSphereMapper %.1f, ratio %.3f (goal <= "
              "16 bytes)\n",
              static_cast<long long>(count), our_bytes, ours->GetBufferBytesPerAtom(),
              ours->GetLastDrawListBytesPerAtom(), theirs.BytesPerAtom(count),
              our_bytes / theirs.BytesPerAtom(count));

  // Animation steps: only the positions go up for ours; VTK's mapper rebuilds its buffers.
  // Medians of 9 still frames and of 9 steps, the camera fixed, in a 64 x 48 window so that
  // drawing the pixels does not drown the update.
  auto steps = [&](vtkMapper* mapper, double& still, double& step) {
    small.Show(mapper, false);
    small.Frame();
    std::vector<double> still_times;
    std::vector<double> step_times;
    for (int i = 0; i < 9; ++i)
    {
      still_times.push_back(small.Frame());
      step_times.push_back(small.AnimationStep(atoms));
    }
    still = median(still_times);
    step = median(step_times);
  };
  double still = 0;
  double step = 0;
  steps(ours, still, step);
  const double uploaded = double(ours->GetLastUploadBytes());
  theirs.Radii->SetInputData(atoms);
  double vtk_still = 0;
  double vtk_step = 0;
  steps(theirs.Mapper, vtk_still, vtk_step);
  std::printf("BENCH atom-mapper animation step: %lld atoms, new positions (64x48 window): "
              "vtkMesoAtomMapper %.3f s (still frame %.3f s, so %.3f s for the update; %.1f MB "
              "uploaded = %.1f "
              "bytes/atom), vtkOpenGLSphereMapper %.3f s (still %.3f s, update %.3f s), ratio of "
              "updates %.3f\n",
              static_cast<long long>(count), step, still, step - still, uploaded / 1e6,
              uploaded / double(count), vtk_step, vtk_still, vtk_step - vtk_still,
              (step - still) / std::max(1e-3, vtk_step - vtk_still));
}

/// The polynomial warp evaluated on the GPU against the same tiles mapped on the CPU and drawn
/// as they are.
void compare_warp(Stage& stage, int tiles, int frames, int atoms_per_cell)
{
  mesolens_bench::MitochondrionMapping mitochondrion(
    mesolens_test::data_file("membranes/dppc128_slipids_323K.gro"), tiles);
  vtkMesoTrajectoryReader* membrane = mitochondrion.Membrane;
  vtkMesoMembraneMapping* mapping = mitochondrion.Mapping;
  if (!mapping->GetExecutive()->Update())
  {
    std::printf("BENCH atom-mapper warp: the mapping of %d x %d tiles failed; skipped\n", tiles,
                tiles);
    return;
  }
  vtkNew<vtkPolyData> mapped;
  mapped->ShallowCopy(mapping->GetOutput());
  vtkNew<vtkMesoAtomMapper> cpu;
  cpu->SetInputData(mapped);
  cpu->SetRadiusScale(1e-4);
  mapping->OutputAtomsOff();
  vtkNew<vtkMesoAtomMapper> gpu;
  gpu->SetInputConnection(membrane->GetOutputPort());
  gpu->SetWarpConnection(mapping->GetOutputPort());
  gpu->SetRadiusScale(1e-4);
  gpu->SetAtomsPerCell(atoms_per_cell);
  // Every run turns the camera from the same start, the CPU-mapped atoms' view: the same
  // pictures, compared pixel by pixel at the end.
  stage.Show(cpu, false);
  vtkNew<vtkCamera> start;
  start->DeepCopy(stage.Renderer->GetActiveCamera());
  auto run = [&](vtkMesoAtomMapper* mapper, bool culling) {
    mapper->SetOcclusionCulling(culling);
    stage.ShowFrom(mapper, false, start);
    return stage.Time(frames);
  };
  const auto drawn = run(cpu, false);
  const auto warped_whole = run(gpu, false);
  // The two culled cases, whose ratio is the figure, in turns (3 rounds, medians): a drift of
  // the machine over the run weighs on both alike.
  std::vector<double> culled_times, warped_times;
  std::vector<unsigned char> cpu_picture, gpu_picture;
  for (int round = 0; round < 3; ++round)
  {
    culled_times.push_back(run(cpu, true).second);
    cpu_picture = stage.Pixels();
    warped_times.push_back(run(gpu, true).second);
    gpu_picture = stage.Pixels();
  }
  const std::pair<double, double> culled{ 0.0, mesolens_bench::median(culled_times) };
  const std::pair<double, double> warped{ 0.0, mesolens_bench::median(warped_times) };
  const double mapped_atoms = double(mapped->GetNumberOfPoints());
  const double cpu_drawn = 100.0 * double(cpu->GetLastDrawnAtomCount()) / mapped_atoms;
  std::size_t differing = 0;
  for (std::size_t i = 0; i + 2 < cpu_picture.size() && cpu_picture.size() == gpu_picture.size();
       i += 3)
  {
    for (std::size_t c = 0; c < 3; ++c)
    {
      if (std::abs(int(cpu_picture[i + c]) - int(gpu_picture[i + c])) > 16)
      {
        ++differing;
        break;
      }
    }
  }
  std::printf(
    "BENCH atom-mapper GPU polynomial warp: %d x %d tiles of the DPPC patch, %lld "
    "atoms, space-filling: warped on the GPU %.3f s per frame from %.1f MB (%.1f %% drawn; "
    "%.3f s unculled), the CPU-mapped atoms %.3f s from %.1f MB, culled %.3f s (%.1f %% "
    "drawn): ratio warp / culled %.3f (goal <= 1), unculled warp / culled %.3f; pictures "
    "differ at %.3f %% of the pixels (by more than 16 of 255)\n",
    tiles, tiles, static_cast<long long>(mapped->GetNumberOfPoints()), warped.second,
    gpu->GetBufferBytesPerAtom() * mapped_atoms / (tiles * tiles) / 1e6,
    100.0 * double(gpu->GetLastDrawnAtomCount()) / mapped_atoms, warped_whole.second, drawn.second,
    cpu->GetBufferBytesPerAtom() * mapped_atoms / 1e6, culled.second, cpu_drawn,
    warped.second / culled.second, warped_whole.second / culled.second,
    100.0 * double(differing) / double(std::max<std::size_t>(1, cpu_picture.size() / 3)));
}
} // namespace

int main(int argc, char* argv[])
{
  std::vector<vtkIdType> sizes{ 100000, 1000000, 4000000 };
  int frames = 5;
  bool warp = true;
  std::vector<int> warp_tiles{ 8 };
  int atoms_per_cell = 0;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--atoms" && i + 1 < argc)
    {
      sizes.clear();
      for (const std::string& item : mesolens_test::comma_list(argv[++i]))
      {
        sizes.push_back(std::atoll(item.c_str()));
      }
    }
    else if (arg == "--frames" && i + 1 < argc)
    {
      frames = std::max(1, std::atoi(argv[++i]));
    }
    else if (arg == "--atoms-per-cell" && i + 1 < argc)
    {
      atoms_per_cell = std::max(0, std::atoi(argv[++i]));
    }
    else if (arg == "--warp-tiles" && i + 1 < argc)
    {
      warp_tiles.clear();
      for (const std::string& item : mesolens_test::comma_list(argv[++i]))
      {
        warp_tiles.push_back(std::max(1, std::atoi(item.c_str())));
      }
    }
    else if (arg == "--no-warp")
    {
      warp = false;
    }
  }
  vtkNew<vtkMesoTrajectoryReader> reader;
  reader->SetTopologyFileName(
    mesolens_test::data_file("membranes/dppc128_slipids_323K.gro").c_str());
  reader->RemoveWatersOn();
  reader->Update();
  Stage stage;
  Stage small(64, 48);
  for (const vtkIdType count : sizes)
  {
    compare_mappers(stage, small, reader->GetOutput(), count, frames, atoms_per_cell);
  }
  for (const int tiles : warp ? warp_tiles : std::vector<int>{})
  {
    compare_warp(stage, tiles, frames, atoms_per_cell);
  }
  return 0;
}
