// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoArrayNames.h"
#include "vtkMesoSecondaryStructure.h"

#include "mesolens_test_data.h"
#include "mesolens_vtk_test_utilities.h"
#include "vtkMesoStructureReader.h"
#include "vtkMesoTrajectoryReader.h"

#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkStringArray.h>

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace {
/// All chains' DSSP strings joined.
std::string dssp_of(vtkPolyData* output)
{
  auto* chains =
    vtkStringArray::SafeDownCast(output->GetFieldData()->GetAbstractArray(vtkMesoArrayNames::DSSP));
  std::string joined;
  for (vtkIdType c = 0; chains && c < chains->GetNumberOfValues(); ++c)
    joined += chains->GetValue(c);
  return joined;
}
} // namespace

TEST(vtkMesoSecondaryStructure, CrambinAsMkdsspAssignsIt)
{
  vtkNew<vtkMesoStructureReader> reader;
  reader->SetFileName(mesolens_test::data_file("proteins/1crn.pdb").c_str());
  vtkNew<vtkMesoSecondaryStructure> dssp;
  dssp->SetInputConnection(reader->GetOutputPort());
  mesolens_test::EventRecorder events(dssp);
  dssp->Update();
  ASSERT_TRUE(events.Errors.empty()) << events.AllErrors();
  vtkPolyData* output = dssp->GetOutput();
  EXPECT_EQ(dssp_of(output), "-EE-SSHHHHHHHHHHHTTT--HHHHHHHHS-EE-SSS---GGG--");
  // Every atom carries its residue's class: the CA of residue 10 (index 9) is in the helix.
  vtkDataArray* classes = output->GetPointData()->GetArray(vtkMesoArrayNames::SecondaryStructure);
  vtkDataArray* runs = output->GetPointData()->GetArray(vtkMesoArrayNames::SecondaryStructureId);
  vtkDataArray* residues = output->GetPointData()->GetArray(vtkMesoArrayNames::ResidueIndex);
  auto* names = vtkStringArray::SafeDownCast(
    output->GetPointData()->GetAbstractArray(vtkMesoArrayNames::AtomName));
  int helix_atoms = 0;
  for (vtkIdType a = 0; a < output->GetNumberOfPoints(); ++a)
  {
    if (residues->GetTuple1(a) == 9)
    {
      EXPECT_EQ(classes->GetTuple1(a), 1.0) << names->GetValue(a);
      EXPECT_GE(runs->GetTuple1(a), 0.0);
      ++helix_atoms;
    }
  }
  EXPECT_GT(helix_atoms, 4);
  EXPECT_EQ(output->GetFieldData()
              ->GetArray(vtkMesoArrayNames::ResidueSecondaryStructure)
              ->GetNumberOfTuples(),
            46);
  EXPECT_GT(output->GetFieldData()->GetArray(vtkMesoArrayNames::HydrogenBonds)->GetTuple1(0), 20.0);
  // The positions are the input's (a shallow copy).
  EXPECT_EQ(output->GetPoints(), reader->GetOutput()->GetPoints());
}

TEST(vtkMesoSecondaryStructure, FileRecordsKeptOrRecomputed)
{
  // 1tii has HELIX/SHEET records (mkdssp refuses the file).
  vtkNew<vtkMesoStructureReader> reader;
  reader->SetFileName(mesolens_test::data_file("proteins/1tii.pdb").c_str());
  vtkNew<vtkMesoSecondaryStructure> dssp;
  dssp->SetInputConnection(reader->GetOutputPort());
  dssp->Update();
  const std::string computed = dssp_of(dssp->GetOutput());
  EXPECT_GT(computed.size(), 700u);
  EXPECT_NE(computed.find("HHHH"), std::string::npos);
  EXPECT_NE(computed.find("EEEE"), std::string::npos);
  dssp->KeepFileRecordsOn();
  dssp->Update();
  // Kept: the reader's classes (no turns, bends or 3-10 helices in the records) and no DSSP.
  vtkDataArray* kept =
    dssp->GetOutput()->GetPointData()->GetArray(vtkMesoArrayNames::SecondaryStructure);
  EXPECT_EQ(kept,
            reader->GetOutput()->GetPointData()->GetArray(vtkMesoArrayNames::SecondaryStructure));
  EXPECT_EQ(dssp->GetOutput()->GetFieldData()->GetAbstractArray(vtkMesoArrayNames::DSSP), nullptr);
}

TEST(vtkMesoSecondaryStructure, NmrModelsAsTimeSteps)
{
  // Trp-cage: 38 models with hydrogens; each time step assigned (mkdssp on model 1 below).
  vtkNew<vtkMesoStructureReader> reader;
  reader->SetFileName(mesolens_test::data_file("proteins/1l2y.pdb").c_str());
  vtkNew<vtkMesoSecondaryStructure> dssp;
  dssp->SetInputConnection(reader->GetOutputPort());
  dssp->UpdateInformation();
  const int steps =
    dssp->GetOutputInformation(0)->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  ASSERT_EQ(steps, 38);
  // A copy: the pipeline replaces the information's vector when it updates.
  const double* steps_in_information =
    dssp->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  const std::vector<double> times(steps_in_information, steps_in_information + steps);
  dssp->UpdateTimeStep(times[0]);
  EXPECT_EQ(dssp_of(dssp->GetOutput()), "-HHHHHHHTTGGGGT-PPP-");
  int helical = 0;
  for (int s = 0; s < steps; ++s)
  {
    dssp->UpdateTimeStep(times[s]);
    helical += dssp_of(dssp->GetOutput()).substr(2, 5) == "HHHHH";
  }
  EXPECT_GE(helical, 35);
}

TEST(vtkMesoSecondaryStructure, TrajectoryFramesWithHysteresis)
{
  // The YiiP transporter in its membrane, frame by frame: the assignment follows the frames;
  // with a hysteresis of 3 frames fewer residues change class from frame to frame.
  vtkNew<vtkMesoTrajectoryReader> trajectory;
  trajectory->SetTopologyFileName(mesolens_test::data_file("membranes/yiip_popepopg.gro").c_str());
  trajectory->SetTrajectoryFileName(
    mesolens_test::data_file("membranes/yiip_popepopg.xtc").c_str());
  vtkNew<vtkMesoSecondaryStructure> dssp;
  dssp->SetInputConnection(trajectory->GetOutputPort());
  dssp->UpdateInformation();
  const int steps =
    dssp->GetOutputInformation(0)->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  ASSERT_GE(steps, 5);
  // A copy: the pipeline replaces the information's vector when it updates.
  const double* steps_in_information =
    dssp->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  const std::vector<double> times(steps_in_information, steps_in_information + steps);
  auto changes_over_frames = [&](int hysteresis) {
    dssp->SetHysteresisFrames(hysteresis);
    std::string previous;
    int changes = 0;
    for (int s = 0; s < steps; ++s)
    {
      dssp->UpdateTimeStep(times[s]);
      const std::string now = dssp_of(dssp->GetOutput());
      EXPECT_GT(now.size(), 500u);
      if (!previous.empty())
        for (std::size_t r = 0; r < now.size(); ++r)
          changes += now[r] != previous[r];
      previous = now;
    }
    return changes;
  };
  const int raw = changes_over_frames(1);
  const int held = changes_over_frames(3);
  std::printf("YiiP: %d frames, class changes between frames %d raw, %d with a 3-frame hold\n",
              steps, raw, held);
  EXPECT_GT(raw, 0);
  EXPECT_LT(held, raw);
  const std::string last = dssp_of(dssp->GetOutput());
  EXPECT_GT(std::count(last.begin(), last.end(), 'H'), 200); // a helical transporter
}

TEST(vtkMesoSecondaryStructure, ProteasomeFromAGroFile)
{
  // 3l5q.gro: 79 452 atoms, no chain ids, no HELIX/SHEET records, no hydrogens.
  const std::string path = mesolens_test::shared_file("proteins/3l5q.gro");
  if (!mesolens_test::exists(path))
    GTEST_SKIP() << "needs ../shared/data";
  vtkNew<vtkMesoTrajectoryReader> reader;
  reader->SetTopologyFileName(path.c_str());
  vtkNew<vtkMesoSecondaryStructure> dssp;
  dssp->SetInputConnection(reader->GetOutputPort());
  mesolens_test::EventRecorder events(dssp);
  dssp->Update();
  ASSERT_TRUE(events.Errors.empty()) << events.AllErrors();
  const std::string all = dssp_of(dssp->GetOutput());
  const auto helix = std::count(all.begin(), all.end(), 'H');
  const auto strand = std::count(all.begin(), all.end(), 'E');
  std::printf("3l5q: %zu residues, %zu chains, %.1f %% H, %.1f %% E\n", all.size(),
              std::size_t(dssp->GetOutput()
                            ->GetFieldData()
                            ->GetAbstractArray(vtkMesoArrayNames::DSSP)
                            ->GetNumberOfTuples()),
              100.0 * double(helix) / double(all.size()),
              100.0 * double(strand) / double(all.size()));
  EXPECT_GT(all.size(), 9000u);
  EXPECT_GT(double(helix) / double(all.size()), 0.2);
  EXPECT_GT(double(strand) / double(all.size()), 0.12);
}

TEST(vtkMesoSecondaryStructure, BadInputsGiveAnErrorAndNoOutput)
{
  vtkNew<vtkMesoSecondaryStructure> dssp;
  mesolens_test::EventRecorder events(dssp);
  // Plain points without the reader's arrays.
  vtkNew<vtkPolyData> plain;
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  plain->SetPoints(points);
  dssp->SetInputData(plain);
  dssp->Update();
  EXPECT_NE(events.AllErrors().find(vtkMesoArrayNames::AtomName), std::string::npos);
  EXPECT_EQ(dssp->GetOutput()->GetNumberOfPoints(), 0);
  // No atoms.
  events.Errors.clear();
  vtkNew<vtkPolyData> empty;
  dssp->SetInputData(empty);
  dssp->Update();
  EXPECT_FALSE(events.Errors.empty());
  // A nucleic acid: no amino acids, nothing assigned, no error.
  events.Errors.clear();
  vtkNew<vtkMesoStructureReader> dna;
  dna->SetFileName(mesolens_test::data_file("proteins/1bna.pdb").c_str());
  dssp->SetInputConnection(dna->GetOutputPort());
  dssp->Update();
  EXPECT_TRUE(events.Errors.empty()) << events.AllErrors();
  EXPECT_EQ(dssp_of(dssp->GetOutput()), "");
  EXPECT_GT(dssp->GetOutput()->GetNumberOfPoints(), 400);
  // A NaN backbone atom.
  vtkNew<vtkMesoStructureReader> crambin;
  crambin->SetFileName(mesolens_test::data_file("proteins/1crn.pdb").c_str());
  crambin->Update();
  vtkNew<vtkPolyData> broken;
  broken->DeepCopy(crambin->GetOutput());
  broken->GetPoints()->SetPoint(1, std::nan(""), 0, 0); // the CA of residue 1
  dssp->SetInputData(broken);
  dssp->Update();
  EXPECT_NE(events.AllErrors().find("non-finite"), std::string::npos);
  EXPECT_EQ(dssp->GetOutput()->GetNumberOfPoints(), 0);
}
