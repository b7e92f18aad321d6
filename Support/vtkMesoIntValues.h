// SPDX-License-Identifier: GPL-3.0-or-later
// An id array's values as ints, without a copy when it already holds them (private to the
// MesoLens modules).
#ifndef vtkMesoIntValues_h
#define vtkMesoIntValues_h

#include <vtkDataArray.h>
#include <vtkIntArray.h>

#include <cstddef>
#include <vector>

/// The first component of every tuple of `array` as an int: the array's own memory when it is a
/// one-component vtkIntArray (the readers' and the mapping's MoleculeId are), else a copy kept in
/// `copy`. nullptr for a null array.
inline const int* vtkMesoIntValues(vtkDataArray* array, std::vector<int>& copy)
{
  if (!array)
  {
    return nullptr;
  }
  auto* ints = vtkIntArray::FastDownCast(array);
  if (ints && ints->GetNumberOfComponents() == 1)
  {
    return ints->GetPointer(0);
  }
  copy.resize(static_cast<std::size_t>(array->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
  {
    copy[static_cast<std::size_t>(i)] = static_cast<int>(array->GetComponent(i, 0));
  }
  return copy.data();
}

#endif
