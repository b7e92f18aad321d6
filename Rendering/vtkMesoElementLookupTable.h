// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * @class   vtkMesoElementLookupTable
 * @brief   Colours atoms by element: a lookup table indexed by atomic number.
 *
 * Entry z (0..118) holds the Jmol/CPK colour of element z from VTK's Blue Obelisk data
 * (vtkPeriodicTable); entry 0 (unknown element, coarse-grained bead) is a neutral grey. Map the
 * `AtomicNumber` array of a MesoLens reader through it (the table range is [0, 118]).
 */
#ifndef vtkMesoElementLookupTable_h
#define vtkMesoElementLookupTable_h

#include "MesoLensRenderingModule.h"
#include "vtkLookupTable.h"

class MESOLENSRENDERING_EXPORT vtkMesoElementLookupTable : public vtkLookupTable
{
public:
  static vtkMesoElementLookupTable* New();
  vtkTypeMacro(vtkMesoElementLookupTable, vtkLookupTable);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkMesoElementLookupTable();
  ~vtkMesoElementLookupTable() override = default;

private:
  vtkMesoElementLookupTable(const vtkMesoElementLookupTable&) = delete;
  void operator=(const vtkMesoElementLookupTable&) = delete;
};

#endif
