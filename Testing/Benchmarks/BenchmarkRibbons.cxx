// SPDX-License-Identifier: GPL-3.0-or-later
// Ribbon benchmark: vtkMesoRibbons on the 79 k-atom proteasome 3l5q.gro at each quality level,
// and DSSP + ribbons against the goal of 100 ms; then against VTK's vtkProteinRibbonFilter on
// PDB files it reads (its own reader's output, the file's HELIX/SHEET records), in the same run.
//
//   BenchmarkRibbons [--repeats N] [--levels 1,2,3,6,12]   (samples per residue on 3l5q)
#include "mesolens_benchmark_timing.h"
#include "vtkMesoParallelFor.h"
#include "mesolens_test_data.h"
#include "vtkMesoRibbons.h"
#include "vtkMesoSecondaryStructure.h"
#include "vtkMesoStructureReader.h"
#include "vtkMesoTrajectoryReader.h"

#include <vtkNew.h>
#include <vtkPDBReader.h>
#include <vtkPolyData.h>
#include <vtkProteinRibbonFilter.h>
#include <vtkSMPTools.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {
using mesolens_test::median_seconds;
} // namespace

int main(int argc, char* argv[])
{
  const int repeats = mesolens_test::count_argument(argc, argv, "--repeats", 5);
  std::vector<int> levels{ 1, 2, 3, 6, 12 };
  for (int i = 1; i + 1 < argc; ++i)
  {
    if (std::string(argv[i]) == "--levels")
    {
      levels.clear();
      for (const std::string& item : mesolens_test::comma_list(argv[i + 1]))
      {
        levels.push_back(std::max(1, std::atoi(item.c_str())));
      }
    }
  }
  std::printf("BENCH ribbons threads: %d\n", vtkMesoParallelFor::ThreadCount());

  // 1. The proteasome, from a GRO file (no records: DSSP needed).
  const std::string gro = mesolens_test::shared_file("proteins/3l5q.gro");
  if (mesolens_test::exists(gro))
  {
    vtkNew<vtkMesoTrajectoryReader> reader;
    reader->SetTopologyFileName(gro.c_str());
    reader->Update();
    vtkNew<vtkMesoSecondaryStructure> dssp;
    dssp->SetInputData(reader->GetOutput());
    const double assign = median_seconds(repeats, [&] {
      dssp->Modified();
      dssp->Update();
    });
    vtkNew<vtkMesoRibbons> ribbons;
    ribbons->SetInputData(dssp->GetOutput());
    ribbons->Update(); // the atom layout is learnt once; the timings below are per frame
    for (const int level : levels)
    {
      ribbons->SetSubdivisions(level);
      const double seconds = median_seconds(repeats, [&] {
        ribbons->Modified();
        ribbons->Update();
      });
      std::printf("BENCH ribbons 3l5q.gro (%lld atoms) %2d samples/residue: %lld triangles, "
                  "%.1f ms; with DSSP (%.1f ms) %.1f ms, goal 100 ms, ratio %.2f\n",
                  static_cast<long long>(reader->GetOutput()->GetNumberOfPoints()), level,
                  static_cast<long long>(ribbons->GetOutput()->GetNumberOfPolys()), 1e3 * seconds,
                  1e3 * assign, 1e3 * (seconds + assign), (seconds + assign) / 0.1);
    }
  }
  else
  {
    std::printf("BENCH ribbons 3l5q.gro needs ../shared/data: skipped\n");
  }

  // 2. Against vtkProteinRibbonFilter (VTK 9.1), each on its own reader's output.
  for (const std::string& path : { mesolens_test::data_file("proteins/1tii.pdb"),
                                   mesolens_test::shared_file("proteins/4jsv.pdb") })
  {
    if (!mesolens_test::exists(path))
    {
      continue;
    }
    const std::string name = path.substr(path.rfind('/') + 1);
    vtkNew<vtkPDBReader> vtk_reader;
    vtk_reader->SetFileName(path.c_str());
    vtk_reader->Update();
    vtkNew<vtkProteinRibbonFilter> vtk_ribbons;
    vtk_ribbons->SetInputData(vtk_reader->GetOutput());
    const double vtk_seconds = median_seconds(repeats, [&] {
      vtk_ribbons->Modified();
      vtk_ribbons->Update();
    });
    const vtkIdType vtk_triangles = vtk_ribbons->GetOutput()->GetNumberOfCells();
    vtkNew<vtkMesoStructureReader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    vtkNew<vtkMesoSecondaryStructure> dssp;
    dssp->SetInputData(reader->GetOutput());
    vtkNew<vtkMesoRibbons> ribbons;
    ribbons->SetInputConnection(dssp->GetOutputPort());
    ribbons->Update(); // the atom layout is learnt once; the timings below are per frame
    for (int level : { 6, 12 })
    {
      ribbons->SetSubdivisions(level);
      const double ours = median_seconds(repeats, [&] {
        ribbons->Modified();
        ribbons->Update();
      });
      const double with_dssp = median_seconds(repeats, [&] {
        dssp->Modified();
        ribbons->Update();
      });
      std::printf("BENCH ribbons %s: vtkProteinRibbonFilter (defaults, file records) %.1f ms, "
                  "%lld cells; vtkMesoRibbons %d samples/residue %.1f ms (%lld triangles), with "
                  "DSSP %.1f ms; ratio ours/VTK %.2f (with DSSP %.2f)\n",
                  name.c_str(), 1e3 * vtk_seconds, static_cast<long long>(vtk_triangles), level,
                  1e3 * ours, static_cast<long long>(ribbons->GetOutput()->GetNumberOfPolys()),
                  1e3 * with_dssp, ours / vtk_seconds, with_dssp / vtk_seconds);
    }
  }
  return 0;
}
