// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoArrayNames.h"
#include "vtkMesoMolecularSurface.h"

#include "mesolens_test_data.h"
#include "mesolens_vtk_test_utilities.h"
#include "vtkMesoStructureReader.h"
#include "vtkMesoSurfaceArea.h"

#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFeatureEdges.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>

namespace {
constexpr double pi = 3.14159265358979323846;

double field(vtkPolyData* data, const char* name)
{
  vtkDataArray* array = data->GetFieldData()->GetArray(name);
  return array ? array->GetTuple1(0) : std::nan("");
}

vtkIdType open_edges(vtkPolyData* surface)
{
  vtkNew<vtkFeatureEdges> edges;
  edges->SetInputData(surface);
  edges->BoundaryEdgesOn();
  edges->NonManifoldEdgesOn();
  edges->FeatureEdgesOff();
  edges->ManifoldEdgesOff();
  edges->Update();
  return edges->GetOutput()->GetNumberOfCells();
}

vtkNew<vtkPolyData> spheres(const std::vector<std::array<double, 4>>& atoms)
{
  vtkNew<vtkPolyData> data;
  vtkNew<vtkPoints> points;
  vtkNew<vtkDoubleArray> radius;
  radius->SetName("Radius");
  for (const auto& atom : atoms)
  {
    points->InsertNextPoint(atom[0], atom[1], atom[2]);
    radius->InsertNextValue(atom[3]);
  }
  data->SetPoints(points);
  data->GetPointData()->AddArray(radius);
  return data;
}
} // namespace

TEST(vtkMesoMolecularSurface, OneAtomInEveryKind)
{
  auto atom = spheres({ { 1, 2, 3, 1.6 } });
  vtkNew<vtkMesoMolecularSurface> surface;
  surface->SetInputData(atom);
  surface->SetRadiusArrayName("Radius");
  for (int type : { 0, 1, 2 })
  {
    surface->SetSurfaceType(type);
    surface->Update();
    vtkPolyData* out = surface->GetOutput();
    const double radius = 1.6 + (type == 1 ? 1.4 : 0.0);
    EXPECT_NEAR(field(out, vtkMesoArrayNames::Area), 4 * pi * radius * radius, 1e-9);
    EXPECT_NEAR(field(out, vtkMesoArrayNames::Volume), 4.0 / 3.0 * pi * radius * radius * radius,
                1e-9);
    ASSERT_GT(out->GetNumberOfPolys(), 100);
    EXPECT_EQ(open_edges(out), 0);
    double p[3];
    out->GetPoint(0, p);
    EXPECT_NEAR(std::hypot(p[0] - 1, p[1] - 2, p[2] - 3), radius, 1e-5);
    ASSERT_NE(out->GetPointData()->GetNormals(), nullptr);
    ASSERT_NE(out->GetPointData()->GetArray(vtkMesoArrayNames::AtomId), nullptr);
    ASSERT_NE(out->GetPointData()->GetArray(vtkMesoArrayNames::PatchType), nullptr);
    ASSERT_NE(out->GetPointData()->GetArray("Radius"), nullptr); // atom arrays carried over
  }
}

TEST(vtkMesoMolecularSurface, EnterotoxinByChainWithProgress)
{
  vtkNew<vtkMesoStructureReader> reader;
  reader->SetFileName(mesolens_test::data_file("proteins/1tii.pdb").c_str());
  vtkNew<vtkMesoMolecularSurface> surface;
  surface->SetInputConnection(reader->GetOutputPort());
  surface->SetTolerance(0.3);
  mesolens_test::EventRecorder events(surface);
  std::vector<double> progress;
  vtkNew<vtkCallbackCommand> on_progress;
  on_progress->SetClientData(&progress);
  on_progress->SetCallback([](vtkObject*, unsigned long, void* client, void* data) {
    static_cast<std::vector<double>*>(client)->push_back(*static_cast<double*>(data));
  });
  surface->AddObserver(vtkCommand::ProgressEvent, on_progress);
  surface->Update();
  ASSERT_TRUE(events.Errors.empty()) << events.AllErrors();
  vtkPolyData* out = surface->GetOutput();
  EXPECT_EQ(open_edges(out), 0);
  EXPECT_GT(progress.size(), 3u);
  EXPECT_DOUBLE_EQ(progress.back(), 1.0);
  // Every vertex belongs to a real atom, chains are numbered, all three patch kinds appear.
  vtkDataArray* atom_ids = out->GetPointData()->GetArray(vtkMesoArrayNames::AtomId);
  vtkDataArray* chains = out->GetPointData()->GetArray(vtkMesoArrayNames::ChainIndex);
  vtkDataArray* patches = out->GetPointData()->GetArray(vtkMesoArrayNames::PatchType);
  ASSERT_TRUE(atom_ids && chains && patches);
  std::set<int> chain_set, patch_set;
  for (vtkIdType v = 0; v < out->GetNumberOfPoints(); ++v)
  {
    ASSERT_GE(atom_ids->GetTuple1(v), 0);
    ASSERT_LT(atom_ids->GetTuple1(v), reader->GetOutput()->GetNumberOfPoints());
    chain_set.insert(int(chains->GetTuple1(v)));
    patch_set.insert(int(patches->GetTuple1(v)));
  }
  EXPECT_GE(chain_set.size(), 2u);
  EXPECT_EQ(patch_set.size(), 3u);
  // EDTSurf (a grid, its own radii, ATOM records only) gives 24946 Å²; PyMOL 26278.
  EXPECT_GT(field(out, vtkMesoArrayNames::Area), 22000.0);
  EXPECT_LT(field(out, vtkMesoArrayNames::Area), 30000.0);
  EXPECT_NEAR(field(out, vtkMesoArrayNames::ConvexArea) +
                field(out, vtkMesoArrayNames::ToroidalArea) +
                field(out, vtkMesoArrayNames::ConcaveArea),
              field(out, vtkMesoArrayNames::Area), 1e-6 * field(out, vtkMesoArrayNames::Area));
  // Dropping cavities leaves the outer surface alone.
  // (`out` is the filter's output object: the figures before the change are kept first.)
  const double with_cavities = field(out, vtkMesoArrayNames::Area);
  const double cavities = field(out, vtkMesoArrayNames::CavityCount);
  ASSERT_GT(cavities, 0);
  surface->KeepCavitiesOff();
  surface->Update();
  EXPECT_EQ(field(surface->GetOutput(), vtkMesoArrayNames::CavityCount), cavities);
  EXPECT_EQ(field(surface->GetOutput(), vtkMesoArrayNames::ComponentCount), 1);
  EXPECT_LT(field(surface->GetOutput(), vtkMesoArrayNames::Area), with_cavities);
  EXPECT_EQ(open_edges(surface->GetOutput()), 0);
  // The mesh alone: the same triangles, no exact figures.
  const vtkIdType triangles = surface->GetOutput()->GetNumberOfCells();
  surface->ComputeExactFiguresOff();
  surface->Update();
  EXPECT_EQ(surface->GetOutput()->GetNumberOfCells(), triangles);
  EXPECT_EQ(surface->GetOutput()->GetFieldData()->GetArray(vtkMesoArrayNames::Area), nullptr);
  EXPECT_EQ(surface->GetOutput()->GetFieldData()->GetArray(vtkMesoArrayNames::Volume), nullptr);
  EXPECT_EQ(field(surface->GetOutput(), vtkMesoArrayNames::ComponentCount), 1);
}

TEST(vtkMesoMolecularSurface, AccessibleAreaMatchesTheSurfaceAreaFilter)
{
  vtkNew<vtkMesoStructureReader> reader;
  reader->SetFileName(mesolens_test::data_file("proteins/1crn.pdb").c_str());
  vtkNew<vtkMesoMolecularSurface> surface;
  surface->SetInputConnection(reader->GetOutputPort());
  surface->SetSurfaceTypeToSolventAccessible();
  surface->SetTolerance(0.3);
  vtkNew<vtkMesoSurfaceArea> area;
  area->SetInputConnection(reader->GetOutputPort());
  surface->Update();
  area->Update();
  EXPECT_NEAR(field(surface->GetOutput(), vtkMesoArrayNames::Area),
              field(area->GetOutput(), vtkMesoArrayNames::TotalArea), 1e-6);
  EXPECT_NEAR(field(surface->GetOutput(), vtkMesoArrayNames::Volume),
              field(area->GetOutput(), vtkMesoArrayNames::Volume), 1e-6);
}

TEST(vtkMesoMolecularSurface, BadInputsGiveAnErrorAndNoSurface)
{
  vtkNew<vtkMesoMolecularSurface> surface;
  mesolens_test::EventRecorder events(surface);
  const auto fails = [&](vtkPolyData* input, const char* expected) {
    events.Clear();
    surface->SetInputData(input);
    surface->Update();
    EXPECT_FALSE(events.Errors.empty());
    EXPECT_NE(events.AllErrors().find(expected), std::string::npos) << events.AllErrors();
    EXPECT_EQ(surface->GetOutput()->GetNumberOfPoints(), 0);
  };
  vtkNew<vtkPolyData> empty;
  fails(empty, "No atoms");
  surface->SetRadiusArrayName("Radius");
  auto nan_position = spheres({ { std::nan(""), 0, 0, 1.5 } });
  fails(nan_position, "non-finite");
  auto huge = spheres({ { 0, 0, 0, 1e6 } });
  fails(huge, "radius");
  auto zero = spheres({ { 0, 0, 0, 0.0 } });
  fails(zero, "radius");
  surface->SetRadiusArrayName("Missing");
  auto fine = spheres({ { 0, 0, 0, 1.5 } });
  fails(fine, "no point array `Missing`");
  // Setters clamp out-of-range parameters.
  surface->SetProbeRadius(-1);
  EXPECT_GT(surface->GetProbeRadius(), 0);
  surface->SetTolerance(100);
  EXPECT_LE(surface->GetTolerance(), 1.0);
}
