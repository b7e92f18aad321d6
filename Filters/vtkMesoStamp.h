// SPDX-License-Identifier: GPL-3.0-or-later
// What an object was when a filter computed something from it (private to MesoLensFilters).
#ifndef vtkMesoStamp_h
#define vtkMesoStamp_h

#include "vtkMesoArrayNames.h"

#include <vtkObject.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <vector>

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

/// The stamps of the point arrays that say which atom is which (names, residues, chains,
/// molecules, alternates): while they hold, a filter may keep its atom layout and read only the
/// positions of a new frame.
inline std::vector<vtkMesoStamp> vtkMesoAtomLayoutStamps(vtkPolyData* atoms)
{
  std::vector<vtkMesoStamp> stamps;
  for (const char* name :
       { vtkMesoArrayNames::AtomName, vtkMesoArrayNames::ResidueIndex,
         vtkMesoArrayNames::ResidueName, vtkMesoArrayNames::ChainId, vtkMesoArrayNames::MoleculeId,
         vtkMesoArrayNames::Occupancy, vtkMesoArrayNames::AltLoc })
  {
    stamps.push_back(vtkMesoStamp::Of(atoms->GetPointData()->GetAbstractArray(name)));
  }
  stamps.push_back({ nullptr, static_cast<vtkMTimeType>(atoms->GetNumberOfPoints()) });
  return stamps;
}

#endif
