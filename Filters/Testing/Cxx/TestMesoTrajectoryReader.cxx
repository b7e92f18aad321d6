// SPDX-License-Identifier: GPL-3.0-or-later
// Reference coordinates: MDAnalysis (Testing/Tools/reference_values.py).
#include "vtkMesoArrayNames.h"
#include "vtkMesoTrajectoryReader.h"

#include "mesolens_test_data.h"
#include "mesolens_vtk_test_utilities.h"

#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkStringArray.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

using mesolens_test::data_file;

namespace {
void expect_point(vtkPolyData* atoms, vtkIdType id, double x, double y, double z,
                  double scale = 1.0)
{
  double p[3];
  atoms->GetPoint(id, p);
  EXPECT_NEAR(p[0], x * scale, 1e-3 * scale) << id;
  EXPECT_NEAR(p[1], y * scale, 1e-3 * scale) << id;
  EXPECT_NEAR(p[2], z * scale, 1e-3 * scale) << id;
}

double field(vtkPolyData* data, const char* name)
{
  return data->GetFieldData()->GetArray(name)->GetTuple1(0);
}

/// Largest distance of an atom from the first atom of its molecule.
double largest_molecule_extent(vtkPolyData* atoms)
{
  vtkDataArray* molecules = atoms->GetPointData()->GetArray(vtkMesoArrayNames::MoleculeId);
  std::map<long, vtkIdType> first;
  double largest = 0;
  for (vtkIdType i = 0; i < atoms->GetNumberOfPoints(); ++i)
  {
    const long m = long(molecules->GetTuple1(i));
    const auto found = first.emplace(m, i).first->second;
    double a[3];
    double b[3];
    atoms->GetPoint(i, a);
    atoms->GetPoint(found, b);
    largest = std::max(largest,
                       std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                                 (a[2] - b[2]) * (a[2] - b[2])));
  }
  return largest;
}
} // namespace

TEST(vtkMesoTrajectoryReader, TimeStepsAndFrames)
{
  vtkNew<vtkMesoTrajectoryReader> reader;
  reader->SetTopologyFileName(data_file("membranes/yiip_popepopg.gro").c_str());
  reader->SetTrajectoryFileName(data_file("membranes/yiip_popepopg.xtc").c_str());
  reader->MakeMoleculesWholeOff(); // compare raw coordinates
  reader->UpdateInformation();
  vtkInformation* info = reader->GetOutputInformation(0);
  ASSERT_EQ(info->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS()), 5);
  const double* times = info->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  EXPECT_DOUBLE_EQ(times[4], 80000.0);
  EXPECT_EQ(reader->GetNumberOfFrames(), 5);
  EXPECT_EQ(reader->GetNumberOfTopologyAtoms(), 43480);

  reader->UpdateTimeStep(40000.0);
  vtkPolyData* atoms = reader->GetOutput();
  EXPECT_EQ(atoms->GetNumberOfPoints(), 43480);
  expect_point(atoms, 0, 22.75, 14.02, 56.94);
  expect_point(atoms, 1000, 10.13, 48.15, 46.31);
  EXPECT_EQ(field(atoms, vtkMesoArrayNames::FrameIndex), 2.0);
  EXPECT_DOUBLE_EQ(atoms->GetInformation()->Get(vtkDataObject::DATA_TIME_STEP()), 40000.0);
  // Between frames: the latest frame not after the time; before the first: the first.
  reader->UpdateTimeStep(79999.0);
  EXPECT_EQ(field(reader->GetOutput(), vtkMesoArrayNames::FrameIndex), 3.0);
  reader->UpdateTimeStep(-5.0);
  EXPECT_EQ(field(reader->GetOutput(), vtkMesoArrayNames::FrameIndex), 0.0);
  expect_point(reader->GetOutput(), 0, 21.27, 11.35, 62.89);
  reader->UpdateTimeStep(1e9);
  EXPECT_EQ(field(reader->GetOutput(), vtkMesoArrayNames::FrameIndex), 4.0);
  expect_point(reader->GetOutput(), 43479, -15.01, 62.42, 83.23);
  // Topology arrays and bonds are those of the .gro.
  EXPECT_GT(reader->GetOutput()->GetNumberOfLines(), 40000);
  auto* residues = vtkStringArray::SafeDownCast(
    reader->GetOutput()->GetPointData()->GetAbstractArray(vtkMesoArrayNames::ResidueName));
  ASSERT_NE(residues, nullptr);
  // Box vectors of the hexagonal cell.
  auto* box = reader->GetOutput()->GetFieldData()->GetArray(vtkMesoArrayNames::PeriodicBoxVectors);
  ASSERT_NE(box, nullptr);
  EXPECT_NEAR(box->GetComponent(0, 0), 108.905, 1e-2);
}

TEST(vtkMesoTrajectoryReader, NanometreUnits)
{
  vtkNew<vtkMesoTrajectoryReader> reader;
  reader->SetTopologyFileName(data_file("membranes/yiip_popepopg.gro").c_str());
  reader->SetTrajectoryFileName(data_file("membranes/yiip_popepopg.xtc").c_str());
  reader->MakeMoleculesWholeOff();
  reader->SetLengthUnitToNanometer();
  reader->UpdateTimeStep(40000.0);
  expect_point(reader->GetOutput(), 0, 22.75, 14.02, 56.94, 0.1);
}

TEST(vtkMesoTrajectoryReader, VesicleMoleculesAreWholeAndContinuous)
{
  vtkNew<vtkMesoTrajectoryReader> raw;
  raw->SetTopologyFileName(data_file("membranes/martini_dppc_vesicle.gro").c_str());
  raw->SetTrajectoryFileName(data_file("membranes/martini_dppc_vesicle.xtc").c_str());
  raw->MakeMoleculesWholeOff();
  raw->UpdateTimeStep(0.0);
  // 279 lipids are split by the triclinic box: some span most of the 470 Å box.
  EXPECT_GT(largest_molecule_extent(raw->GetOutput()), 200.0);

  vtkNew<vtkMesoTrajectoryReader> whole;
  whole->SetTopologyFileName(data_file("membranes/martini_dppc_vesicle.gro").c_str());
  whole->SetTrajectoryFileName(data_file("membranes/martini_dppc_vesicle.xtc").c_str());
  whole->UpdateTimeStep(0.0);
  // A DPPC Martini lipid is ~3 nm long.
  EXPECT_LT(largest_molecule_extent(whole->GetOutput()), 40.0);
  EXPECT_EQ(
    whole->GetOutput()->GetPointData()->GetArray(vtkMesoArrayNames::AtomicNumber)->GetRange()[1],
    0.0);
  // Martini DPPC: 12 beads and 11 bonds per lipid, recovered exactly by the per-type consensus.
  EXPECT_EQ(whole->GetOutput()->GetNumberOfLines(), 3072 * 11);

  // Continuity: requesting frame 10 directly, then frame 9, gives no molecule jumps between them.
  whole->UpdateTimeStep(5000.0);
  vtkNew<vtkPolyData> last;
  last->DeepCopy(whole->GetOutput());
  EXPECT_LT(largest_molecule_extent(last), 40.0);
  whole->UpdateTimeStep(4500.0);
  vtkPolyData* previous = whole->GetOutput();
  double largest_step = 0;
  for (vtkIdType i = 0; i < last->GetNumberOfPoints(); ++i)
  {
    double a[3];
    double b[3];
    last->GetPoint(i, a);
    previous->GetPoint(i, b);
    largest_step =
      std::max(largest_step, std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]));
  }
  EXPECT_LT(largest_step, 100.0); // beads move a few Å in 500 ps, never a box length
}

TEST(vtkMesoTrajectoryReader, GroOnlyAndRemoveWaters)
{
  vtkNew<vtkMesoTrajectoryReader> reader;
  reader->SetTopologyFileName(data_file("membranes/dppc128_slipids_323K.gro").c_str());
  reader->Update();
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 28160);
  EXPECT_EQ(reader->GetNumberOfFrames(), 1);
  reader->RemoveWatersOn();
  reader->Update();
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 16640); // 128 lipids x 130 atoms
  EXPECT_EQ(
    reader->GetOutput()->GetPointData()->GetArray(vtkMesoArrayNames::MoleculeId)->GetRange()[1],
    127.0);
  // Every atom of an all-atom lipid has at least one bond.
  EXPECT_GT(reader->GetOutput()->GetNumberOfLines(), 16000);
}

TEST(vtkMesoTrajectoryReader, PdbTopology)
{
  vtkNew<vtkMesoTrajectoryReader> reader;
  reader->SetTopologyFileName(data_file("proteins/1crn.pdb").c_str());
  reader->Update();
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 327);
  EXPECT_EQ(reader->GetOutput()->GetNumberOfLines(), 337);
}

TEST(vtkMesoTrajectoryReader, TakesTheTopologyBesideTheTrajectory)
{
  vtkNew<vtkMesoTrajectoryReader> named;
  named->SetTopologyFileName(data_file("membranes/yiip_popepopg.gro").c_str());
  named->SetTrajectoryFileName(data_file("membranes/yiip_popepopg.xtc").c_str());
  named->Update();
  vtkNew<vtkMesoTrajectoryReader> beside;
  beside->SetTrajectoryFileName(data_file("membranes/yiip_popepopg.xtc").c_str());
  beside->Update();
  ASSERT_GT(named->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_EQ(beside->GetOutput()->GetNumberOfPoints(), named->GetOutput()->GetNumberOfPoints());
  EXPECT_EQ(beside->GetOutput()->GetNumberOfLines(), named->GetOutput()->GetNumberOfLines());
  EXPECT_EQ(beside->GetNumberOfFrames(), named->GetNumberOfFrames());
  // No topology set and none beside: a clear error naming the trajectory.
  const std::string lonely = mesolens_test::output_file("lonely_trajectory");
  std::filesystem::create_directories(lonely);
  std::filesystem::copy_file(data_file("membranes/yiip_popepopg.xtc"), lonely + "/run.xtc",
                             std::filesystem::copy_options::overwrite_existing);
  std::ofstream(lonely + "/a.gro") << "";
  std::ofstream(lonely + "/b.gro") << "";
  vtkNew<vtkMesoTrajectoryReader> reader;
  mesolens_test::EventRecorder events(reader);
  reader->SetTrajectoryFileName((lonely + "/run.xtc").c_str());
  EXPECT_EQ(reader->GetExecutive()->Update(), 0);
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_NE(events.AllErrors().find("no topology lies beside"), std::string::npos)
    << events.AllErrors();
}

TEST(vtkMesoTrajectoryReader, BadInputsFailCleanly)
{
  const std::string gro = data_file("membranes/yiip_popepopg.gro");
  const std::string xtc = data_file("membranes/yiip_popepopg.xtc");
  const struct
  {
    std::string topology;
    std::string trajectory;
    const char* problem;
  } cases[] = {
    { mesolens_test::output_file("missing.gro"), "", "no such file" },
    { gro, mesolens_test::output_file("missing.xtc"), "no such file" },
    { gro, mesolens_test::write_bytes("traj_empty.xtc", ""), "empty" },
    { gro, mesolens_test::truncated_copy(xtc, 500000, "traj_truncated.xtc"), "truncated" },
    { gro, mesolens_test::garbage_file("traj_garbage.xtc"), "not an XTC" },
    { data_file("membranes/martini_dppc_vesicle.gro"), xtc, "mismatch" },
    { mesolens_test::garbage_file("traj_garbage.gro"), "", "GRO" },
  };
  for (const auto& c : cases)
  {
    SCOPED_TRACE(c.topology + " + " + c.trajectory);
    vtkNew<vtkMesoTrajectoryReader> reader;
    mesolens_test::EventRecorder events(reader);
    reader->SetTopologyFileName(c.topology.c_str());
    reader->SetTrajectoryFileName(c.trajectory.c_str());
    EXPECT_EQ(reader->GetExecutive()->Update(), 0);
    EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 0);
    ASSERT_FALSE(events.Errors.empty());
    EXPECT_NE(events.AllErrors().find(c.problem), std::string::npos) << events.AllErrors();
  }
  // The complete frames of a truncated trajectory can be read on request.
  vtkNew<vtkMesoTrajectoryReader> lenient;
  lenient->SetTopologyFileName(gro.c_str());
  lenient->SetTrajectoryFileName(mesolens_test::output_file("traj_truncated.xtc").c_str());
  lenient->SkipIncompleteFramesOn();
  EXPECT_EQ(lenient->GetExecutive()->Update(), 1);
  EXPECT_EQ(lenient->GetNumberOfFrames(), 3);
}
