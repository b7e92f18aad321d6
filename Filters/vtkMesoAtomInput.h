// SPDX-License-Identifier: GPL-3.0-or-later
// What every atom filter does first: its input's atoms as Core sees them, the atom table kept
// while the atoms' layout stays (private to MesoLensFilters).
#ifndef vtkMesoAtomInput_h
#define vtkMesoAtomInput_h

#include "vtkMesoStamp.h"

#include "mesolens/common/point_span.h"
#include "mesolens/molecules/atom_table.h"

#include <array>
#include <cstdint>
#include <vector>

class vtkPolyData;

/// One filter's view of its atom input, reused from update to update.
class vtkMesoAtomInput
{
public:
  /// Reads the atoms' table (Å; names, residues, chains, molecules, classes, positions of this
  /// frame) when their layout changed since the last call (vtkMesoAtomLayoutStamps), and says
  /// whether it did: a new frame of the same atoms needs only Positions(). Throws
  /// mesolens::InvalidInput naming the array that is missing (AtomName, ResidueIndex).
  bool ReadLayout(vtkPolyData* atoms);

  /// The table the last ReadLayout() read (its positions are those of that frame).
  const mesolens::AtomTable& Layout() const
  {
    return this->Table;
  }

  /// This frame's positions, one per atom: the points' own memory when they are floats, else a
  /// copy held here until the next call.
  mesolens::PointSpan<const float> Positions(vtkPolyData* atoms);

  /// The point array `name` as one byte per atom (the array's memory when it holds unsigned
  /// chars, else a copy held here until the next call); nullptr when absent.
  const std::uint8_t* Bytes(vtkPolyData* atoms, const char* name);

  /// The atoms as spheres (vtkMesoAtomTableConversion::AtomSpheres): centres and radii in Å.
  /// Throws mesolens::InvalidInput when the named radius array is missing.
  static void Spheres(vtkPolyData* atoms, const char* radius_array, double bead_radius,
                      std::vector<std::array<double, 3>>& centres, std::vector<double>& radii);

private:
  std::vector<vtkMesoStamp> LayoutFrom;
  mesolens::AtomTable Table;
  std::vector<float> PositionCopy;
  std::vector<std::uint8_t> ByteCopy;
};

#endif
