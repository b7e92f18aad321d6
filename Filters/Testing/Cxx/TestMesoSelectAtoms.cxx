// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoArrayNames.h"
#include "vtkMesoSelectAtoms.h"
#include "vtkMesoStructureReader.h"
#include "vtkMesoTrajectoryReader.h"

#include "mesolens_test_data.h"
#include "mesolens_vtk_test_utilities.h"

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSphereSource.h>
#include <vtkStringArray.h>

#include <gtest/gtest.h>

#include <set>

namespace {
using mesolens_test::data_file;

vtkIdType SelectedCount(vtkPolyData* atoms, const char* mask = "Selected")
{
  vtkDataArray* array = atoms->GetPointData()->GetArray(mask);
  EXPECT_NE(array, nullptr);
  vtkIdType count = 0;
  for (vtkIdType i = 0; array && i < array->GetNumberOfTuples(); ++i)
  {
    count += array->GetTuple1(i) != 0.0 ? 1 : 0;
  }
  return count;
}

vtkIdType Count(vtkAlgorithm* source, const char* selection)
{
  vtkNew<vtkMesoSelectAtoms> select;
  select->SetInputConnection(source->GetOutputPort());
  select->SetSelection(selection);
  select->Update();
  return SelectedCount(select->GetOutput());
}
} // namespace

TEST(vtkMesoSelectAtoms, MaskMarksTheSelectedAtoms)
{
  vtkNew<vtkMesoStructureReader> reader;
  reader->SetFileName(data_file("proteins/1crn.pdb").c_str());
  vtkNew<vtkMesoSelectAtoms> select;
  select->SetInputConnection(reader->GetOutputPort());
  EXPECT_STREQ(select->GetSelection(), "all");
  select->SetSelection("name CA");
  select->Update();
  vtkPolyData* out = select->GetOutput();
  EXPECT_EQ(out->GetNumberOfPoints(), 327);
  EXPECT_EQ(out->GetNumberOfLines(), reader->GetOutput()->GetNumberOfLines());
  EXPECT_EQ(SelectedCount(out), 46); // one CA per residue
  EXPECT_EQ(Count(reader, "backbone"), 4 * 46);
  EXPECT_EQ(Count(reader, "resid 1-10 and not hydrogen"), 70);
  // Cys 3 and Cys 40 make a disulfide: their sulfurs are 2.0 Å apart.
  EXPECT_EQ(Count(reader, "same residue as (name SG and within 2.1 of (name SG and resid 3))"),
            2 * 6);
  // B-factors: the built-in field and the point array of the same values agree.
  EXPECT_EQ(Count(reader, "beta > 10"), Count(reader, "BFactor > 10"));
  EXPECT_GT(Count(reader, "beta > 10"), 0);
  select->SetMaskArrayName("Cysteines");
  select->SetSelection("resname CYS");
  select->Update();
  EXPECT_EQ(SelectedCount(select->GetOutput(), "Cysteines"), 6 * 6);
}

TEST(vtkMesoSelectAtoms, ExtractKeepsTheAtomsArraysAndBondsBetweenThem)
{
  vtkNew<vtkMesoStructureReader> reader;
  reader->SetFileName(data_file("proteins/1crn.pdb").c_str());
  vtkNew<vtkMesoSelectAtoms> select;
  select->SetInputConnection(reader->GetOutputPort());
  select->SetSelection("resid 3-4");
  select->SetOutputModeToExtract();
  select->Update();
  vtkPolyData* out = select->GetOutput();
  // Residues 3 and 4, two cysteines of 6 atoms.
  ASSERT_EQ(out->GetNumberOfPoints(), 12);
  EXPECT_EQ(out->GetNumberOfVerts(), 12);
  // 5 + 5 bonds inside the residues and the peptide bond between them (their disulfides leave).
  EXPECT_EQ(out->GetNumberOfLines(), 11);
  auto* names = vtkStringArray::SafeDownCast(
    out->GetPointData()->GetAbstractArray(vtkMesoArrayNames::AtomName));
  auto* residues = out->GetPointData()->GetArray(vtkMesoArrayNames::ResidueNumber);
  ASSERT_NE(names, nullptr);
  ASSERT_NE(residues, nullptr);
  EXPECT_EQ(names->GetValue(0), "N");
  EXPECT_EQ(residues->GetTuple1(0), 3.0);
  EXPECT_EQ(residues->GetTuple1(11), 4.0);
  // The extracted atoms sit where they were.
  vtkPolyData* in = reader->GetOutput();
  vtkIdType first = 0;
  while (in->GetPointData()->GetArray(vtkMesoArrayNames::ResidueNumber)->GetTuple1(first) != 3.0)
  {
    ++first;
  }
  for (int d = 0; d < 3; ++d)
  {
    EXPECT_EQ(out->GetPoint(0)[d], in->GetPoint(first)[d]);
  }
  // Every bond joins two extracted atoms.
  vtkNew<vtkIdList> line;
  vtkCellArray* lines = out->GetLines();
  for (lines->InitTraversal(); lines->GetNextCell(line);)
  {
    ASSERT_EQ(line->GetNumberOfIds(), 2);
    EXPECT_LT(line->GetId(0), 12);
    EXPECT_LT(line->GetId(1), 12);
  }
  select->SetSelection("none");
  select->Update();
  EXPECT_EQ(select->GetOutput()->GetNumberOfPoints(), 0);
}

TEST(vtkMesoSelectAtoms, EveryTimeStepIsSelectedAtItsOwnPositions)
{
  vtkNew<vtkMesoTrajectoryReader> reader;
  reader->SetTopologyFileName(data_file("membranes/martini_dppc_vesicle.gro").c_str());
  reader->SetTrajectoryFileName(data_file("membranes/martini_dppc_vesicle.xtc").c_str());
  vtkNew<vtkMesoSelectAtoms> select;
  select->SetInputConnection(reader->GetOutputPort());
  select->SetSelection("name PO4 and x < 150");
  std::set<vtkIdType> counts;
  for (double time : { 0.0, 1e9 })
  {
    select->UpdateTimeStep(time);
    vtkPolyData* atoms = reader->GetOutput();
    auto* names = vtkStringArray::SafeDownCast(
      atoms->GetPointData()->GetAbstractArray(vtkMesoArrayNames::AtomName));
    vtkIdType expected = 0;
    for (vtkIdType i = 0; i < atoms->GetNumberOfPoints(); ++i)
    {
      expected += names->GetValue(i) == "PO4" && atoms->GetPoint(i)[0] < 150.0 ? 1 : 0;
    }
    EXPECT_EQ(SelectedCount(select->GetOutput()), expected);
    counts.insert(expected);
  }
  EXPECT_EQ(counts.size(), 2u); // the lipids moved between the frames
}

TEST(vtkMesoSelectAtoms, LipidsAndSterolsOfAMembrane)
{
  vtkNew<vtkMesoTrajectoryReader> reader;
  reader->SetTopologyFileName(data_file("membranes/martini_dppc_chol_bilayer.gro").c_str());
  EXPECT_EQ(Count(reader, "lipid and name PO4"), 360);
  EXPECT_EQ(Count(reader, "resname CHOL"), 5040 - 360 * 12);
  EXPECT_EQ(Count(reader, "lipid"), 5040);
  EXPECT_EQ(Count(reader, "same residue as name ROH"), 5040 - 360 * 12);
}

TEST(vtkMesoSelectAtoms, LengthScaleConvertsTheInputUnits)
{
  vtkNew<vtkMesoStructureReader> reader;
  reader->SetFileName(data_file("proteins/1crn.pdb").c_str());
  reader->Update();
  vtkNew<vtkPolyData> nanometres; // the atoms in nm
  nanometres->DeepCopy(reader->GetOutput());
  for (vtkIdType i = 0; i < nanometres->GetNumberOfPoints(); ++i)
  {
    double p[3];
    nanometres->GetPoint(i, p);
    nanometres->GetPoints()->SetPoint(i, 0.1 * p[0], 0.1 * p[1], 0.1 * p[2]);
  }
  vtkNew<vtkMesoSelectAtoms> select;
  select->SetInputData(nanometres);
  select->SetSelection("within 5 of resid 1");
  select->Update();
  const vtkIdType read_as_angstrom = SelectedCount(select->GetOutput());
  select->SetLengthScale(0.1);
  select->Update();
  EXPECT_EQ(SelectedCount(select->GetOutput()), Count(reader, "within 5 of resid 1"));
  EXPECT_GT(read_as_angstrom, SelectedCount(select->GetOutput())); // 10 times closer as Å
}

TEST(vtkMesoSelectAtoms, BadSelectionsAndInputsGiveAnErrorAndAnEmptyOutput)
{
  vtkNew<vtkMesoStructureReader> reader;
  reader->SetFileName(data_file("proteins/1crn.pdb").c_str());
  vtkNew<vtkMesoSelectAtoms> select;
  select->SetInputConnection(reader->GetOutputPort());
  mesolens_test::EventRecorder events(select);
  const std::pair<const char*, const char*> bad[] = {
    { "name CA and (resid 5", "missing ')' at character 21" },
    { "resname", "'resname' needs at least one value at character 8" },
    { "nmae CA", "unknown keyword 'nmae' at character 1" },
    { "charge2 > 0", "'charge2' is neither a keyword nor a per-atom array at character 1" },
    { "AtomName > 0", "'AtomName' is neither a keyword nor a per-atom array" },
  };
  for (const auto& [selection, message] : bad)
  {
    events.Clear();
    select->SetSelection(selection);
    EXPECT_EQ(select->GetExecutive()->Update(), 0) << selection;
    EXPECT_EQ(select->GetOutput()->GetNumberOfPoints(), 0) << selection;
    EXPECT_NE(events.AllErrors().find(message), std::string::npos) << events.AllErrors();
  }
  events.Clear();
  select->SetSelection("all");
  select->SetMaskArrayName("");
  EXPECT_EQ(select->GetExecutive()->Update(), 0);
  EXPECT_NE(events.AllErrors().find("MaskArrayName"), std::string::npos);

  vtkNew<vtkSphereSource> sphere;
  vtkNew<vtkMesoSelectAtoms> not_atoms;
  not_atoms->SetInputConnection(sphere->GetOutputPort());
  mesolens_test::EventRecorder sphere_events(not_atoms);
  EXPECT_EQ(not_atoms->GetExecutive()->Update(), 0);
  EXPECT_EQ(not_atoms->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_NE(sphere_events.AllErrors().find("AtomName"), std::string::npos);
}
