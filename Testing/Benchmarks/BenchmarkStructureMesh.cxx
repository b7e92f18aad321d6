// SPDX-License-Identifier: GPL-3.0-or-later
// Structure-mesh benchmark: the cutaway's structure mesh made from the molecules of every
// membrane in Data/membranes and ../shared/data/membranes (each file name once), and from a
// head-group-only cloud (the PO4 beads of the Martini vesicle), through vtkMesoStructuredCutaway
// without a given structure. Per input and asked vertex count N it prints the vertices got, the
// smallest and largest triangle angle (the goal: all within 30-120°), the connected components
// and boundary loops (goal: one component; a flat periodic patch one loop, a vesicle none), the
// mesh's extent, and the time of the filter's first update (grouping, centres, structure mesh,
// assignment), with its ratio to the baseline of reading the same file in the same run.
//
//   BenchmarkStructureMesh [--smoke] [--repeats N]
//
// --smoke (CI): N = 500 only, one run each.
#include "vtkMesoArrayNames.h"
#include "vtkMesoParallelFor.h"
#include "mesolens_benchmark_timing.h"
#include "mesolens_test_data.h"
#include "mesolens_vtk_test_utilities.h"
#include "vtkMesoStructuredCutaway.h"
#include "vtkMesoTrajectoryReader.h"

#include "mesolens/cutaway/structure_mesh.h"
#include "mesolens/mesh/triangle_mesh.h"

#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkCellArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSMPTools.h>
#include <vtkStringArray.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <dirent.h>
#include <set>
#include <string>
#include <vector>

namespace {
using mesolens_test::median_seconds;
using mesolens_test::seconds_of;

/// The .gro files in `folder` (sorted; none when it is absent).
std::vector<std::string> membrane_files(const std::string& folder)
{
  std::vector<std::string> names;
  if (DIR* directory = opendir(folder.c_str()))
  {
    while (const dirent* entry = readdir(directory))
    {
      const std::string name = entry->d_name;
      if (name.size() > 4 && name.compare(name.size() - 4, 4, ".gro") == 0)
      {
        names.push_back(name);
      }
    }
    closedir(directory);
  }
  std::sort(names.begin(), names.end());
  return names;
}

/// The triangles of a polydata as a Core mesh.
mesolens::TriangleMesh triangle_mesh(vtkPolyData* surface)
{
  mesolens::TriangleMesh mesh;
  for (vtkIdType v = 0; v < surface->GetNumberOfPoints(); ++v)
  {
    double p[3];
    surface->GetPoint(v, p);
    mesh.points.insert(mesh.points.end(), { p[0], p[1], p[2] });
  }
  vtkNew<vtkIdList> corners;
  for (vtkIdType t = 0; t < surface->GetPolys()->GetNumberOfCells(); ++t)
  {
    surface->GetPolys()->GetCellAtId(t, corners);
    for (vtkIdType k = 0; k < corners->GetNumberOfIds(); ++k)
    {
      mesh.triangles.push_back(corners->GetId(k));
    }
  }
  return mesh;
}

/// The atoms of `atoms` whose AtomName is `name`, with their point data and field data.
vtkSmartPointer<vtkPolyData> atoms_named(vtkPolyData* atoms, const char* name)
{
  auto* names = vtkStringArray::SafeDownCast(
    atoms->GetPointData()->GetAbstractArray(vtkMesoArrayNames::AtomName));
  vtkNew<vtkIdList> kept;
  for (vtkIdType a = 0; names && a < atoms->GetNumberOfPoints(); ++a)
  {
    if (names->GetValue(a) == name)
    {
      kept->InsertNextId(a);
    }
  }
  auto selected = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  atoms->GetPoints()->GetPoints(kept, points);
  selected->SetPoints(points);
  selected->GetPointData()->CopyAllocate(atoms->GetPointData(), kept->GetNumberOfIds());
  for (vtkIdType k = 0; k < kept->GetNumberOfIds(); ++k)
  {
    selected->GetPointData()->CopyData(atoms->GetPointData(), kept->GetId(k), k);
  }
  selected->GetFieldData()->ShallowCopy(atoms->GetFieldData());
  return selected;
}

/// Makes the structure of `atoms` with `vertices` vertices `repeats` times and prints one line.
void measure(const std::string& label, vtkPolyData* atoms, int vertices, int repeats,
             double read_seconds)
{
  vtkSmartPointer<vtkPolyData> structure;
  std::string errors;
  long molecules = 0;
  const double seconds = median_seconds(repeats, [&] {
    vtkNew<vtkMesoStructuredCutaway> cutaway;
    cutaway->SetInputData(atoms);
    cutaway->SetStructureVertices(vertices);
    mesolens_test::EventRecorder events(cutaway);
    cutaway->Update();
    errors = events.AllErrors();
    structure = cutaway->GetOutput(1);
    vtkDataArray* visible =
      cutaway->GetOutput()->GetFieldData()->GetArray(vtkMesoArrayNames::MoleculeVisible);
    molecules = visible ? long(visible->GetNumberOfTuples()) : 0;
  });
  std::printf("BENCH structure-mesh %s, N = %d:", label.c_str(), vertices);
  if (!errors.empty() || structure->GetNumberOfCells() == 0)
  {
    std::replace(errors.begin(), errors.end(), '\n', ' ');
    std::printf(" no mesh (%s); %.3f s\n", errors.c_str(), seconds);
    return;
  }
  const mesolens::TriangleMesh mesh = triangle_mesh(structure);
  const auto field = [&](const char* name) {
    vtkDataArray* array = structure->GetFieldData()->GetArray(name);
    return array ? array->GetTuple1(0) : -1.0;
  };
  double bounds[6];
  structure->GetBounds(bounds);
  std::printf(" %lld vertices (%.2f x asked), angles %.1f-%.1f°, %zu component(s), %zu boundary "
              "loop(s), extent %.0f x %.0f x %.0f Å; %ld molecules; %.3f s, %.2f x reading the "
              "file (%.3f s)\n",
              static_cast<long long>(structure->GetNumberOfPoints()),
              double(structure->GetNumberOfPoints()) / vertices, field(vtkMesoArrayNames::MinAngle),
              field(vtkMesoArrayNames::MaxAngle), mesolens::mesh_quality(mesh).components,
              mesolens::boundary_loops(mesh).size(), bounds[1] - bounds[0], bounds[3] - bounds[2],
              bounds[5] - bounds[4], molecules, seconds, seconds / read_seconds, read_seconds);
}
} // namespace

int main(int argc, char* argv[])
{
  bool smoke = false;
  for (int i = 1; i < argc; ++i)
  {
    smoke = smoke || !std::strcmp(argv[i], "--smoke");
  }
  const int repeats = mesolens_test::count_argument(argc, argv, "--repeats", smoke ? 1 : 3);
  const std::vector<int> counts =
    smoke ? std::vector<int>{ 500 } : std::vector<int>{ 20, 150, 500, 2000 };
  std::printf("BENCH structure-mesh: %d threads, median of %d runs\n",
              vtkMesoParallelFor::ThreadCount(), repeats);

  // Each file name once: the repository's copy first, the shared folder's others after.
  std::vector<std::string> paths;
  std::set<std::string> seen;
  for (const std::string& folder :
       { mesolens_test::data_file("membranes"), mesolens_test::shared_file("membranes") })
  {
    for (const std::string& name : membrane_files(folder))
    {
      if (seen.insert(name).second)
      {
        paths.push_back(folder + "/" + name);
      }
    }
  }
  for (const std::string& path : paths)
  {
    vtkNew<vtkMesoTrajectoryReader> reader;
    reader->SetTopologyFileName(path.c_str());
    const double read = seconds_of([&] { reader->Update(); });
    vtkNew<vtkPolyData> atoms;
    atoms->ShallowCopy(reader->GetOutput());
    const std::string name = path.substr(path.find_last_of('/') + 1);
    std::printf("BENCH structure-mesh input %s: %lld atoms, read in %.3f s\n", name.c_str(),
                static_cast<long long>(atoms->GetNumberOfPoints()), read);
    for (int n : counts)
    {
      measure(name, atoms, n, repeats, read);
    }
    if (name == "martini_dppc_vesicle.gro")
    {
      // Head groups only: one PO4 bead per lipid, the two leaflets about 40 Å apart.
      const vtkSmartPointer<vtkPolyData> heads = atoms_named(atoms, "PO4");
      std::printf("BENCH structure-mesh input %s PO4 beads only: %lld beads\n", name.c_str(),
                  static_cast<long long>(heads->GetNumberOfPoints()));
      for (int n : counts)
      {
        measure(name + " PO4 only", heads, n, repeats, read);
      }
    }
  }
  return 0;
}
