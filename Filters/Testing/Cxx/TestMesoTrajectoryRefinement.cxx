// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoArrayNames.h"
#include "vtkMesoTrajectoryReader.h"
#include "vtkMesoTrajectoryRefinement.h"

#include "mesolens_test_data.h"
#include "mesolens_vtk_test_utilities.h"

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataAlgorithm.h>
#include <vtkSphereSource.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

using mesolens_test::data_file;
using vtkSDDP = vtkStreamingDemandDrivenPipeline;

namespace {
double cubic(double s)
{
  return 1.5 - 0.7 * s + 0.3 * s * s - 0.05 * s * s * s;
}

/// A temporal source of three atoms at key times 0, 10, 20, ... (ps): atom 0 moves along a cubic
/// in x, atom 1 drifts +3 Å per frame in x across a 10 Å box and is wrapped into [0, 10), atom 2
/// moves linearly in y. Optionally changes its point count, emits NaN or fails at one frame.
class MovingAtomsSource : public vtkPolyDataAlgorithm
{
public:
  static MovingAtomsSource* New();
  vtkTypeMacro(MovingAtomsSource, vtkPolyDataAlgorithm);
  int Frames = 8;
  int ExtraPointAtFrame = -1;
  int NaNAtFrame = -1;
  int FailAtFrame = -1;
  int Executions = 0;

protected:
  MovingAtomsSource()
  {
    this->SetNumberOfInputPorts(0);
  }
  int RequestInformation(vtkInformation*, vtkInformationVector**,
                         vtkInformationVector* outputVector) override
  {
    std::vector<double> times;
    for (int k = 0; k < this->Frames; ++k)
    {
      times.push_back(10.0 * k);
    }
    vtkInformation* info = outputVector->GetInformationObject(0);
    info->Set(vtkSDDP::TIME_STEPS(), times.data(), this->Frames);
    const double range[2] = { times.front(), times.back() };
    info->Set(vtkSDDP::TIME_RANGE(), range, 2);
    return 1;
  }
  int RequestData(vtkInformation*, vtkInformationVector**,
                  vtkInformationVector* outputVector) override
  {
    ++this->Executions;
    vtkInformation* info = outputVector->GetInformationObject(0);
    const double time =
      info->Has(vtkSDDP::UPDATE_TIME_STEP()) ? info->Get(vtkSDDP::UPDATE_TIME_STEP()) : 0.0;
    const int k = std::max(0, std::min(this->Frames - 1, int(std::floor(time / 10.0 + 1e-9))));
    if (k == this->FailAtFrame)
    {
      return 0;
    }
    const double wrapped = std::fmod(1.0 + 3.0 * k, 10.0);
    vtkNew<vtkPoints> points;
    points->InsertNextPoint(cubic(k), 0, 0);
    points->InsertNextPoint(k == this->NaNAtFrame ? std::nan("") : wrapped, 5, 5);
    points->InsertNextPoint(0, 3.0 - 0.5 * k, 0);
    if (k == this->ExtraPointAtFrame)
    {
      points->InsertNextPoint(0, 0, 0);
    }
    vtkPolyData* output = vtkPolyData::GetData(outputVector);
    output->SetPoints(points);
    vtkNew<vtkDoubleArray> box;
    box->SetName(vtkMesoArrayNames::PeriodicBoxVectors);
    box->SetNumberOfComponents(9);
    const double vectors[9] = { 10, 0, 0, 0, 10, 0, 0, 0, 10 };
    box->InsertNextTuple(vectors);
    output->GetFieldData()->AddArray(box);
    output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), 10.0 * k);
    return 1;
  }
};
vtkStandardNewMacro(MovingAtomsSource);

std::vector<double> time_steps(vtkAlgorithm* algorithm)
{
  algorithm->UpdateInformation();
  vtkInformation* info = algorithm->GetOutputInformation(0);
  const double* times = info->Get(vtkSDDP::TIME_STEPS());
  return std::vector<double>(times, times + info->Length(vtkSDDP::TIME_STEPS()));
}

vtkPolyData* frame_at(vtkMesoTrajectoryRefinement* refinement, double time)
{
  refinement->UpdateTimeStep(time);
  return vtkPolyData::SafeDownCast(refinement->GetOutput());
}

/// Weights of refined frame j: the 4-point scheme run on a unit impulse at each key frame, with
/// the reflected linear extrapolation at the ends (independent of the library's stencil code).
std::vector<double> impulse_weights(int keys, int levels, int j)
{
  std::vector<double> weights;
  for (int key = 0; key < keys; ++key)
  {
    std::vector<double> x(std::size_t(keys), 0.0);
    x[std::size_t(key)] = 1.0;
    for (int level = 0; level < levels; ++level)
    {
      const long n = long(x.size());
      auto at = [&](long i) {
        return i < 0 ? 2 * x[0] - x[1]
          : i >= n   ? 2 * x[std::size_t(n - 1)] - x[std::size_t(n - 2)]
                     : x[std::size_t(i)];
      };
      std::vector<double> refined;
      for (long i = 0; i < n; ++i)
      {
        refined.push_back(x[std::size_t(i)]);
        if (i + 1 < n)
        {
          refined.push_back((-at(i - 1) + 9 * at(i) + 9 * at(i + 1) - at(i + 2)) / 16);
        }
      }
      x = refined;
    }
    weights.push_back(x[std::size_t(j)]);
  }
  return weights;
}
} // namespace

TEST(vtkMesoTrajectoryRefinement, Defaults)
{
  vtkNew<vtkMesoTrajectoryRefinement> refinement;
  EXPECT_EQ(refinement->GetRefinementLevels(), 2);
  EXPECT_TRUE(refinement->GetUnwrapPeriodicJumps());
  refinement->SetRefinementLevels(12);
  EXPECT_EQ(refinement->GetRefinementLevels(), 8);
  refinement->SetRefinementLevels(-1);
  EXPECT_EQ(refinement->GetRefinementLevels(), 0);
  std::ostringstream print;
  refinement->Print(print);
  EXPECT_NE(print.str().find("RefinementLevels: 0"), std::string::npos);
  EXPECT_NE(print.str().find("UnwrapPeriodicJumps: 1"), std::string::npos);
}

TEST(vtkMesoTrajectoryRefinement, CubicAndLinearMotion)
{
  vtkNew<MovingAtomsSource> source;
  vtkNew<vtkMesoTrajectoryRefinement> refinement;
  refinement->SetInputConnection(source->GetOutputPort());
  refinement->SetRefinementLevels(3);
  const std::vector<double> times = time_steps(refinement);
  ASSERT_EQ(times.size(), 7u * 8u + 1u);
  EXPECT_EQ(refinement->GetNumberOfRefinedFrames(), 57);
  EXPECT_DOUBLE_EQ(times[3], 3.75);
  const double* range = refinement->GetOutputInformation(0)->Get(vtkSDDP::TIME_RANGE());
  EXPECT_EQ(range[1], 70.0);
  for (std::size_t j = 0; j < times.size(); ++j)
  {
    vtkPolyData* out = frame_at(refinement, times[j]);
    ASSERT_EQ(out->GetNumberOfPoints(), 3);
    const double s = double(j) / 8.0;
    // The cubic is exact away from the two key frames at either end.
    if (s >= 3.0 && s <= 4.0)
    {
      EXPECT_NEAR(out->GetPoint(0)[0], cubic(s), 1e-5) << j;
    }
    EXPECT_NEAR(out->GetPoint(2)[1], 3.0 - 0.5 * s, 1e-5) << j; // linear: exact everywhere
    EXPECT_EQ(out->GetInformation()->Get(vtkDataObject::DATA_TIME_STEP()), times[j]);
    EXPECT_EQ(out->GetFieldData()->GetArray(vtkMesoArrayNames::RefinedFrameIndex)->GetTuple1(0),
              double(j));
  }
  // A time between refined frames gives the latest one not after it.
  EXPECT_EQ(frame_at(refinement, 4.0)
              ->GetFieldData()
              ->GetArray(vtkMesoArrayNames::RefinedFrameIndex)
              ->GetTuple1(0),
            3.0);
}

TEST(vtkMesoTrajectoryRefinement, ReadsOnlyTheStencilFrames)
{
  vtkNew<MovingAtomsSource> source;
  vtkNew<vtkMesoTrajectoryRefinement> refinement;
  refinement->SetInputConnection(source->GetOutputPort());
  refinement->SetRefinementLevels(2);
  refinement->UpdateTimeStep(32.5); // refined frame 13, between key frames 3 and 4
  const std::vector<double> weights = impulse_weights(8, 2, 13);
  const auto used = std::count_if(weights.begin(), weights.end(), [](double w) { return w != 0; });
  EXPECT_EQ(used, 5);
  EXPECT_EQ(source->Executions, used); // each key frame of the stencil once
  source->Executions = 0;
  refinement->UpdateTimeStep(40.0); // a key frame: only itself
  EXPECT_LE(source->Executions, 1);
}

TEST(vtkMesoTrajectoryRefinement, PeriodicCrossingIsContinuous)
{
  vtkNew<MovingAtomsSource> source;
  vtkNew<vtkMesoTrajectoryRefinement> refinement;
  refinement->SetInputConnection(source->GetOutputPort());
  refinement->SetRefinementLevels(2);
  const std::vector<double> times = time_steps(refinement);
  for (std::size_t j = 0; j < times.size(); ++j)
  {
    // Relative to the nearest key frame, the atom moves on the unwrapped line +3 Å per frame
    // (key frames two apart are more than half a box apart: unwrapping must chain).
    const double s = double(j) / 4.0;
    const double nearest = std::floor(s + 0.5 - 1e-12);
    const double key_x = std::fmod(1.0 + 3.0 * nearest, 10.0);
    EXPECT_NEAR(frame_at(refinement, times[j])->GetPoint(1)[0], key_x + 3.0 * (s - nearest), 1e-5)
      << j;
  }
  // Without unwrapping the atom flies across the box between key frames 2 (x = 7) and 3 (x = 0).
  refinement->UnwrapPeriodicJumpsOff();
  EXPECT_LT(frame_at(refinement, times[10])->GetPoint(1)[0], 6.0);
}

TEST(vtkMesoTrajectoryRefinement, ChainedFiltersEqualMoreLevels)
{
  // One level refined once more is two levels (the end rule applies at every level), and the
  // downstream filter drives the upstream one through the pipeline for each of its key frames.
  vtkNew<MovingAtomsSource> source;
  vtkNew<vtkMesoTrajectoryRefinement> first;
  first->SetInputConnection(source->GetOutputPort());
  first->SetRefinementLevels(1);
  vtkNew<vtkMesoTrajectoryRefinement> second;
  second->SetInputConnection(first->GetOutputPort());
  second->SetRefinementLevels(1);
  vtkNew<vtkMesoTrajectoryRefinement> direct;
  direct->SetInputConnection(source->GetOutputPort());
  direct->SetRefinementLevels(2);
  const std::vector<double> times = time_steps(direct);
  ASSERT_EQ(time_steps(second), times);
  for (const std::size_t j : { 9u, 2u, 27u, 13u, 0u, 14u })
  {
    vtkNew<vtkPolyData> expected;
    expected->DeepCopy(frame_at(direct, times[j]));
    vtkPolyData* chained = frame_at(second, times[j]);
    ASSERT_EQ(chained->GetNumberOfPoints(), 3);
    for (vtkIdType i = 0; i < 3; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        // Equal up to the periodic image (each filter unwraps to its own nearest key frame).
        const double d = chained->GetPoint(i)[c] - expected->GetPoint(i)[c];
        EXPECT_NEAR(d - 10.0 * std::round(d / 10.0), 0.0, 1e-5) << j;
      }
    }
  }
}

TEST(vtkMesoTrajectoryRefinement, RealTrajectory)
{
  vtkNew<vtkMesoTrajectoryReader> reader;
  reader->SetTopologyFileName(data_file("membranes/yiip_popepopg.gro").c_str());
  reader->SetTrajectoryFileName(data_file("membranes/yiip_popepopg.xtc").c_str());
  reader->MakeMoleculesWholeOn();
  reader->KeepMoleculesContinuousOn();
  vtkNew<vtkMesoTrajectoryRefinement> refinement;
  refinement->SetInputConnection(reader->GetOutputPort());
  refinement->SetRefinementLevels(2);
  const std::vector<double> times = time_steps(refinement);
  ASSERT_EQ(times.size(), 4u * 4u + 1u);
  EXPECT_DOUBLE_EQ(times[1], 5000.0);
  EXPECT_DOUBLE_EQ(times[16], 80000.0);

  // An independent reader gives the key frames.
  vtkNew<vtkMesoTrajectoryReader> keys;
  keys->SetTopologyFileName(data_file("membranes/yiip_popepopg.gro").c_str());
  keys->SetTrajectoryFileName(data_file("membranes/yiip_popepopg.xtc").c_str());
  std::vector<vtkSmartPointer<vtkPolyData>> key_frames;
  for (int k = 0; k < 5; ++k)
  {
    keys->UpdateTimeStep(20000.0 * k);
    key_frames.push_back(vtkSmartPointer<vtkPolyData>::New());
    key_frames.back()->DeepCopy(keys->GetOutput());
  }

  // Arbitrary order: in-between frames, key frames, back again.
  for (const int j : { 6, 16, 1, 8, 0, 13, 4, 6 })
  {
    SCOPED_TRACE(j);
    vtkPolyData* out = frame_at(refinement, times[std::size_t(j)]);
    ASSERT_EQ(out->GetNumberOfPoints(), 43480);
    EXPECT_EQ(out->GetNumberOfLines(), key_frames[0]->GetNumberOfLines());
    EXPECT_NE(out->GetPointData()->GetArray(vtkMesoArrayNames::MoleculeId), nullptr);
    const std::vector<double> weights = impulse_weights(5, 2, j);
    double largest_error = 0;
    for (vtkIdType i = 0; i < out->GetNumberOfPoints(); i += 7)
    {
      for (int c = 0; c < 3; ++c)
      {
        double expected = 0;
        for (int k = 0; k < 5; ++k)
        {
          expected += weights[std::size_t(k)] * key_frames[std::size_t(k)]->GetPoint(i)[c];
        }
        const double value = out->GetPoint(i)[c];
        if (j % 4 == 0)
        {
          ASSERT_EQ(value, key_frames[std::size_t(j / 4)]->GetPoint(i)[c]); // exact key frame
        }
        largest_error = std::max(largest_error, std::abs(value - expected));
      }
    }
    EXPECT_LT(largest_error, 1e-3);
  }
}

TEST(vtkMesoTrajectoryRefinement, InputWithoutTimeSteps)
{
  vtkNew<vtkSphereSource> sphere;
  vtkNew<vtkMesoTrajectoryRefinement> refinement;
  refinement->SetInputConnection(sphere->GetOutputPort());
  mesolens_test::EventRecorder events(refinement);
  EXPECT_EQ(refinement->GetExecutive()->Update(), 0);
  EXPECT_EQ(refinement->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_NE(events.AllErrors().find("no TIME_STEPS"), std::string::npos) << events.AllErrors();
  EXPECT_EQ(refinement->GetNumberOfRefinedFrames(), 0);
}

TEST(vtkMesoTrajectoryRefinement, BadKeyFrames)
{
  const struct
  {
    int extra_point_at;
    int nan_at;
    int fail_at;
    const char* problem;
  } cases[] = { { 4, -1, -1, "same points" },
                { -1, 3, -1, "not finite" },
                { -1, -1, 5, "failed to produce key frame 5" } };
  for (const auto& c : cases)
  {
    SCOPED_TRACE(c.problem);
    vtkNew<MovingAtomsSource> source;
    source->ExtraPointAtFrame = c.extra_point_at;
    source->NaNAtFrame = c.nan_at;
    source->FailAtFrame = c.fail_at;
    mesolens_test::EventRecorder source_events(source); // the source's own failure, not printed
    vtkNew<vtkMesoTrajectoryRefinement> refinement;
    refinement->SetInputConnection(source->GetOutputPort());
    mesolens_test::EventRecorder events(refinement);
    EXPECT_EQ(refinement->UpdateTimeStep(35.0), 0); // stencil: key frames 2 to 5
    EXPECT_EQ(refinement->GetOutput()->GetNumberOfPoints(), 0);
    EXPECT_NE(events.AllErrors().find(c.problem), std::string::npos) << events.AllErrors();
    // The filter recovers on a good request.
    events.Clear();
    refinement->UpdateTimeStep(0.0);
    EXPECT_EQ(refinement->GetOutput()->GetNumberOfPoints(), 3);
  }
}
