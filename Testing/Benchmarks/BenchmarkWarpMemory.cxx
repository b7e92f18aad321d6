// SPDX-License-Identifier: GPL-3.0-or-later
// Memory of the GPU membrane warp: what drawing a mapped membrane with vtkMesoAtomMapper's warp
// adds to the process (resident memory after the frames, freed memory returned to the system
// first), against the bytes of the buffers the mapper reports (atoms, warp, draw lists), and,
// each in a process of its own, what drawing the same atoms mapped on the CPU adds, with
// vtkMesoAtomMapper and with VTK's vtkOpenGLSphereMapper. On llvmpipe the "GPU" buffers are host
// memory, and so is the rasterizer's scene: the triangles of a frame binned to screen tiles,
// which grows with the triangles drawn whatever draws them. The window, its render passes and
// the mapping are in place before the first figure, so what is measured is the drawing's.
//
//   BenchmarkWarpMemory [--membrane yiip|dppc] [--tiles 5] [--frames 3]
//                       [--draw warp|warp-unculled|cpu|vtk]     (one case; all by default)
//
// yiip: the YiiP membrane of Data/ (43 480 atoms with its protein); dppc: the DPPC patch
// (16 640 atoms, waters removed). The surface is the mitochondrion's outer membrane.
#include "vtkMesoAtomMapper.h"
#include "vtkMesoMembraneMapping.h"
#include "vtkMesoTrajectoryReader.h"

#include "atom_stage.h"
#include "mesolens_benchmark_timing.h"
#include "mesolens_test_data.h"

#include <vtkCamera.h>
#include <vtkCullerCollection.h>
#include <vtkExecutive.h>
#include <vtkNew.h>
#include <vtkPolyData.h>

#include <malloc.h>

#include <cstdio>
#include <cstdlib>
#include <string>

namespace {
/// Resident memory of this process in bytes, after returning freed heap pages to the system.
double resident_bytes()
{
  malloc_trim(0);
  return mesolens_test::process_status_bytes("VmRSS");
}
} // namespace

int main(int argc, char* argv[])
{
  const std::string draw = mesolens_test::text_argument(argc, argv, "--draw", "");
  if (draw.empty())
  {
    // Each case in a fresh process: the rasterizer keeps its scene memory for reuse.
    std::string options;
    for (const char* name : { "--membrane", "--tiles", "--frames" })
    {
      if (const char* value = mesolens_test::text_argument(argc, argv, name, nullptr))
      {
        options += std::string(" ") + name + " " + value;
      }
    }
    int failures = 0;
    for (const char* kind : { "warp", "warp-unculled", "cpu", "vtk" })
    {
      std::fflush(stdout);
      failures += std::system((std::string(argv[0]) + options + " --draw " + kind).c_str()) != 0;
    }
    return failures == 0 ? 0 : 1;
  }
  const std::string membrane_name = mesolens_test::text_argument(argc, argv, "--membrane", "yiip");
  const int tiles = mesolens_test::count_argument(argc, argv, "--tiles", 5);
  const int frames = mesolens_test::count_argument(argc, argv, "--frames", 3);
  const std::string topology = membrane_name == "dppc"
    ? mesolens_test::data_file("membranes/dppc128_slipids_323K.gro")
    : mesolens_test::data_file("membranes/yiip_popepopg.gro");
  const bool warp = draw.rfind("warp", 0) == 0;

  mesolens_bench::MitochondrionMapping mitochondrion(topology, tiles);
  vtkMesoTrajectoryReader* membrane = mitochondrion.Membrane;
  vtkMesoMembraneMapping* mapping = mitochondrion.Mapping;
  mapping->SetOutputAtoms(!warp);
  if (!mapping->GetExecutive()->Update() || !membrane->GetExecutive()->Update())
  {
    std::printf("BENCH warp-memory: the mapping of %d x %d tiles failed; skipped\n", tiles, tiles);
    return 0;
  }
  const double patch_atoms = double(membrane->GetOutput()->GetNumberOfPoints());
  vtkNew<vtkPolyData> mapped;
  mapped->ShallowCopy(mapping->GetOutput());

  // The window, its passes and the renderer's first frame before the first figure. Then, with
  // the camera turned away, everything is built and uploaded but no atom reaches the rasterizer.
  mesolens_bench::Stage stage;
  stage.Renderer->GetCullers()->RemoveAllItems(); // or it would skip the turned-away actor
  vtkNew<vtkPolyData> nothing;
  vtkNew<vtkMesoAtomMapper> empty;
  empty->SetInputData(nothing);
  stage.Show(empty, false);
  stage.Frame();
  const double before = resident_bytes();

  vtkNew<vtkMesoAtomMapper> ours;
  ours->SetRadiusScale(1e-4);
  mesolens_bench::VTKSpheres theirs(mapped);
  theirs.Radii->SetLengthScale(1e-4); // radii in the scene's µm
  theirs.Radii->Update();
  if (warp)
  {
    ours->SetInputConnection(membrane->GetOutputPort());
    ours->SetWarpConnection(mapping->GetOutputPort());
    ours->SetOcclusionCulling(draw == "warp");
  }
  else
  {
    ours->SetInputData(mapped);
  }
  stage.Show(draw == "vtk" ? static_cast<vtkMapper*>(theirs.Mapper) : ours.Get(), false);
  vtkCamera* camera = stage.Renderer->GetActiveCamera();
  camera->Yaw(180);
  stage.Frame();
  stage.Frame();
  const double built = resident_bytes() - before;
  camera->Yaw(180);
  stage.Time(frames);
  const double held = resident_bytes() - before;
  const double atoms_drawn =
    draw == "vtk" ? double(mapped->GetNumberOfPoints()) : double(ours->GetLastDrawnAtomCount());
  if (!warp)
  {
    std::printf("BENCH warp-memory: the same %.0f atoms mapped on the CPU, drawn by %s: %.1f MiB "
                "built (camera turned away), %.1f MiB once drawn, %.0f atoms drawn (%.0f bytes "
                "per atom drawn beyond the built)\n",
                double(mapped->GetNumberOfPoints()),
                draw == "vtk" ? "vtkOpenGLSphereMapper" : "vtkMesoAtomMapper (culled)",
                built / 1048576.0, held / 1048576.0, atoms_drawn, (held - built) / atoms_drawn);
    return 0;
  }
  const double atom_buffers = ours->GetBufferBytesPerAtom() * patch_atoms;
  const double warp_buffers = double(ours->GetWarpBufferBytes());
  const double draw_lists = ours->GetLastDrawListBytesPerAtom() * patch_atoms;
  const double buffers = atom_buffers + warp_buffers + draw_lists;
  std::printf("BENCH warp-memory: %s patch, %.0f atoms, %d x %d tiles, %d frames at 1024x768, "
              "GPU warp%s: %.1f MiB built (camera turned away) | its buffers %.1f MiB (atoms "
              "%.2f, warp %.2f, draw lists %.2f) | ratio %.2f (goal <= 2) | %.1f MiB once drawn, "
              "%.0f atoms drawn (%.0f bytes per atom drawn beyond the built: the rasterizer's)\n",
              membrane_name.c_str(), patch_atoms, tiles, tiles, frames,
              draw == "warp" ? " culled" : " unculled", built / 1048576.0, buffers / 1048576.0,
              atom_buffers / 1048576.0, warp_buffers / 1048576.0, draw_lists / 1048576.0,
              built / buffers, held / 1048576.0, atoms_drawn, (held - built) / atoms_drawn);
  return 0;
}
