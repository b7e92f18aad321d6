// SPDX-License-Identifier: GPL-3.0-or-later
// Solvent-excluded surface benchmark: vtkMesoMolecularSurface (probe 1.4 Å, element radii) against
// EDTSurf (Debian's edtsurf, its SES at its default scale, `-s 4`) and PyMOL (python3-pymol,
// surface_quality 1) on the same atoms (ATOM records, every alternate location) in the same run.
// Per file: our exact area and volume; per tolerance our time, the mesh's area error against the
// exact area (and that of its triangles projected onto the surface's normals, which leaves the
// chords' shortfall alone), its triangles and the peak memory, and the time at the coarsest
// tolerance whose mesh area lies within 0.5 % of the exact one (against 3wip's goal of 0.5 s), and
// that mesh's time without the exact figures (ComputeExactFigures off); the two tools' area, volume
// and time, and the ratios of our time to theirs. Then the 79 k-atom proteasome (3l5q.gro), which
// neither tool reads (goal 3 s), also as a mesh alone.
//
//   BenchmarkMolecularSurface [--repeats N]
//   BenchmarkMolecularSurface --smoke    (CI: crambin alone, at 0.3 and 0.1 Å, once each)
#include "vtkMesoArrayNames.h"
#include "vtkMesoParallelFor.h"
#include "mesolens_benchmark_timing.h"
#include "mesolens_test_data.h"
#include "mesolens_test_protein.h"
#include "vtkMesoMolecularSurface.h"
#include "vtkMesoStructureReader.h"
#include "vtkMesoTrajectoryReader.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkMassProperties.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSMPTools.h>
#include <vtkUnsignedShortArray.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {
using mesolens_test::median_seconds;

double field(vtkPolyData* data, const char* name)
{
  return data->GetFieldData()->GetArray(name)->GetTuple1(0);
}

/// Area of the mesh's triangles, Å².
double mesh_area(vtkPolyData* mesh)
{
  vtkNew<vtkMassProperties> properties;
  properties->SetInputData(mesh);
  properties->Update();
  return properties->GetSurfaceArea();
}

/// The mesh's area with each triangle projected onto the mean of its corners' normals (the
/// surface's), Å²: its shortfall from the exact area is the chords' alone. A triangle tilted
/// against the surface by an angle t has 1 - cos t of its area beyond that projection, so a mesh
/// can match the exact area with chords that fall short and triangles that tilt.
double projected_area(vtkPolyData* mesh)
{
  vtkDataArray* normals = mesh->GetPointData()->GetNormals();
  vtkPoints* points = mesh->GetPoints();
  double total = 0;
  auto cells = vtk::TakeSmartPointer(mesh->GetPolys()->NewIterator());
  for (cells->GoToFirstCell(); !cells->IsDoneWithTraversal(); cells->GoToNextCell())
  {
    vtkIdType size = 0;
    const vtkIdType* ids = nullptr;
    cells->GetCurrentCell(size, ids);
    if (size != 3)
    {
      continue;
    }
    std::array<std::array<double, 3>, 3> corner{};
    std::array<double, 3> mean{ 0, 0, 0 };
    for (int k = 0; k < 3; ++k)
    {
      points->GetPoint(ids[k], corner[std::size_t(k)].data());
      for (int a = 0; a < 3; ++a)
      {
        mean[std::size_t(a)] += normals->GetComponent(ids[k], a);
      }
    }
    std::array<double, 3> u{}, v{};
    for (std::size_t a = 0; a < 3; ++a)
    {
      u[a] = corner[1][a] - corner[0][a];
      v[a] = corner[2][a] - corner[0][a];
    }
    // Half the cross product is the vector area; its part along the unit mean normal counts.
    const std::array<double, 3> cross = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                                          u[0] * v[1] - u[1] * v[0] };
    const double length = std::sqrt(mean[0] * mean[0] + mean[1] * mean[1] + mean[2] * mean[2]);
    if (length > 0)
    {
      total += 0.5 * (cross[0] * mean[0] + cross[1] * mean[1] + cross[2] * mean[2]) / length;
    }
  }
  return total;
}

/// Peak resident memory since the last reset, MiB (Linux: VmHWM, reset through clear_refs).
double peak_mib()
{
  return mesolens_test::process_status_bytes("VmHWM") / 1048576.0;
}
void reset_peak()
{
  std::ofstream("/proc/self/clear_refs") << "5";
}

struct Baseline
{
  bool ok = false;
  double area = 0, volume = 0, seconds = 0, wall = 0;
  std::string note;
};

/// Runs `command`, returning its standard output and the wall time.
std::string run(const std::string& command, double& wall)
{
  std::string output;
  wall = mesolens_test::seconds_of([&] {
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe)
    {
      return;
    }
    char buffer[4096];
    while (std::fgets(buffer, sizeof buffer, pipe))
    {
      output += buffer;
    }
    pclose(pipe);
  });
  return output;
}

Baseline edtsurf(const std::string& path)
{
  Baseline result;
  const std::filesystem::path folder =
    std::filesystem::temp_directory_path() / "mesolens_benchmark_edtsurf";
  std::filesystem::create_directories(folder);
  const std::string output =
    run("EDTSurf -i " + path + " -s 4 -o " + (folder / "surface").string() + " 2>&1", result.wall);
  std::istringstream lines(output);
  std::string line;
  double scale = 0;
  while (std::getline(lines, line))
  {
    double a = 0, b = 0;
    if (std::sscanf(line.c_str(), "Total area %lf and volume %lf", &a, &b) == 2)
    {
      result.area = a;
      result.volume = b;
      result.ok = true;
    }
    else if (std::sscanf(line.c_str(), "Total time %lf", &a) == 1)
    {
      result.seconds = a;
    }
    const auto at = line.find("scale factor");
    if (at != std::string::npos)
    {
      scale = std::atof(line.c_str() + at + 12);
    }
  }
  std::filesystem::remove_all(folder);
  char note[64];
  std::snprintf(note, sizeof note, "grid %.2f Å", scale > 0 ? 1.0 / scale : 0.0);
  result.note = note;
  return result;
}

Baseline pymol(const std::string& path)
{
  Baseline result;
  const std::string script = std::string(MESOLENS_SOURCE_DIR) + "/Testing/Tools/pymol_ses.py";
  const std::string output =
    run("/usr/bin/python3 " + script + " " + path + " 2>/dev/null", result.wall);
  const auto at = output.find("area=");
  long long triangles = 0;
  if (at != std::string::npos &&
      std::sscanf(output.c_str() + at, "area=%lf volume=%lf seconds=%lf triangles=%lld",
                  &result.area, &result.volume, &result.seconds, &triangles) == 4)
  {
    result.ok = true;
    result.note = std::to_string(triangles) + " triangles";
  }
  return result;
}
} // namespace

int main(int argc, char* argv[])
{
  const bool smoke = argc > 1 && std::string(argv[1]) == "--smoke";
  const int repeats = smoke ? 1 : mesolens_test::count_argument(argc, argv, "--repeats", 3);
  std::printf("BENCH ses threads: %d\n", vtkMesoParallelFor::ThreadCount());
  const bool have_edtsurf = mesolens_test::program_available("command -v EDTSurf");
  const bool have_pymol = mesolens_test::program_available("/usr/bin/python3 -c 'import pymol'");
  if (!have_edtsurf || !have_pymol)
  {
    std::printf("BENCH ses EDTSurf %s, PyMOL %s (Debian packages edtsurf, python3-pymol)\n",
                have_edtsurf ? "found" : "missing: no EDTSurf ratios",
                have_pymol ? "found" : "missing: no PyMOL ratios");
  }
  // Sparse input first, while the process is small (its peak memory is the whole process's):
  // the search grids hold the occupied space alone (the dense index they replaced took 2.8 GB
  // and 4.5-7 s for two atoms 1000 Å apart on a diagonal, and refused them 3000 Å apart).
  for (const double apart : { 1000.0, 3000.0 })
  {
    vtkNew<vtkPolyData> pair;
    vtkNew<vtkPoints> points;
    points->InsertNextPoint(0, 0, 0);
    points->InsertNextPoint(apart, apart, apart);
    vtkNew<vtkUnsignedShortArray> elements;
    elements->SetName(vtkMesoArrayNames::AtomicNumber);
    elements->InsertNextValue(6);
    elements->InsertNextValue(6);
    pair->SetPoints(points);
    pair->GetPointData()->AddArray(elements);
    vtkNew<vtkMesoMolecularSurface> surface;
    surface->SetInputData(pair);
    surface->SetTolerance(0.2);
    reset_peak();
    const double seconds = median_seconds(1, [&] { surface->Update(); });
    std::printf("BENCH ses two carbon atoms %.0f Å apart on a diagonal: %.3f s, peak memory %.0f "
                "MiB, %lld triangles\n",
                apart, seconds, peak_mib(),
                static_cast<long long>(surface->GetOutput()->GetNumberOfPolys()));
  }
  std::vector<std::string> files{ mesolens_test::data_file("proteins/1crn.pdb"),
                                  mesolens_test::data_file("proteins/1tii.pdb"),
                                  mesolens_test::shared_file("proteins/3wip.pdb"),
                                  mesolens_test::shared_file("proteins/4jsv.pdb") };
  std::vector<double> tolerances{ 0.3, 0.15, 0.13, 0.12, 0.11, 0.1, 0.09, 0.08, 0.06, 0.02 };
  if (smoke)
  {
    files.resize(1);
    tolerances = { 0.3, 0.1 };
  }
  for (const std::string& path : files)
  {
    if (!mesolens_test::exists(path))
    {
      continue;
    }
    const std::string name = path.substr(path.rfind('/') + 1);
    vtkNew<vtkMesoStructureReader> reader;
    reader->SetFileName(path.c_str());
    reader->KeepAllAlternateLocationsOn(); // as EDTSurf and PyMOL read them
    reader->Update();
    auto atoms = mesolens_test::protein_atoms(reader->GetOutput());
    vtkNew<vtkMesoMolecularSurface> surface;
    surface->SetInputData(atoms);
    double time_at_interactive = 0;
    double exact_area = 0, exact_volume = 0; // the same at every tolerance
    // The fastest tolerance whose mesh area lies within 0.5 % of the exact area.
    double accurate_seconds = 0, accurate_tolerance = 0;
    for (const double tolerance : tolerances)
    {
      surface->SetTolerance(tolerance);
      reset_peak();
      const double seconds = median_seconds(tolerance < 0.06 ? 1 : repeats, [&] {
        surface->Modified();
        surface->Update();
      });
      vtkPolyData* out = surface->GetOutput();
      const double exact = field(out, vtkMesoArrayNames::Area);
      exact_area = exact;
      exact_volume = field(out, vtkMesoArrayNames::Volume);
      const double error = mesh_area(out) / exact - 1.0;
      std::printf("BENCH ses %s (%lld atoms) tolerance %.2f Å: %.3f s, mesh area %+.2f %% of the "
                  "exact %.1f Å² (%+.2f %% with its triangles projected onto the surface's "
                  "normals), volume %.1f Å³, %lld triangles, peak memory %.0f MiB, %d singular "
                  "patches\n",
                  name.c_str(), static_cast<long long>(atoms->GetNumberOfPoints()), tolerance,
                  seconds, 100 * error, exact, 100 * (projected_area(out) / exact - 1.0),
                  field(out, vtkMesoArrayNames::Volume),
                  static_cast<long long>(out->GetNumberOfPolys()), peak_mib(),
                  int(field(out, vtkMesoArrayNames::SingularPatchCount)));
      if (tolerance == 0.1)
      {
        time_at_interactive = seconds;
      }
      if (std::abs(error) <= 0.005 && (accurate_tolerance == 0 || seconds < accurate_seconds))
      {
        accurate_seconds = seconds;
        accurate_tolerance = tolerance;
      }
    }
    if (accurate_tolerance > 0)
    {
      const bool goal = name == "3wip.pdb"; // the goal: 0.5 s at <= 0.5 % area error
      std::printf("BENCH ses %s at <= 0.5 %% mesh area error: tolerance %.2f Å, %.3f s%s",
                  name.c_str(), accurate_tolerance, accurate_seconds, goal ? "" : "\n");
      if (goal)
      {
        std::printf(" (goal 0.5 s: ratio %.2f)\n", accurate_seconds / 0.5);
      }
      // The same mesh without the exact figures (ComputeExactFigures off), as the tools make it.
      surface->SetTolerance(accurate_tolerance);
      surface->ComputeExactFiguresOff();
      const double mesh_seconds = median_seconds(repeats, [&] {
        surface->Modified();
        surface->Update();
      });
      surface->ComputeExactFiguresOn();
      std::printf("BENCH ses %s mesh alone (no exact figures) at tolerance %.2f Å: %.3f s%s",
                  name.c_str(), accurate_tolerance, mesh_seconds, goal ? "" : "\n");
      if (goal)
      {
        std::printf(" (goal 0.5 s: ratio %.2f)\n", mesh_seconds / 0.5);
      }
    }
    for (const auto& [tool, baseline] :
         { std::make_pair(std::string("EDTSurf"), have_edtsurf ? edtsurf(path) : Baseline{}),
           std::make_pair(std::string("PyMOL"), have_pymol ? pymol(path) : Baseline{}) })
    {
      if (!baseline.ok)
      {
        continue;
      }
      std::printf("BENCH ses %s %s (%s): area %.1f Å² (ours %+.2f %%), volume %.1f Å³ (ours "
                  "%+.2f %%), surface %.2f s (whole program %.2f s); ratio ours (tolerance 0.1) "
                  "/ %s %.3f\n",
                  name.c_str(), tool.c_str(), baseline.note.c_str(), baseline.area,
                  100 * (exact_area / baseline.area - 1), baseline.volume,
                  100 * (exact_volume / baseline.volume - 1), baseline.seconds, baseline.wall,
                  tool.c_str(), time_at_interactive / baseline.seconds);
    }
  }
  const std::string gro = mesolens_test::shared_file("proteins/3l5q.gro");
  if (!smoke && mesolens_test::exists(gro))
  {
    vtkNew<vtkMesoTrajectoryReader> reader;
    reader->SetTopologyFileName(gro.c_str());
    reader->Update();
    vtkNew<vtkMesoMolecularSurface> surface;
    surface->SetInputData(reader->GetOutput());
    for (const double tolerance : { 1.0, 0.3, 0.1 })
    {
      surface->SetTolerance(tolerance);
      reset_peak();
      const double seconds = median_seconds(1, [&] {
        surface->Modified();
        surface->Update();
      });
      vtkPolyData* out = surface->GetOutput();
      std::printf("BENCH ses 3l5q.gro (%lld atoms) tolerance %.2f Å: %.2f s (goal 3 s: ratio "
                  "%.2f), exact area %.0f Å², volume %.0f Å³, mesh area %+.2f %% (%+.2f %% "
                  "projected), %lld triangles, peak memory %.0f MiB\n",
                  static_cast<long long>(reader->GetOutput()->GetNumberOfPoints()), tolerance,
                  seconds, seconds / 3.0, field(out, vtkMesoArrayNames::Area),
                  field(out, vtkMesoArrayNames::Volume),
                  100 * (mesh_area(out) / field(out, vtkMesoArrayNames::Area) - 1),
                  100 * (projected_area(out) / field(out, vtkMesoArrayNames::Area) - 1),
                  static_cast<long long>(out->GetNumberOfPolys()), peak_mib());
    }
    surface->ComputeExactFiguresOff();
    for (const double tolerance : { 0.3, 1.0 })
    {
      surface->SetTolerance(tolerance);
      const double seconds = median_seconds(1, [&] {
        surface->Modified();
        surface->Update();
      });
      std::printf("BENCH ses 3l5q.gro mesh alone (no exact figures) tolerance %.2f Å: %.2f s (goal "
                  "3 s: ratio %.2f), %lld triangles\n",
                  tolerance, seconds, seconds / 3.0,
                  static_cast<long long>(surface->GetOutput()->GetNumberOfPolys()));
    }
  }
  return 0;
}
