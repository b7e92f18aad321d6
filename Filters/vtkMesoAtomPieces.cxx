// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoAtomPieces.h"

#include "vtkMesoArrayNames.h"

#include <vtkAbstractArray.h>
#include <vtkAppendPolyData.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkMultiProcessController.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkUnsignedCharArray.h>

#include <numeric>
#include <tuple>
#include <unordered_map>
#include <vector>

namespace vtkMesoAtomPieces {

std::pair<int, int> Requested(vtkInformation* info)
{
  using Pipeline = vtkStreamingDemandDrivenPipeline;
  if (!info || !info->Has(Pipeline::UPDATE_NUMBER_OF_PIECES()) ||
      !info->Has(Pipeline::UPDATE_PIECE_NUMBER()))
  {
    return { 0, 1 };
  }
  const int pieces = info->Get(Pipeline::UPDATE_NUMBER_OF_PIECES());
  const int piece = info->Get(Pipeline::UPDATE_PIECE_NUMBER());
  return pieces < 1 || piece < 0 || piece >= pieces ? std::pair{ 0, 1 }
                                                    : std::pair{ piece, pieces };
}

std::vector<vtkIdType> AtomsOfPiece(vtkPolyData* atoms, int piece, int pieces)
{
  const vtkIdType n = atoms ? atoms->GetNumberOfPoints() : 0;
  std::vector<vtkIdType> kept;
  // A molecule goes to the piece its first atom's rank among all atoms falls in; the rest of
  // its atoms follow it.
  vtkDataArray* ids =
    n > 0 ? atoms->GetPointData()->GetArray(vtkMesoArrayNames::MoleculeId) : nullptr;
  std::unordered_map<long long, int> piece_of_molecule;
  for (vtkIdType a = 0; a < n; ++a)
  {
    const int first_atom_piece = static_cast<int>((static_cast<long double>(a) * pieces) / n);
    int owner = first_atom_piece;
    if (ids)
    {
      owner =
        piece_of_molecule.emplace(static_cast<long long>(ids->GetComponent(a, 0)), first_atom_piece)
          .first->second;
    }
    if (owner == piece)
    {
      kept.push_back(a);
    }
  }
  return kept;
}

void KeepPiece(vtkPolyData* atoms, int piece, int pieces)
{
  if (pieces <= 1 || !atoms || atoms->GetNumberOfPoints() == 0)
  {
    return;
  }
  ExtractAtomIds(atoms, AtomsOfPiece(atoms, piece, pieces), atoms);
}

void ExtractAtomIds(vtkPolyData* atoms, const std::vector<vtkIdType>& ids, vtkPolyData* output)
{
  vtkNew<vtkUnsignedCharArray> keep;
  keep->SetNumberOfValues(atoms->GetNumberOfPoints());
  keep->FillValue(0);
  for (const vtkIdType a : ids)
  {
    keep->SetValue(a, 1);
  }
  vtkNew<vtkPolyData> kept;
  ExtractAtoms(atoms, keep, kept);
  output->ShallowCopy(kept);
}

bool Gathers(vtkInformation* info)
{
  const int pieces = Requested(info).second;
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  return pieces > 1 && controller && controller->GetNumberOfProcesses() == pieces;
}

void RequestWholeInputsWhenStreaming(vtkInformationVector** inputs, int ports,
                                     vtkInformationVector* outputs)
{
  vtkInformation* out = outputs->GetInformationObject(0);
  if (Requested(out).second < 2 || Gathers(out))
  {
    return;
  }
  using Pipeline = vtkStreamingDemandDrivenPipeline;
  for (int port = 0; port < ports; ++port)
  {
    for (int c = 0; c < inputs[port]->GetNumberOfInformationObjects(); ++c)
    {
      vtkInformation* in = inputs[port]->GetInformationObject(c);
      in->Set(Pipeline::UPDATE_PIECE_NUMBER(), 0);
      in->Set(Pipeline::UPDATE_NUMBER_OF_PIECES(), 1);
      in->Set(Pipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
    }
  }
}

GatheredInput::GatheredInput(vtkInformationVector* input, vtkInformationVector* outputs,
                             Output output, std::initializer_list<const char*> only_arrays)
  : Outputs(outputs)
  , Keep(output)
{
  vtkPolyData* local = vtkPolyData::GetData(input);
  this->All = local;
  if (!this->All)
  {
    this->All = vtkSmartPointer<vtkPolyData>::New();
  }
  this->Own = this->All->GetNumberOfPoints();
  this->Versions = local ? local->GetMTime() : 0;
  vtkInformation* out = outputs->GetInformationObject(0);
  std::tie(this->ThisPiece, this->Pieces) = Requested(out);
  if (!Gathers(out))
  {
    return;
  }
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  this->WasGathered = true;
  this->ThisPiece = controller->GetLocalProcessId();
  vtkNew<vtkPolyData> mine;
  if (local && only_arrays.size() == 0)
  {
    mine->ShallowCopy(local);
  }
  else if (local && local->GetPoints())
  {
    mine->SetPoints(local->GetPoints());
    for (const char* name : only_arrays)
    {
      if (vtkAbstractArray* array = local->GetPointData()->GetAbstractArray(name))
      {
        mine->GetPointData()->AddArray(array);
      }
    }
    mine->GetFieldData()->ShallowCopy(local->GetFieldData());
  }
  std::vector<vtkSmartPointer<vtkDataObject>> everyone;
  controller->AllGather(mine, everyone);
  std::vector<long long> versions(static_cast<std::size_t>(controller->GetNumberOfProcesses()));
  const long long version = static_cast<long long>(this->Versions);
  controller->AllGather(&version, versions.data(), 1);
  this->Versions = 0;
  for (const long long v : versions)
  {
    this->Versions += static_cast<vtkMTimeType>(v);
  }
  vtkNew<vtkAppendPolyData> append;
  vtkFieldData* fields = nullptr;
  for (std::size_t rank = 0; rank < everyone.size(); ++rank)
  {
    auto piece = vtkPolyData::SafeDownCast(everyone[rank]);
    if (!piece || piece->GetNumberOfPoints() == 0)
    {
      continue;
    }
    if (static_cast<int>(rank) < this->ThisPiece)
    {
      this->First += piece->GetNumberOfPoints();
    }
    fields = fields ? fields : piece->GetFieldData();
    append->AddInputData(piece);
  }
  this->All = vtkSmartPointer<vtkPolyData>::New();
  if (append->GetNumberOfInputConnections(0) > 0)
  {
    append->Update();
    this->All->ShallowCopy(append->GetOutput());
    this->All->GetFieldData()->ShallowCopy(fields);
  }
}

GatheredInput::~GatheredInput()
{
  if (this->Keep != KeepOwn || this->Pieces < 2)
  {
    return;
  }
  vtkPolyData* output = vtkPolyData::GetData(this->Outputs, 0);
  if (!this->WasGathered)
  {
    KeepPiece(output, this->ThisPiece, this->Pieces); // streaming: the whole input was asked for
    return;
  }
  if (!output || output->GetNumberOfPoints() != this->All->GetNumberOfPoints())
  {
    return; // an error left it empty
  }
  std::vector<vtkIdType> own(static_cast<std::size_t>(this->Own));
  std::iota(own.begin(), own.end(), this->First);
  ExtractAtomIds(output, own, output);
}

vtkPolyData* GatheredInput::Whole() const
{
  return this->All;
}

bool GatheredInput::Gathered() const
{
  return this->WasGathered;
}

int GatheredInput::Piece() const
{
  return this->ThisPiece;
}

int GatheredInput::PieceCount() const
{
  return this->Pieces;
}

vtkIdType GatheredInput::FirstOwn() const
{
  return this->First;
}

vtkMTimeType GatheredInput::Version() const
{
  return this->Versions;
}

void ExtractAtoms(vtkPolyData* atoms, const vtkUnsignedCharArray* keep, vtkPolyData* output)
{
  const vtkIdType n = atoms->GetNumberOfPoints();
  std::vector<vtkIdType> new_id(static_cast<std::size_t>(n), -1);
  vtkNew<vtkIdList> kept;
  for (vtkIdType a = 0; a < n; ++a)
  {
    if (keep->GetValue(a))
    {
      new_id[static_cast<std::size_t>(a)] = kept->GetNumberOfIds();
      kept->InsertNextId(a);
    }
  }
  vtkNew<vtkPoints> points;
  points->SetDataType(atoms->GetPoints()->GetDataType());
  atoms->GetPoints()->GetPoints(kept, points);
  output->SetPoints(points);
  vtkNew<vtkIdList> order;
  order->SetNumberOfIds(kept->GetNumberOfIds());
  std::iota(order->begin(), order->end(), 0);
  output->GetPointData()->CopyAllocate(atoms->GetPointData(), kept->GetNumberOfIds());
  output->GetPointData()->CopyData(atoms->GetPointData(), kept, order);
  output->GetFieldData()->ShallowCopy(atoms->GetFieldData());
  // Vertices first, then lines: the cell data of polydata is in that order.
  output->GetCellData()->CopyAllocate(atoms->GetCellData());
  vtkIdType cell = 0;
  vtkIdType kept_cells = 0;
  vtkNew<vtkIdList> ids;
  for (vtkCellArray* source : { atoms->GetVerts(), atoms->GetLines() })
  {
    vtkNew<vtkCellArray> cells;
    const vtkIdType count = source ? source->GetNumberOfCells() : 0;
    for (vtkIdType c = 0; c < count; ++c, ++cell)
    {
      source->GetCellAtId(c, ids);
      bool all = true;
      for (vtkIdType k = 0; k < ids->GetNumberOfIds() && all; ++k)
      {
        const vtkIdType mapped = new_id[static_cast<std::size_t>(ids->GetId(k))];
        all = mapped >= 0;
        ids->SetId(k, mapped);
      }
      if (all)
      {
        cells->InsertNextCell(ids);
        output->GetCellData()->CopyData(atoms->GetCellData(), cell, kept_cells++);
      }
    }
    if (source == atoms->GetVerts())
    {
      output->SetVerts(cells);
    }
    else
    {
      output->SetLines(cells);
    }
  }
}

} // namespace vtkMesoAtomPieces
