// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoArrayNames.h"
#include "vtkMesoStructureReader.h"

#include "mesolens_test_data.h"
#include "mesolens_vtk_test_utilities.h"

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkStringArray.h>

#include <gtest/gtest.h>

#include <sstream>

using mesolens_test::data_file;

TEST(vtkMesoStructureReader, ArraysOfOneAtomPerVertex)
{
  vtkNew<vtkMesoStructureReader> reader;
  reader->SetFileName(data_file("proteins/1crn.pdb").c_str());
  ASSERT_EQ(reader->GetExecutive()->Update(), 1);
  vtkPolyData* atoms = reader->GetOutput();
  EXPECT_EQ(atoms->GetNumberOfPoints(), 327);
  EXPECT_EQ(atoms->GetNumberOfVerts(), 327);
  EXPECT_EQ(atoms->GetNumberOfLines(), 337);
  vtkPointData* pd = atoms->GetPointData();
  for (const char* name :
       { vtkMesoArrayNames::AtomicNumber, vtkMesoArrayNames::ResidueNumber,
         vtkMesoArrayNames::SerialNumber, vtkMesoArrayNames::ResidueIndex,
         vtkMesoArrayNames::MoleculeId, vtkMesoArrayNames::SecondaryStructure,
         vtkMesoArrayNames::SecondaryStructureId, vtkMesoArrayNames::Occupancy,
         vtkMesoArrayNames::BFactor, vtkMesoArrayNames::IsHetAtm, vtkMesoArrayNames::FormalCharge })
  {
    ASSERT_NE(pd->GetArray(name), nullptr) << name;
    EXPECT_EQ(pd->GetArray(name)->GetNumberOfTuples(), 327) << name;
  }
  for (const char* name :
       { vtkMesoArrayNames::AtomName, vtkMesoArrayNames::Element, vtkMesoArrayNames::ResidueName,
         vtkMesoArrayNames::ChainId, vtkMesoArrayNames::InsertionCode, vtkMesoArrayNames::AltLoc })
  {
    auto* strings = vtkStringArray::SafeDownCast(pd->GetAbstractArray(name));
    ASSERT_NE(strings, nullptr) << name;
    EXPECT_EQ(strings->GetNumberOfValues(), 327) << name;
  }
  auto* names = vtkStringArray::SafeDownCast(pd->GetAbstractArray(vtkMesoArrayNames::AtomName));
  auto* elements = vtkStringArray::SafeDownCast(pd->GetAbstractArray(vtkMesoArrayNames::Element));
  EXPECT_EQ(names->GetValue(1), "CA");
  EXPECT_EQ(elements->GetValue(1), "C");
  EXPECT_EQ(pd->GetArray(vtkMesoArrayNames::AtomicNumber)->GetTuple1(0), 7.0);
  EXPECT_EQ(pd->GetScalars(), pd->GetArray(vtkMesoArrayNames::AtomicNumber));
  double bounds[6];
  atoms->GetBounds(bounds);
  EXPECT_LT(bounds[0], bounds[1]);
  auto* box = atoms->GetFieldData()->GetArray(vtkMesoArrayNames::PeriodicBoxVectors);
  ASSERT_NE(box, nullptr);
  EXPECT_NEAR(box->GetComponent(0, 0), 40.96, 1e-3); // CRYST1 a
  std::ostringstream print;
  reader->Print(print);
  EXPECT_NE(print.str().find("BondTolerance: 0.45"), std::string::npos);
}

TEST(vtkMesoStructureReader, ModelsAreTimeSteps)
{
  vtkNew<vtkMesoStructureReader> reader;
  reader->SetFileName(data_file("proteins/1l2y.pdb").c_str());
  reader->UpdateInformation();
  vtkInformation* info = reader->GetOutputInformation(0);
  ASSERT_TRUE(info->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()));
  EXPECT_EQ(info->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS()), 38);
  EXPECT_EQ(reader->GetNumberOfModels(), 38);
  reader->UpdateTimeStep(0);
  double first[3];
  reader->GetOutput()->GetPoint(0, first);
  reader->UpdateTimeStep(12.4); // nearest model: 12
  EXPECT_EQ(
    reader->GetOutput()->GetFieldData()->GetArray(vtkMesoArrayNames::ModelIndex)->GetTuple1(0),
    12.0);
  double twelfth[3];
  reader->GetOutput()->GetPoint(0, twelfth);
  EXPECT_NE(first[0], twelfth[0]);
  reader->UpdateTimeStep(1000); // clamped to the last model
  EXPECT_EQ(
    reader->GetOutput()->GetFieldData()->GetArray(vtkMesoArrayNames::ModelIndex)->GetTuple1(0),
    37.0);
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 304);
}

TEST(vtkMesoStructureReader, OptionsChangeTheOutput)
{
  vtkNew<vtkMesoStructureReader> reader;
  reader->SetFileName(data_file("proteins/3o5r.pdb").c_str());
  reader->Update();
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 1326);
  reader->KeepAllAlternateLocationsOn();
  reader->Update();
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 1470);
  reader->KeepAllAlternateLocationsOff();
  reader->RemoveWatersOn();
  reader->Update();
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 1039); // gemmi: one conformer, no water
  reader->SetFileName(data_file("proteins/1crn.pdb").c_str());
  reader->PerceiveBondsOff();
  reader->Update();
  EXPECT_EQ(reader->GetOutput()->GetNumberOfLines(), 3); // CONECT disulfides only
  reader->SetBondTolerance(7.0);
  EXPECT_EQ(reader->GetBondTolerance(), 1.0);
}

// GROMACS writes residue numbers modulo 10000 and serials modulo 100000; the arrays have the
// true ones (Data/README.md: 280 atoms numbered 99811.., residues 9990..10040).
TEST(vtkMesoStructureReader, GromacsNumbersReachTheArrays)
{
  vtkNew<vtkMesoStructureReader> reader;
  reader->SetFileName(data_file("proteins/awkward/gromacs_wrapped_numbers.pdb").c_str());
  ASSERT_EQ(reader->GetExecutive()->Update(), 1);
  vtkPointData* pd = reader->GetOutput()->GetPointData();
  ASSERT_EQ(reader->GetOutput()->GetNumberOfPoints(), 280);
  EXPECT_EQ(pd->GetArray(vtkMesoArrayNames::SerialNumber)->GetTuple1(189), 100000.0);
  EXPECT_EQ(pd->GetArray(vtkMesoArrayNames::SerialNumber)->GetTuple1(279), 100090.0);
  EXPECT_EQ(pd->GetArray(vtkMesoArrayNames::ResidueNumber)->GetTuple1(157), 10000.0);
  EXPECT_EQ(pd->GetArray(vtkMesoArrayNames::ResidueNumber)->GetTuple1(279), 10040.0);
  auto* residue_names =
    vtkStringArray::SafeDownCast(pd->GetAbstractArray(vtkMesoArrayNames::ResidueName));
  EXPECT_EQ(residue_names->GetValue(0), "DPPC");
  EXPECT_EQ(residue_names->GetValue(279), "SOL");
  EXPECT_NE(std::string(reader->GetWarnings()).find("restart after 9999 "), std::string::npos);
}

TEST(vtkMesoStructureReader, CanReadFile)
{
  EXPECT_EQ(vtkMesoStructureReader::CanReadFile(data_file("proteins/1crn.pdb").c_str()), 1);
  EXPECT_EQ(vtkMesoStructureReader::CanReadFile(data_file("proteins/1crn.cif").c_str()), 1);
  EXPECT_EQ(
    vtkMesoStructureReader::CanReadFile(data_file("meshes/hipsc_cell_membrane_1.obj").c_str()), 0);
  EXPECT_EQ(vtkMesoStructureReader::CanReadFile(nullptr), 0);
}

// Each bad input: an error naming the file and the problem, an empty output, a failed update.
TEST(vtkMesoStructureReader, BadInputsFailCleanly)
{
  const std::string text = mesolens_test::read_bytes(data_file("proteins/1crn.pdb"));
  std::string nan_text = text;
  const std::size_t atom = nan_text.find("\nATOM      5");
  nan_text.replace(atom + 1 + 30, 8, "     nan");
  const struct
  {
    std::string path;
    const char* problem;
  } cases[] = {
    { mesolens_test::output_file("no_such_file.pdb"), "no such file" },
    { mesolens_test::write_bytes("reader_empty.pdb", ""), "empty" },
    { mesolens_test::write_bytes("reader_truncated.pdb",
                                 text.substr(0, text.find("ATOM    100") + 40)),
      "truncated" },
    { mesolens_test::garbage_file("reader_garbage.pdb"), "binary data" },
    { mesolens_test::write_bytes("reader_nan.pdb", nan_text), "non-finite" },
    // A record shifted right by a six-digit serial, with a garbled x coordinate.
    { mesolens_test::write_bytes("reader_garbled_shift.pdb",
                                 "ATOM  100000  N   GLY C10000      11.1x4   6.012  -3.456  1.00  "
                                 "0.00           N\n"),
      "not a number" },
  };
  for (const auto& c : cases)
  {
    SCOPED_TRACE(c.path);
    vtkNew<vtkMesoStructureReader> reader;
    // A previous good result must not survive a failed update.
    reader->SetFileName(data_file("proteins/1crn.pdb").c_str());
    reader->Update();
    ASSERT_EQ(reader->GetOutput()->GetNumberOfPoints(), 327);
    mesolens_test::EventRecorder events(reader);
    reader->SetFileName(c.path.c_str());
    EXPECT_EQ(reader->GetExecutive()->Update(), 0);
    EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 0);
    ASSERT_FALSE(events.Errors.empty());
    EXPECT_NE(events.AllErrors().find(c.path), std::string::npos) << events.AllErrors();
    EXPECT_NE(events.AllErrors().find(c.problem), std::string::npos) << events.AllErrors();
  }
  vtkNew<vtkMesoStructureReader> unset;
  mesolens_test::EventRecorder events(unset);
  EXPECT_EQ(unset->GetExecutive()->Update(), 0);
  EXPECT_NE(events.AllErrors().find("FileName"), std::string::npos);
}
