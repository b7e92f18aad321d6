// SPDX-License-Identifier: GPL-3.0-or-later
// Solvent-accessible area benchmark: vtkMesoSurfaceArea (exact, element radii, probe 1.4 Å)
// against Debian's FreeSASA 2.1.2 (Lee & Richards with 20 slices, its default, and Shrake &
// Rupley with 100 points; ProtOr radii) on the same files in the same run, whole programs
// (reading included) and our computation alone; then the 79 k-atom proteasome (3l5q.gro).
//
//   BenchmarkSurfaceArea [--repeats N]
#include "vtkMesoArrayNames.h"
#include "vtkMesoParallelFor.h"
#include "mesolens_benchmark_timing.h"
#include "mesolens_test_data.h"
#include "vtkMesoStructureReader.h"
#include "vtkMesoSurfaceArea.h"
#include "vtkMesoTrajectoryReader.h"

#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSMPTools.h>

#include <cstdio>
#include <cstdlib>
#include <string>

namespace {
using mesolens_test::median_seconds;
} // namespace

int main(int argc, char* argv[])
{
  const int repeats = mesolens_test::count_argument(argc, argv, "--repeats", 5);
  std::printf("BENCH sas threads: %d\n", vtkMesoParallelFor::ThreadCount());
  const bool freesasa = mesolens_test::program_available("freesasa --version");
  if (!freesasa)
  {
    std::printf("BENCH sas FreeSASA is not installed (Debian package freesasa): no ratios\n");
  }
  for (const std::string& path : { mesolens_test::data_file("proteins/1ubq.pdb"),
                                   mesolens_test::data_file("proteins/4we2.pdb"),
                                   mesolens_test::data_file("proteins/1tii.pdb"),
                                   mesolens_test::shared_file("proteins/3wip.pdb"),
                                   mesolens_test::shared_file("proteins/4jsv.pdb") })
  {
    if (!mesolens_test::exists(path))
    {
      continue;
    }
    const std::string name = path.substr(path.rfind('/') + 1);
    vtkNew<vtkMesoStructureReader> reader;
    reader->SetFileName(path.c_str());
    reader->RemoveWatersOn(); // FreeSASA leaves out HETATM by default, waters among them
    reader->Update();
    vtkNew<vtkMesoSurfaceArea> area;
    area->SetInputData(reader->GetOutput());
    const double alone = median_seconds(repeats, [&] {
      area->Modified();
      area->Update();
    });
    const double total =
      area->GetOutput()->GetFieldData()->GetArray(vtkMesoArrayNames::TotalArea)->GetTuple1(0);
    const double whole = median_seconds(repeats, [&] {
      vtkNew<vtkMesoStructureReader> fresh;
      fresh->SetFileName(path.c_str());
      fresh->RemoveWatersOn();
      vtkNew<vtkMesoSurfaceArea> measure;
      measure->SetInputConnection(fresh->GetOutputPort());
      measure->Update();
    });
    std::printf("BENCH sas %s (%lld atoms): exact %.1f Å² (element radii, ligands kept: not "
                "FreeSASA's area), %.1f ms (reading included %.1f ms)\n",
                name.c_str(), static_cast<long long>(reader->GetOutput()->GetNumberOfPoints()),
                total, 1e3 * alone, 1e3 * whole);
    if (freesasa)
    {
      const std::string lee_richards = "freesasa " + path + " > /dev/null 2>&1";
      const std::string shrake_rupley =
        "freesasa --shrake-rupley --resolution=100 " + path + " > /dev/null 2>&1";
      const double lr = median_seconds(repeats, [&] { (void)std::system(lee_richards.c_str()); });
      const double sr = median_seconds(repeats, [&] { (void)std::system(shrake_rupley.c_str()); });
      std::printf("BENCH sas %s FreeSASA: Lee-Richards (20 slices) %.1f ms, Shrake-Rupley (100 "
                  "points) %.1f ms; ratio ours (reading included) / LR %.2f, / SR %.2f\n",
                  name.c_str(), 1e3 * lr, 1e3 * sr, whole / lr, whole / sr);
    }
  }
  const std::string gro = mesolens_test::shared_file("proteins/3l5q.gro");
  if (mesolens_test::exists(gro))
  {
    vtkNew<vtkMesoTrajectoryReader> reader;
    reader->SetTopologyFileName(gro.c_str());
    reader->Update();
    vtkNew<vtkMesoSurfaceArea> area;
    area->SetInputData(reader->GetOutput());
    const double seconds = median_seconds(std::min(repeats, 3), [&] {
      area->Modified();
      area->Update();
    });
    std::printf(
      "BENCH sas 3l5q.gro (%lld atoms): exact SAS %.0f Å², volume %.0f Å³, %.2f s\n",
      static_cast<long long>(reader->GetOutput()->GetNumberOfPoints()),
      area->GetOutput()->GetFieldData()->GetArray(vtkMesoArrayNames::TotalArea)->GetTuple1(0),
      area->GetOutput()->GetFieldData()->GetArray(vtkMesoArrayNames::Volume)->GetTuple1(0),
      seconds);
  }
  return 0;
}
