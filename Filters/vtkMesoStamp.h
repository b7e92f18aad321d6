// SPDX-License-Identifier: GPL-3.0-or-later
// What an object was when a filter computed something from it (private to MesoLensFilters).
#ifndef vtkMesoStamp_h
#define vtkMesoStamp_h

#include <vtkObject.h>

/// An object's address and modification time: while both are the same, whatever was computed
/// from the object still holds.
struct vtkMesoStamp
{
  const void* Object = nullptr;
  vtkMTimeType Time = 0;

  static vtkMesoStamp Of(vtkObject* object)
  {
    return { object, object ? object->GetMTime() : 0 };
  }
  bool operator==(const vtkMesoStamp& other) const
  {
    return this->Object == other.Object && this->Time == other.Time;
  }
  bool operator!=(const vtkMesoStamp& other) const
  {
    return !(*this == other);
  }
};

#endif
