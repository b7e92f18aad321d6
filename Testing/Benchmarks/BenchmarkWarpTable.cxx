// SPDX-License-Identifier: GPL-3.0-or-later
// Table 1 of Membrane Mapping (Waltemate, Sommer and Botsch, VCBM 2014) on this machine's
// OpenGL: a membrane patch mapped in k x k tiles onto a cell-sized sphere and drawn
// space-filling, in frames per second, three ways: the warp evaluated on the GPU from the patch
// (vtkMesoAtomMapper with the mapping's warp, culled), the atoms mapped on the CPU and drawn
// culled (vtkMesoAtomMapper), and VTK's vtkOpenGLSphereMapper on the same CPU-mapped atoms; with
// and without SSAO; and the GPU buffer memory of each (with the culling's draw lists). The
// first line is the OpenGL renderer.
//
//   BenchmarkWarpTable [--size 1920x1080] [--tiles 1,3,5,10,15] [--patches yiip,dppc]
//                      [--methods polynomial,instancing] [--frames 5]
//
// Patches (waters removed): YiiP in POPE/POPG (yiip_popepopg.gro) and the DPPC bilayer
// (dppc128_slipids_323K.gro), both all-atom, in Å; the sphere has a radius of 1.5 µm (15,000 Å,
// a small cell or a large organelle), the patch is mapped at its north pole at true size. The
// camera looks down the normal, then 40 degrees off it, framing the mapped tiles; each timed
// frame turns it 2 degrees; times are medians.
#include "atom_stage.h"
#include "mesolens_benchmark_timing.h"
#include "mesolens_test_data.h"
#include "vtkMesoAtomMapper.h"
#include "vtkMesoMembraneMapping.h"
#include "vtkMesoTrajectoryReader.h"

#include <vtkCamera.h>
#include <vtkExecutive.h>
#include <vtkFieldData.h>
#include <vtkSphereSource.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {
using mesolens_bench::Stage;
using mesolens_bench::VTKSpheres;

/// The renderer string of the window's OpenGL context.
std::string renderer_of(vtkOpenGLRenderWindow* window)
{
  window->Render();
  const std::string report = window->ReportCapabilities();
  const std::string key = "OpenGL renderer string:";
  const std::size_t at = report.find(key);
  if (at == std::string::npos)
  {
    return "unknown";
  }
  const std::size_t end = report.find('\n', at);
  return report.substr(at + key.size() + 1, end - at - key.size() - 1);
}

struct Patch
{
  std::string Name;
  std::string File;
};

/// One row per method and SSAO setting for one patch and k.
void table_rows(Stage& stage, vtkPolyData* sphere, const Patch& patch, int tiles,
                const std::vector<std::string>& methods, int frames)
{
  vtkNew<vtkMesoTrajectoryReader> membrane;
  membrane->SetTopologyFileName(mesolens_test::data_file(patch.File).c_str());
  membrane->RemoveWatersOn();
  membrane->Update();
  for (const std::string& method : methods)
  {
    vtkNew<vtkMesoMembraneMapping> mapping;
    mapping->SetInputData(0, sphere);
    mapping->SetMembraneConnection(membrane->GetOutputPort());
    mapping->SetSeedPoint(0, 0, 15000);
    mapping->SetTiles(tiles);
    mapping->SetMembraneToMeshScale(1.0);
    if (method == "instancing")
    {
      mapping->SetMappingMethodToMoleculeInstancing();
    }
    else
    {
      mapping->SetMappingMethodToPolynomial();
    }
    if (!mapping->GetExecutive()->Update())
    {
      std::printf("TABLE1 %s %dx%d %s: the mapping failed; skipped\n", patch.Name.c_str(), tiles,
                  tiles, method.c_str());
      continue;
    }
    const int mapped_tiles =
      int(mapping->GetOutput()->GetFieldData()->GetArray("Tiles")->GetComponent(0, 0));
    vtkNew<vtkPolyData> mapped;
    mapped->ShallowCopy(mapping->GetOutput());
    const vtkIdType atoms = mapped->GetNumberOfPoints();
    vtkNew<vtkMesoAtomMapper> cpu;
    cpu->SetInputData(mapped);
    VTKSpheres spheres(mapped);
    mapping->OutputAtomsOff();
    vtkNew<vtkMesoAtomMapper> gpu;
    gpu->SetInputConnection(membrane->GetOutputPort());
    gpu->SetWarpConnection(mapping->GetOutputPort());
    for (const bool ssao : { false, true })
    {
      // Every mapper turns from the CPU-mapped atoms' view: the same pictures.
      stage.Show(cpu, ssao);
      vtkNew<vtkCamera> start;
      start->DeepCopy(stage.Renderer->GetActiveCamera());
      stage.ShowFrom(gpu, ssao, start);
      const double warped = stage.Time(frames).second;
      const double warp_share = double(gpu->GetLastDrawnAtomCount()) / double(atoms);
      stage.ShowFrom(cpu, ssao, start);
      const double culled = stage.Time(frames).second;
      const double drawn_share = double(cpu->GetLastDrawnAtomCount()) / double(atoms);
      stage.ShowFrom(spheres.Mapper, ssao, start);
      const double vtk = stage.Time(frames).second;
      const double patch_atoms = double(membrane->GetOutput()->GetNumberOfPoints());
      std::printf(
        "TABLE1 %s (%lld atoms) %dx%d tiles (%dx%d mapped, %lld atoms) %s%s: GPU warp %.1f fps "
        "(%.0f %% drawn) | CPU-mapped culled %.1f fps (%.0f %% drawn) | vtkOpenGLSphereMapper "
        "%.1f fps | ratio warp/culled frame time %.2f | GPU MB: warp %.1f, CPU-mapped %.1f, VTK "
        "%.1f\n",
        patch.Name.c_str(), static_cast<long long>(patch_atoms), tiles, tiles, mapped_tiles,
        mapped_tiles, static_cast<long long>(atoms), method.c_str(), ssao ? ", SSAO" : "",
        1.0 / warped, 100.0 * warp_share, 1.0 / culled, 100.0 * drawn_share, 1.0 / vtk,
        warped / culled,
        (gpu->GetBufferBytesPerAtom() * patch_atoms +
         gpu->GetLastDrawListBytesPerAtom() * double(gpu->GetInput()->GetNumberOfPoints())) /
          1e6,
        (cpu->GetBufferBytesPerAtom() + cpu->GetLastDrawListBytesPerAtom()) * double(atoms) / 1e6,
        spheres.BytesPerAtom(atoms) * double(atoms) / 1e6);
      std::fflush(stdout);
    }
  }
}
} // namespace

int main(int argc, char* argv[])
{
  int width = 1920;
  int height = 1080;
  std::vector<int> tiles{ 1, 3, 5, 10, 15 };
  std::vector<std::string> patches{ "yiip", "dppc" };
  std::vector<std::string> methods{ "polynomial", "instancing" };
  int frames = 5;
  for (int i = 1; i + 1 < argc; i += 2)
  {
    const std::string arg = argv[i];
    const std::string value = argv[i + 1];
    if (arg == "--size")
    {
      std::sscanf(value.c_str(), "%dx%d", &width, &height);
    }
    else if (arg == "--tiles")
    {
      tiles.clear();
      for (const std::string& k : mesolens_test::comma_list(value))
      {
        tiles.push_back(std::max(1, std::atoi(k.c_str())));
      }
    }
    else if (arg == "--patches")
    {
      patches = mesolens_test::comma_list(value);
    }
    else if (arg == "--methods")
    {
      methods = mesolens_test::comma_list(value);
    }
    else if (arg == "--frames")
    {
      frames = std::max(1, std::atoi(value.c_str()));
    }
  }
  Stage stage(width, height);
  std::printf("TABLE1 OpenGL renderer: %s; window %d x %d\n", renderer_of(stage.Window).c_str(),
              width, height);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(15000);
  sphere->SetThetaResolution(256);
  sphere->SetPhiResolution(256);
  sphere->Update();
  for (const std::string& name : patches)
  {
    const Patch patch = name == "yiip" ? Patch{ "YiiP", "membranes/yiip_popepopg.gro" }
                                       : Patch{ "DPPC", "membranes/dppc128_slipids_323K.gro" };
    for (const int k : tiles)
    {
      table_rows(stage, sphere->GetOutput(), patch, k, methods, frames);
    }
  }
  return 0;
}
