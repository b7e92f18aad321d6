// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoTrajectoryRefinement.h"

#include "vtkMesoArrayNames.h"

#include "vtkMesoParallelFor.h"

#include "mesolens/common/errors.h"
#include "mesolens/molecules/molecule_groups.h"
#include "mesolens/molecules/periodic_box.h"
#include "mesolens/mapping/temporal_subdivision.h"

#include <vtkAlgorithmOutput.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPointSet.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkMesoTrajectoryRefinement);

struct vtkMesoTrajectoryRefinement::State
{
  std::vector<double> KeyTimes;     // input TIME_STEPS
  std::vector<double> RefinedTimes; // output TIME_STEPS; empty when the input has none
};

struct vtkMesoTrajectoryRefinement::KeyFrames
{
  mesolens::SubdivisionStencil Stencil;
  std::map<std::size_t, std::vector<float>> Positions; // per key frame, unwrapped
  vtkSmartPointer<vtkPointSet> Nearest; // shallow copy: structure and arrays of the output
};

vtkMesoTrajectoryRefinement::vtkMesoTrajectoryRefinement()
  : Internal(new State)
{
}

vtkMesoTrajectoryRefinement::~vtkMesoTrajectoryRefinement() = default;

namespace {
using vtkSDDP = vtkStreamingDemandDrivenPipeline;

/// The stencil's key frames in loading order: the nearest one, then outwards after it, then
/// outwards before it, so each frame can be unwrapped against one already loaded.
std::vector<std::size_t> loading_order(const mesolens::SubdivisionStencil& stencil)
{
  std::vector<std::size_t> order = { stencil.nearest_key_frame };
  for (const std::size_t k : stencil.key_frames)
  {
    if (k > stencil.nearest_key_frame)
    {
      order.push_back(k);
    }
  }
  for (auto k = stencil.key_frames.rbegin(); k != stencil.key_frames.rend(); ++k)
  {
    if (*k < stencil.nearest_key_frame)
    {
      order.push_back(*k);
    }
  }
  return order;
}

/// The refined frame a request asks for (the first one when it names no time).
std::size_t requested_frame(vtkInformation* outInfo, const std::vector<double>& refined_times)
{
  if (!outInfo->Has(vtkSDDP::UPDATE_TIME_STEP()))
  {
    return 0;
  }
  return mesolens::frame_at_time(refined_times, outInfo->Get(vtkSDDP::UPDATE_TIME_STEP()));
}

/// The box of field data `PeriodicBoxVectors` (9 values, rows a, b, c); unset when absent.
mesolens::PeriodicBox periodic_box(vtkDataObject* data)
{
  mesolens::PeriodicBox box;
  vtkDataArray* vectors = data->GetFieldData()
    ? data->GetFieldData()->GetArray(vtkMesoArrayNames::PeriodicBoxVectors)
    : nullptr;
  if (!vectors || vectors->GetNumberOfValues() != 9)
  {
    return box;
  }
  const int components = vectors->GetNumberOfComponents();
  for (int v = 0; v < 9; ++v)
  {
    box.vectors[std::size_t(v / 3)][std::size_t(v % 3)] =
      vectors->GetComponent(v / components, v % components);
  }
  return box;
}

/// The one-component point array `MoleculeId` with ids >= 0 as ints; empty when absent or
/// negative (then atoms are unwrapped one by one).
std::vector<int> molecule_ids(vtkPointSet* data)
{
  vtkDataArray* ids = data->GetPointData()->GetArray(vtkMesoArrayNames::MoleculeId);
  std::vector<int> molecules;
  if (!ids || ids->GetNumberOfComponents() != 1 ||
      ids->GetNumberOfTuples() != data->GetNumberOfPoints() || ids->GetRange()[0] < 0)
  {
    return molecules;
  }
  molecules.resize(std::size_t(ids->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < ids->GetNumberOfTuples(); ++i)
  {
    molecules[std::size_t(i)] = static_cast<int>(ids->GetComponent(i, 0));
  }
  return molecules;
}

/// The points of `data` as 3 floats each; false when a coordinate is not finite.
bool copy_points(vtkPointSet* data, std::vector<float>& positions)
{
  const vtkIdType n = data->GetNumberOfPoints();
  positions.resize(3 * std::size_t(n));
  if (n == 0)
  {
    return true;
  }
  if (auto* floats = vtkFloatArray::SafeDownCast(data->GetPoints()->GetData()))
  {
    std::memcpy(positions.data(), floats->GetPointer(0), positions.size() * sizeof(float));
  }
  else
  {
    for (vtkIdType i = 0; i < n; ++i)
    {
      double p[3];
      data->GetPoint(i, p);
      for (std::size_t k = 0; k < 3; ++k)
      {
        positions[3 * std::size_t(i) + k] = float(p[k]);
      }
    }
  }
  return std::all_of(positions.begin(), positions.end(), [](float v) { return std::isfinite(v); });
}
} // namespace

int vtkMesoTrajectoryRefinement::GetNumberOfRefinedFrames()
{
  this->UpdateInformation();
  return static_cast<int>(this->Internal->RefinedTimes.size());
}

int vtkMesoTrajectoryRefinement::ExecuteInformation(vtkInformation*,
                                                    vtkInformationVector** inputVector,
                                                    vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  State& state = *this->Internal;
  state = State{};
  outInfo->Remove(vtkSDDP::TIME_STEPS());
  outInfo->Remove(vtkSDDP::TIME_RANGE());
  const int count = inInfo->Length(vtkSDDP::TIME_STEPS());
  if (count <= 0)
  {
    return 1; // reported by RequestData, which leaves an empty output
  }
  const double* times = inInfo->Get(vtkSDDP::TIME_STEPS());
  try
  {
    state.KeyTimes.assign(times, times + count);
    state.RefinedTimes =
      mesolens::refined_times(state.KeyTimes, static_cast<unsigned>(this->RefinementLevels));
  }
  catch (const mesolens::Error& e)
  {
    vtkErrorMacro("Cannot refine the input's time steps: " << e.what());
    state = State{};
    return 0;
  }
  outInfo->Set(vtkSDDP::TIME_STEPS(), state.RefinedTimes.data(),
               static_cast<int>(state.RefinedTimes.size()));
  const double range[2] = { state.RefinedTimes.front(), state.RefinedTimes.back() };
  outInfo->Set(vtkSDDP::TIME_RANGE(), range, 2);
  return 1;
}

int vtkMesoTrajectoryRefinement::ComputeInputUpdateExtent(vtkInformation*,
                                                          vtkInformationVector** inputVector,
                                                          vtkInformationVector* outputVector)
{
  const State& state = *this->Internal;
  if (state.RefinedTimes.empty())
  {
    return 1;
  }
  const std::size_t frame =
    requested_frame(outputVector->GetInformationObject(0), state.RefinedTimes);
  try
  {
    const std::size_t nearest =
      mesolens::subdivision_stencil(state.KeyTimes.size(), unsigned(this->RefinementLevels), frame)
        .nearest_key_frame;
    inputVector[0]->GetInformationObject(0)->Set(vtkSDDP::UPDATE_TIME_STEP(),
                                                 state.KeyTimes[nearest]);
  }
  catch (const mesolens::Error&)
  {
    // reported by RequestData
  }
  return 1;
}

vtkPointSet* vtkMesoTrajectoryRefinement::UpdateInputTo(double time, vtkInformation* inInfo)
{
  vtkPointSet* input = vtkPointSet::GetData(inInfo);
  vtkInformation* dataInfo = input ? input->GetInformation() : nullptr;
  if (dataInfo && dataInfo->Has(vtkDataObject::DATA_TIME_STEP()) &&
      dataInfo->Get(vtkDataObject::DATA_TIME_STEP()) == time)
  {
    return input;
  }
  auto* executive = vtkSDDP::SafeDownCast(this->GetInputExecutive(0, 0));
  vtkAlgorithmOutput* connection = this->GetInputConnection(0, 0);
  if (!executive || !connection)
  {
    return nullptr;
  }
  inInfo->Set(vtkSDDP::UPDATE_TIME_STEP(), time);
  if (!executive->Update(connection->GetIndex()))
  {
    return nullptr;
  }
  return vtkPointSet::GetData(inInfo);
}

bool vtkMesoTrajectoryRefinement::LoadKeyFrames(std::size_t frame, vtkInformation* inInfo,
                                                KeyFrames& frames)
{
  const State& state = *this->Internal;
  try
  {
    frames.Stencil =
      mesolens::subdivision_stencil(state.KeyTimes.size(), unsigned(this->RefinementLevels), frame);
  }
  catch (const mesolens::Error& e)
  {
    vtkErrorMacro("Cannot refine frame " << frame << ": " << e.what());
    return false;
  }
  const std::vector<float>* previous = nullptr;        // neighbour towards the nearest key frame
  std::unique_ptr<mesolens::MoleculeGroups> molecules; // by MoleculeId, when the input has one
  const std::vector<std::size_t> order = loading_order(frames.Stencil);
  for (std::size_t step = 0; step < order.size(); ++step)
  {
    const std::size_t key = order[step];
    const double time = state.KeyTimes[key];
    vtkPointSet* input = this->UpdateInputTo(time, inInfo);
    std::ostringstream where;
    where << "key frame " << key << " (time " << time << ")";
    if (!input)
    {
      vtkErrorMacro("The input failed to produce " << where.str() << ".");
      return false;
    }
    std::vector<float>& p = frames.Positions[key];
    if (!input->GetPoints() || !copy_points(input, p))
    {
      vtkErrorMacro("The points of " << where.str() << " are missing or not finite.");
      return false;
    }
    if (step == 0)
    {
      frames.Nearest.TakeReference(input->NewInstance());
      frames.Nearest->ShallowCopy(input);
      const std::vector<int> ids = molecule_ids(input);
      if (!ids.empty())
      {
        molecules = std::make_unique<mesolens::MoleculeGroups>(
          mesolens::group_molecules(ids.data(), ids.size()));
      }
    }
    else if (p.size() != frames.Positions[order[0]].size())
    {
      vtkErrorMacro(<< where.str() << " has " << p.size() / 3 << " points but key frame "
                    << order[0] << " has " << frames.Positions[order[0]].size() / 3
                    << "; all key frames must have the same points.");
      return false;
    }
    else if (this->UnwrapPeriodicJumps)
    {
      if (key < order[0] && order[step - 1] > order[0])
      {
        previous = &frames.Positions[order[0]]; // the first frame before the nearest one
      }
      mesolens::unwrap_to_reference(p, *previous, periodic_box(input), molecules.get(),
                                    vtkMesoParallelFor::Get());
    }
    previous = &p;
    this->UpdateProgress(0.9 * double(step + 1) / double(order.size()));
    if (this->GetAbortExecute())
    {
      return false;
    }
  }
  return true;
}

int vtkMesoTrajectoryRefinement::RequestData(vtkInformation*, vtkInformationVector** inputVector,
                                             vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkPointSet* output = vtkPointSet::GetData(outInfo);
  output->Initialize();
  const State& state = *this->Internal;
  if (state.RefinedTimes.empty())
  {
    vtkErrorMacro("The input reports no TIME_STEPS; connect a temporal source such as "
                  "vtkMesoTrajectoryReader.");
    return 0;
  }
  const std::size_t frame = requested_frame(outInfo, state.RefinedTimes);
  KeyFrames frames;
  if (!this->LoadKeyFrames(frame, inInfo, frames))
  {
    return 0;
  }

  const mesolens::SubdivisionStencil& stencil = frames.Stencil;
  std::vector<const float*> positions;
  for (const std::size_t key : stencil.key_frames)
  {
    positions.push_back(frames.Positions[key].data());
  }
  const std::size_t values = frames.Positions[stencil.nearest_key_frame].size();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  points->SetNumberOfPoints(static_cast<vtkIdType>(values / 3));
  float* out = vtkFloatArray::SafeDownCast(points->GetData())->GetPointer(0);
  mesolens::combine_frames(positions, stencil.weights, values, out, vtkMesoParallelFor::Get());

  output->ShallowCopy(frames.Nearest);
  output->SetPoints(points);
  vtkNew<vtkFieldData> field;
  field->ShallowCopy(frames.Nearest->GetFieldData());
  vtkNew<vtkDoubleArray> index;
  index->SetName(vtkMesoArrayNames::RefinedFrameIndex);
  index->InsertNextValue(double(frame));
  field->RemoveArray(vtkMesoArrayNames::RefinedFrameIndex);
  field->AddArray(index);
  output->SetFieldData(field);
  output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), state.RefinedTimes[frame]);
  this->UpdateProgress(1.0);
  return 1;
}

void vtkMesoTrajectoryRefinement::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RefinementLevels: " << this->RefinementLevels << "\n";
  os << indent << "UnwrapPeriodicJumps: " << this->UnwrapPeriodicJumps << "\n";
}
