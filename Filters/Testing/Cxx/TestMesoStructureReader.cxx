// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoArrayNames.h"
#include "vtkMesoAssemblyInstances.h"
#include "vtkMesoStructureReader.h"

#include "mesolens_test_data.h"
#include "mesolens_vtk_test_utilities.h"

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkIdTypeArray.h>
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

namespace {
/// Crambin with a REMARK 350 assembly of three copies, the second and third shifted by 100 Å
/// and 200 Å along x.
std::string CrambinTrimer()
{
  std::string remarks = "REMARK 350 BIOMOLECULE: 1\n"
                        "REMARK 350 APPLY THE FOLLOWING TO CHAINS: A\n";
  for (int copy = 1; copy <= 3; ++copy)
  {
    char line[256];
    const double shift = 100.0 * (copy - 1);
    std::snprintf(line, sizeof line,
                  "REMARK 350   BIOMT1 %3d  1.000000  0.000000  0.000000 %14.5f\n"
                  "REMARK 350   BIOMT2 %3d  0.000000  1.000000  0.000000 %14.5f\n"
                  "REMARK 350   BIOMT3 %3d  0.000000  0.000000  1.000000 %14.5f\n",
                  copy, shift, copy, 0.0, copy, 0.0);
    remarks += line;
  }
  // The file's own REMARK 350 (a monomer) is left out.
  std::istringstream crambin(mesolens_test::read_bytes(data_file("proteins/1crn.pdb")));
  std::string records;
  for (std::string record; std::getline(crambin, record);)
  {
    if (record.rfind("REMARK 350", 0) != 0)
    {
      records += record + "\n";
    }
  }
  return mesolens_test::write_bytes("crambin_trimer.pdb", remarks + records);
}
}

TEST(vtkMesoStructureReader, AnAssemblyGivesEveryCopyWithItsIndex)
{
  vtkNew<vtkMesoStructureReader> reader;
  reader->SetFileName(CrambinTrimer().c_str());
  ASSERT_EQ(reader->GetNumberOfAssemblies(), 1);
  EXPECT_STREQ(reader->GetAssemblyName(0), "1");
  EXPECT_EQ(reader->GetAssemblyCopyCount(0), 3);
  EXPECT_EQ(reader->GetAssemblyAtomCount(0), 3 * 327);
  EXPECT_STREQ(reader->GetAssemblyName(1), "");
  reader->Update();
  const vtkIdType lines = reader->GetOutput()->GetNumberOfLines();
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 327);
  EXPECT_EQ(reader->GetOutput()->GetPointData()->GetArray(vtkMesoArrayNames::AssemblyCopy),
            nullptr);

  reader->SetAssembly("1");
  ASSERT_EQ(reader->GetExecutive()->Update(), 1);
  vtkPolyData* atoms = reader->GetOutput();
  ASSERT_EQ(atoms->GetNumberOfPoints(), 3 * 327);
  EXPECT_EQ(atoms->GetNumberOfVerts(), 3 * 327);
  EXPECT_EQ(atoms->GetNumberOfLines(), 3 * lines);
  vtkDataArray* copies = atoms->GetPointData()->GetArray(vtkMesoArrayNames::AssemblyCopy);
  ASSERT_NE(copies, nullptr);
  auto* chains = vtkStringArray::SafeDownCast(
    atoms->GetPointData()->GetAbstractArray(vtkMesoArrayNames::ChainId));
  for (vtkIdType copy = 0; copy < 3; ++copy)
  {
    const vtkIdType first = copy * 327;
    EXPECT_EQ(copies->GetTuple1(first), double(copy));
    EXPECT_EQ(copies->GetTuple1(first + 326), double(copy));
    EXPECT_EQ(chains->GetValue(first), copy == 0 ? "A" : "A-" + std::to_string(copy + 1));
    EXPECT_NEAR(atoms->GetPoint(first)[0], atoms->GetPoint(0)[0] + 100.0 * copy, 1e-3);
    EXPECT_NEAR(atoms->GetPoint(first + 5)[2], atoms->GetPoint(5)[2], 1e-4);
  }
  EXPECT_EQ(atoms->GetFieldData()->GetArray(vtkMesoArrayNames::PeriodicBoxVectors), nullptr);

  // Back to the asymmetric unit.
  reader->SetAssembly("");
  reader->Update();
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 327);
}

TEST(vtkMesoStructureReader, BadAssembliesFailCleanly)
{
  vtkNew<vtkMesoStructureReader> reader;
  reader->SetFileName(CrambinTrimer().c_str());
  mesolens_test::EventRecorder events(reader);
  reader->SetAssembly("7");
  EXPECT_EQ(reader->GetExecutive()->Update(), 0);
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_NE(events.AllErrors().find("no assembly '7' (it defines '1')"), std::string::npos)
    << events.AllErrors();
  events.Clear();
  reader->SetAssembly("1");
  reader->SetMaximumAssemblyAtoms(500);
  EXPECT_EQ(reader->GetExecutive()->Update(), 0);
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_NE(events.AllErrors().find("981"), std::string::npos) << events.AllErrors();
  EXPECT_NE(events.AllErrors().find("500"), std::string::npos) << events.AllErrors();
  events.Clear();
  vtkNew<vtkMesoStructureReader> none;
  mesolens_test::EventRecorder none_events(none);
  none->SetFileName(data_file("proteins/1crn.cif").c_str());
  EXPECT_EQ(none->GetNumberOfAssemblies(), 1);
  none->SetAssembly("PAU");
  EXPECT_EQ(none->GetExecutive()->Update(), 0);
  EXPECT_NE(none_events.AllErrors().find("it defines '1'"), std::string::npos)
    << none_events.AllErrors();
}

TEST(vtkMesoStructureReader, PhiX174VirionHasSixtyCopies)
{
  const std::string path = mesolens_test::shared_file("proteins/1rb8.pdb");
  if (!mesolens_test::exists(path))
  {
    GTEST_SKIP() << "needs ../shared/data";
  }
  vtkNew<vtkMesoStructureReader> reader;
  reader->SetFileName(path.c_str());
  reader->SetAssembly("1");
  ASSERT_EQ(reader->GetExecutive()->Update(), 1);
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 306720); // gemmi's make_assembly
  EXPECT_EQ(
    reader->GetOutput()->GetPointData()->GetArray(vtkMesoArrayNames::AssemblyCopy)->GetRange()[1],
    59.0);
}

TEST(vtkMesoStructureReader, AssemblyCopiesAsInstances)
{
  vtkNew<vtkMesoStructureReader> reader;
  reader->SetFileName(CrambinTrimer().c_str());
  reader->Update();
  EXPECT_EQ(reader->GetOutput(1)->GetNumberOfPoints(), 0); // no assembly chosen
  reader->SetAssembly("1");
  reader->ExpandAssemblyOff();
  ASSERT_EQ(reader->GetExecutive()->Update(), 1);
  EXPECT_EQ(reader->GetOutput(0)->GetNumberOfPoints(), 327);
  EXPECT_EQ(reader->GetOutput(0)->GetPointData()->GetArray(vtkMesoArrayNames::AssemblyCopy),
            nullptr);
  vtkPolyData* copies = reader->GetOutput(1);
  ASSERT_EQ(copies->GetNumberOfPoints(), 3);
  EXPECT_EQ(copies->GetNumberOfVerts(), 3);
  vtkDataArray* orientation =
    copies->GetPointData()->GetArray(vtkMesoArrayNames::AssemblyOrientation);
  ASSERT_NE(orientation, nullptr);
  for (vtkIdType c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(copies->GetPoint(c)[0], 100.0 * c, 1e-9);
    EXPECT_NEAR(orientation->GetComponent(c, 0), 1.0, 1e-12);
  }
  mesolens::AssemblyInstances read;
  ASSERT_TRUE(vtkMesoAssemblyInstances::Read(copies, read));
  ASSERT_EQ(read.instances.size(), 3u);
  ASSERT_EQ(read.atom_sets.size(), 1u);
  EXPECT_TRUE(read.atom_sets[0].whole_table);
  EXPECT_EQ(read.atom_sets[0].atoms.size(), 327u);
  EXPECT_EQ(read.instances[2].matrix[3], 200.0);
  EXPECT_GT(read.instances[1].radius, 10.0);
  // Expanded, output 1 still holds the copies.
  reader->ExpandAssemblyOn();
  reader->Update();
  EXPECT_EQ(reader->GetOutput(0)->GetNumberOfPoints(), 3 * 327);
  EXPECT_EQ(reader->GetOutput(1)->GetNumberOfPoints(), 3);
  // Not the reader's copies: refused.
  vtkNew<vtkPolyData> other;
  EXPECT_FALSE(vtkMesoAssemblyInstances::Read(other, read));
  EXPECT_FALSE(vtkMesoAssemblyInstances::Read(nullptr, read));
  // Atom-set offsets past the atoms they index (a damaged or hand-made copy list): refused,
  // not read out of bounds.
  vtkNew<vtkPolyData> damaged;
  damaged->DeepCopy(copies);
  vtkIdTypeArray* offsets = vtkIdTypeArray::SafeDownCast(
    damaged->GetFieldData()->GetArray(vtkMesoArrayNames::AssemblyAtomSetOffsets));
  ASSERT_NE(offsets, nullptr);
  vtkDataArray* whole = damaged->GetFieldData()->GetArray(vtkMesoArrayNames::AssemblyAtomSetWhole);
  ASSERT_NE(whole, nullptr);
  ASSERT_EQ(offsets->GetNumberOfTuples(), 2);
  // Two sets, the first of rows 0..399 of the 327 listed.
  offsets->SetValue(1, 400);
  offsets->InsertNextValue(327);
  whole->InsertNextTuple1(0);
  EXPECT_FALSE(vtkMesoAssemblyInstances::Read(damaged, read));
  offsets->SetNumberOfTuples(2);
  offsets->SetValue(1, 327);
  whole->SetNumberOfTuples(1);
  ASSERT_TRUE(vtkMesoAssemblyInstances::Read(damaged, read));
  offsets->SetValue(0, -5);
  EXPECT_FALSE(vtkMesoAssemblyInstances::Read(damaged, read));
}
