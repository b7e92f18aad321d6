// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoSelectAtoms.h"

#include "vtkMesoAtomPieces.h"
#include "vtkMesoAtomTableConversion.h"
#include "vtkMesoParallelFor.h"

#include "mesolens/molecules/atom_selection.h"

#include <vtkDataArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
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
  vtkNew<vtkUnsignedCharArray> selected;
  selected->SetName(this->MaskArrayName.c_str());
  selected->SetNumberOfValues(vtkIdType(mask.size()));
  std::copy(mask.begin(), mask.end(), selected->GetPointer(0));
  if (this->OutputMode == EXTRACT)
  {
    vtkMesoAtomPieces::ExtractAtoms(input, selected, output);
    return 1;
  }
  output->ShallowCopy(input);
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
