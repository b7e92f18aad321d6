// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoSelectAtoms.h"

#include "vtkMesoAtomTableConversion.h"
#include "vtkMesoParallelFor.h"

#include "mesolens/molecules/atom_selection.h"

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>

#include <vector>

vtkStandardNewMacro(vtkMesoSelectAtoms);

namespace {

/// The one-component point arrays the expression compares, by name.
void GatherArrays(vtkPointData* data, const std::vector<std::string>& names,
                  mesolens::SelectionArrays& arrays)
{
  for (const std::string& name : names)
  {
    vtkDataArray* array = data->GetArray(name.c_str());
    if (!array || array->GetNumberOfComponents() != 1)
    {
      continue; // evaluate() names the missing array and where the expression uses it
    }
    std::vector<double>& values = arrays[name];
    values.resize(std::size_t(array->GetNumberOfTuples()));
    for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
    {
      values[std::size_t(i)] = array->GetComponent(i, 0);
    }
  }
}

/// The selected atoms of `input`, their point arrays, field data and the bonds between them.
void Extract(vtkPolyData* input, const std::vector<std::uint8_t>& mask, vtkPolyData* output)
{
  if (!input->GetPoints())
  {
    return;
  }
  std::vector<vtkIdType> new_id(mask.size(), -1);
  vtkNew<vtkIdList> kept;
  for (std::size_t i = 0; i < mask.size(); ++i)
  {
    if (mask[i])
    {
      new_id[i] = kept->GetNumberOfIds();
      kept->InsertNextId(vtkIdType(i));
    }
  }
  vtkNew<vtkPoints> points;
  points->SetDataType(input->GetPoints()->GetDataType());
  input->GetPoints()->GetPoints(kept, points);
  output->SetPoints(points);
  output->GetPointData()->CopyAllocate(input->GetPointData(), kept->GetNumberOfIds());
  vtkNew<vtkIdList> destination;
  destination->SetNumberOfIds(kept->GetNumberOfIds());
  for (vtkIdType k = 0; k < kept->GetNumberOfIds(); ++k)
  {
    destination->SetId(k, k);
  }
  output->GetPointData()->CopyData(input->GetPointData(), kept, destination);
  output->GetPointData()->Squeeze();
  output->GetFieldData()->ShallowCopy(input->GetFieldData());
  vtkMesoAtomTableConversion::SetAtomVertices(output);

  vtkNew<vtkCellArray> bonds;
  vtkCellArray* lines = input->GetLines();
  vtkNew<vtkIdList> line;
  for (lines->InitTraversal(); lines->GetNextCell(line);)
  {
    if (line->GetNumberOfIds() != 2)
    {
      continue;
    }
    const vtkIdType a = line->GetId(0);
    const vtkIdType b = line->GetId(1);
    if (a >= 0 && b >= 0 && std::size_t(a) < mask.size() && std::size_t(b) < mask.size() &&
        new_id[std::size_t(a)] >= 0 && new_id[std::size_t(b)] >= 0)
    {
      const vtkIdType ends[2] = { new_id[std::size_t(a)], new_id[std::size_t(b)] };
      bonds->InsertNextCell(2, ends);
    }
  }
  output->SetLines(bonds);
}

} // namespace

int vtkMesoSelectAtoms::RequestData(vtkInformation*, vtkInformationVector** inputVector,
                                    vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  output->Initialize();
  if (this->OutputMode == MASK && this->MaskArrayName.empty())
  {
    vtkErrorMacro("MaskArrayName is empty: name the mask array.");
    return 0;
  }
  mesolens::AtomTable table;
  std::string missing;
  if (!vtkMesoAtomTableConversion::FromPolyData(input, this->LengthScale, table, &missing))
  {
    vtkErrorMacro(<< vtkMesoAtomTableConversion::MissingArrayMessage(missing));
    return 0;
  }
  std::vector<std::uint8_t> mask;
  try
  {
    const mesolens::AtomSelection selection(this->Selection);
    mesolens::SelectionArrays arrays;
    GatherArrays(input->GetPointData(), selection.array_names(), arrays);
    mask = selection.evaluate(table, arrays, vtkMesoParallelFor::Get());
  }
  catch (const mesolens::Error& error)
  {
    vtkErrorMacro(<< error.what());
    return 0;
  }
  if (this->OutputMode == EXTRACT)
  {
    Extract(input, mask, output);
    return 1;
  }
  output->ShallowCopy(input);
  vtkNew<vtkUnsignedCharArray> selected;
  selected->SetName(this->MaskArrayName.c_str());
  selected->SetNumberOfValues(vtkIdType(mask.size()));
  std::copy(mask.begin(), mask.end(), selected->GetPointer(0));
  output->GetPointData()->AddArray(selected);
  return 1;
}

void vtkMesoSelectAtoms::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Selection: " << this->Selection << "\n";
  os << indent << "OutputMode: " << (this->OutputMode == MASK ? "Mask" : "Extract") << "\n";
  os << indent << "MaskArrayName: " << this->MaskArrayName << "\n";
  os << indent << "LengthScale: " << this->LengthScale << "\n";
}
