// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoAtomInput.h"

#include "vtkMesoAtomTableConversion.h"

#include "mesolens/common/errors.h"

#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>

#include <string>

bool vtkMesoAtomInput::ReadLayout(vtkPolyData* atoms)
{
  const auto stamps = vtkMesoAtomLayoutStamps(atoms);
  if (stamps == this->LayoutFrom)
  {
    return false;
  }
  this->LayoutFrom.clear(); // stays invalid when the table cannot be read
  std::string missing;
  if (!vtkMesoAtomTableConversion::FromPolyData(atoms, 1.0, this->Table, &missing))
  {
    throw mesolens::InvalidInput(vtkMesoAtomTableConversion::MissingArrayMessage(missing));
  }
  this->LayoutFrom = stamps;
  return true;
}

mesolens::PointSpan<const float> vtkMesoAtomInput::Positions(vtkPolyData* atoms)
{
  const vtkIdType n = atoms->GetNumberOfPoints();
  if (auto* floats = vtkFloatArray::FastDownCast(atoms->GetPoints()->GetData()))
  {
    return { floats->GetPointer(0), std::size_t(n) };
  }
  this->PositionCopy.resize(3 * std::size_t(n));
  for (vtkIdType a = 0; a < n; ++a)
  {
    double p[3];
    atoms->GetPoint(a, p);
    for (int d = 0; d < 3; ++d)
    {
      this->PositionCopy[3 * std::size_t(a) + std::size_t(d)] = static_cast<float>(p[d]);
    }
  }
  return this->PositionCopy;
}

const std::uint8_t* vtkMesoAtomInput::Bytes(vtkPolyData* atoms, const char* name)
{
  vtkDataArray* array = atoms->GetPointData()->GetArray(name);
  if (!array)
  {
    return nullptr;
  }
  if (auto* bytes = vtkUnsignedCharArray::FastDownCast(array))
  {
    return bytes->GetPointer(0);
  }
  this->ByteCopy.resize(std::size_t(array->GetNumberOfTuples()));
  for (vtkIdType a = 0; a < array->GetNumberOfTuples(); ++a)
  {
    this->ByteCopy[std::size_t(a)] = static_cast<std::uint8_t>(array->GetComponent(a, 0));
  }
  return this->ByteCopy.data();
}

void vtkMesoAtomInput::Spheres(vtkPolyData* atoms, const char* radius_array, double bead_radius,
                               std::vector<std::array<double, 3>>& centres,
                               std::vector<double>& radii)
{
  std::string error;
  if (!vtkMesoAtomTableConversion::AtomSpheres(atoms, radius_array, bead_radius, centres, radii,
                                               error))
  {
    throw mesolens::InvalidInput(error);
  }
}
