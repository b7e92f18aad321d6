// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoElementLookupTable.h"

#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPeriodicTable.h>

vtkStandardNewMacro(vtkMesoElementLookupTable);

vtkMesoElementLookupTable::vtkMesoElementLookupTable()
{
  constexpr int max_atomic_number = 118;
  this->SetNumberOfTableValues(max_atomic_number + 1);
  this->SetTableRange(0, max_atomic_number);
  vtkNew<vtkPeriodicTable> elements;
  const unsigned short known = elements->GetNumberOfElements();
  this->SetTableValue(0, 0.6, 0.6, 0.6, 1.0);
  for (int z = 1; z <= max_atomic_number; ++z)
  {
    float rgb[3] = { 0.6f, 0.6f, 0.6f };
    if (z <= known)
    {
      elements->GetDefaultRGBTuple(static_cast<unsigned short>(z), rgb);
    }
    this->SetTableValue(z, rgb[0], rgb[1], rgb[2], 1.0);
  }
}

void vtkMesoElementLookupTable::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Colours: Jmol/CPK by atomic number, 0 = grey\n";
}
