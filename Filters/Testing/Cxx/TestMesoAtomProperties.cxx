// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoArrayNames.h"
#include "vtkMesoAtomProperties.h"
#include "vtkMesoStructureReader.h"
#include "vtkMesoTrajectoryReader.h"

#include "mesolens_test_data.h"
#include "mesolens_vtk_test_utilities.h"

#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSphereSource.h>

#include <gtest/gtest.h>

TEST(vtkMesoAtomProperties, RadiiFromElements)
{
  vtkNew<vtkMesoStructureReader> reader;
  reader->SetFileName(mesolens_test::data_file("proteins/1crn.pdb").c_str());
  vtkNew<vtkMesoAtomProperties> properties;
  properties->SetInputConnection(reader->GetOutputPort());
  properties->Update();
  vtkPointData* pd = properties->GetOutput()->GetPointData();
  ASSERT_NE(pd->GetArray(vtkMesoArrayNames::VanDerWaalsRadius), nullptr);
  EXPECT_FLOAT_EQ(pd->GetArray(vtkMesoArrayNames::VanDerWaalsRadius)->GetTuple1(0), 1.55f); // N
  EXPECT_FLOAT_EQ(pd->GetArray(vtkMesoArrayNames::CovalentRadius)->GetTuple1(1), 0.73f);    // CA
  properties->SetLengthScale(0.1);
  properties->Update();
  EXPECT_NEAR(properties->GetOutput()
                ->GetPointData()
                ->GetArray(vtkMesoArrayNames::VanDerWaalsRadius)
                ->GetTuple1(0),
              0.155, 1e-6);
}

TEST(vtkMesoAtomProperties, BeadsGetBeadRadius)
{
  vtkNew<vtkMesoTrajectoryReader> reader;
  reader->SetTopologyFileName(
    mesolens_test::data_file("membranes/martini_dppc_chol_bilayer.gro").c_str());
  vtkNew<vtkMesoAtomProperties> properties;
  properties->SetInputConnection(reader->GetOutputPort());
  properties->Update();
  EXPECT_EQ(properties->GetOutput()->GetNumberOfPoints(), 5040);
  // 360 DPPC x 11 bonds + 90 CHOL x 13 (Martini cholesterol's rigid ring constraints).
  EXPECT_EQ(properties->GetOutput()->GetNumberOfLines(), 360 * 11 + 90 * 13);
  EXPECT_FLOAT_EQ(properties->GetOutput()
                    ->GetPointData()
                    ->GetArray(vtkMesoArrayNames::VanDerWaalsRadius)
                    ->GetRange()[1],
                  2.35f);
}

TEST(vtkMesoAtomProperties, InputWithoutAtomicNumbers)
{
  vtkNew<vtkSphereSource> sphere;
  vtkNew<vtkMesoAtomProperties> properties;
  properties->SetInputConnection(sphere->GetOutputPort());
  mesolens_test::EventRecorder events(properties);
  EXPECT_EQ(properties->GetExecutive()->Update(), 0);
  EXPECT_EQ(properties->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_NE(events.AllErrors().find(vtkMesoArrayNames::AtomicNumber), std::string::npos);
}
