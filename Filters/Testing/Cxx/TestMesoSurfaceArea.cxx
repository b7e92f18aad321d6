// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoArrayNames.h"
#include "vtkMesoSurfaceArea.h"

#include "mesolens_test_data.h"
#include "mesolens_vtk_test_utilities.h"
#include "vtkMesoStructureReader.h"

#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <cmath>

namespace {
constexpr double pi = 3.14159265358979323846;

double field(vtkPolyData* data, const char* name)
{
  return data->GetFieldData()->GetArray(name)->GetTuple1(0);
}
} // namespace

TEST(vtkMesoSurfaceArea, TwoAtomsExactlyAndTheProbe)
{
  // Two atoms with given radii 1.5 and 1.2, 2 Å apart: exact areas and volume.
  vtkNew<vtkPolyData> atoms;
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  points->InsertNextPoint(2, 0, 0);
  atoms->SetPoints(points);
  vtkNew<vtkDoubleArray> radius;
  radius->SetName("Radius");
  radius->InsertNextValue(1.5);
  radius->InsertNextValue(1.2);
  atoms->GetPointData()->AddArray(radius);
  vtkNew<vtkMesoSurfaceArea> area;
  area->SetInputData(atoms);
  area->SetRadiusArrayName("Radius");
  area->SetProbeRadius(0.0);
  area->Update();
  const double r1 = 1.5, r2 = 1.2, d = 2.0;
  const double h1 = (r1 * r1 + d * d - r2 * r2) / (2 * r1 * d);
  const double h2 = (r2 * r2 + d * d - r1 * r1) / (2 * r2 * d);
  vtkDataArray* per_atom =
    area->GetOutput()->GetPointData()->GetArray(vtkMesoArrayNames::AccessibleArea);
  EXPECT_NEAR(per_atom->GetTuple1(0), 2 * pi * r1 * r1 * (1 + h1), 1e-4);
  EXPECT_NEAR(per_atom->GetTuple1(1), 2 * pi * r2 * r2 * (1 + h2), 1e-4);
  const double lens = pi * std::pow(r1 + r2 - d, 2) *
    (d * d + 2 * d * (r1 + r2) - 3 * (r1 - r2) * (r1 - r2)) / (12 * d);
  EXPECT_NEAR(field(area->GetOutput(), vtkMesoArrayNames::Volume),
              4.0 / 3.0 * pi * (r1 * r1 * r1 + r2 * r2 * r2) - lens, 1e-9);
  // With the probe, the spheres grow by 1.4 Å: more area in all.
  area->SetProbeRadius(1.4);
  area->Update();
  EXPECT_GT(field(area->GetOutput(), vtkMesoArrayNames::TotalArea), 4 * pi * 2.9 * 2.9);
}

TEST(vtkMesoSurfaceArea, CrambinFromElementRadii)
{
  vtkNew<vtkMesoStructureReader> reader;
  reader->SetFileName(mesolens_test::data_file("proteins/1crn.pdb").c_str());
  vtkNew<vtkMesoSurfaceArea> area;
  area->SetInputConnection(reader->GetOutputPort());
  mesolens_test::EventRecorder events(area);
  area->Update();
  ASSERT_TRUE(events.Errors.empty()) << events.AllErrors();
  const double sas = field(area->GetOutput(), vtkMesoArrayNames::TotalArea);
  // FreeSASA's ProtOr radii give 2999 Å²; Bondi's element radii are a little larger.
  EXPECT_GT(sas, 2800.0);
  EXPECT_LT(sas, 3300.0);
  vtkDataArray* per_atom =
    area->GetOutput()->GetPointData()->GetArray(vtkMesoArrayNames::AccessibleArea);
  double sum = 0;
  int buried = 0;
  for (vtkIdType a = 0; a < per_atom->GetNumberOfTuples(); ++a)
  {
    sum += per_atom->GetTuple1(a);
    buried += per_atom->GetTuple1(a) == 0.0;
  }
  EXPECT_NEAR(sum, sas, 1e-2 * sas);
  EXPECT_GT(buried, 50); // crambin has a core
  // Without the probe (the van der Waals surface) the enclosed volume is smaller.
  const double sas_volume = field(area->GetOutput(), vtkMesoArrayNames::Volume);
  area->SetProbeRadius(0.0);
  area->Update();
  EXPECT_LT(field(area->GetOutput(), vtkMesoArrayNames::Volume), sas_volume);
}

TEST(vtkMesoSurfaceArea, BadInputs)
{
  vtkNew<vtkMesoSurfaceArea> area;
  mesolens_test::EventRecorder events(area);
  vtkNew<vtkPolyData> empty;
  area->SetInputData(empty);
  area->Update();
  EXPECT_FALSE(events.Errors.empty());
  events.Errors.clear();
  vtkNew<vtkPolyData> atoms;
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  points->InsertNextPoint(std::nan(""), 0, 0);
  atoms->SetPoints(points);
  area->SetInputData(atoms);
  area->Update();
  EXPECT_NE(events.AllErrors().find("non-finite"), std::string::npos);
  EXPECT_EQ(area->GetOutput()->GetNumberOfPoints(), 0);
  events.Errors.clear();
  points->SetPoint(1, 1, 0, 0);
  points->Modified();
  area->SetRadiusArrayName("Missing");
  area->Update();
  EXPECT_NE(events.AllErrors().find("Missing"), std::string::npos);
  events.Errors.clear();
  vtkNew<vtkFloatArray> radius;
  radius->SetName("Radius");
  radius->InsertNextValue(1.0);
  radius->InsertNextValue(-3.0);
  atoms->GetPointData()->AddArray(radius);
  area->SetRadiusArrayName("Radius");
  area->SetProbeRadius(0.0);
  area->Update();
  EXPECT_FALSE(events.Errors.empty());
  EXPECT_EQ(area->GetOutput()->GetNumberOfPoints(), 0);
}
