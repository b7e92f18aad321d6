// SPDX-License-Identifier: GPL-3.0-or-later
// Conversion of a Core AtomTable into the vtkPolyData layout of every MesoLens atom reader
// (private to MesoLensFilters; not installed, not wrapped).
#ifndef vtkMesoAtomTableConversion_h
#define vtkMesoAtomTableConversion_h

#include <array>
#include <cstddef>
#include <initializer_list>
#include <string>
#include <vector>

class vtkIdList;
class vtkPointData;
class vtkPolyData;
namespace mesolens {
struct AtomTable;
struct PeriodicBox;
}

namespace vtkMesoAtomTableConversion {

/// Fills `output` with one vertex per atom, one line per bond and the named point arrays
/// documented in vtkMesoStructureReader.h. Positions are multiplied by `length_scale`.
void ToPolyData(const mesolens::AtomTable& table, double length_scale, vtkPolyData* output);

/// The atoms of a polydata laid out as ToPolyData makes them, back as an AtomTable: positions
/// (Å, divided by `length_scale`) and whichever of the named arrays are present (names,
/// elements, residues, insertion codes, chains, alternates, occupancies, B-factors, HETATM
/// flags, serials, formal charges, secondary structure, residue indices, molecule ids); every
/// per-atom vector is filled (defaults where an array is absent); bonds are not read. Returns
/// false, naming what is missing in `missing`, without `AtomName` or `ResidueIndex`.
bool FromPolyData(vtkPolyData* atoms, double length_scale, mesolens::AtomTable& table,
                  std::string* missing = nullptr);

/// The error a filter gives for atoms without the array FromPolyData names as missing.
std::string MissingArrayMessage(const std::string& missing);

/// Replaces the points of an output built by ToPolyData with `positions` (3 floats per atom,
/// Å) times `length_scale`, picking atoms `kept` (all atoms when empty).
void SetPositions(const std::vector<float>& positions, const std::vector<std::size_t>& kept,
                  double length_scale, vtkPolyData* output);

/// Makes every point of `output` a vertex cell (vertex i holds point i), replacing its verts:
/// a vtkPolyData without cells has no bounds and renders nothing.
void SetAtomVertices(vtkPolyData* output);

/// Adds (or replaces) the field-data array "PeriodicBoxVectors" (9 doubles, rows a, b, c, in
/// output length units); removes it when the box is not set.
void SetPeriodicBox(const mesolens::PeriodicBox& box, double length_scale, vtkPolyData* output);

/// Adds a one-value field-data array (replacing one of the same name).
void SetFieldValue(vtkPolyData* output, const char* name, double value);

/// Every numeric point array of the atoms (`atoms`) onto the points of `out`: point v takes the
/// tuple of atom from->GetId(v). String arrays are left out (costly per vertex, they colour
/// nothing), and those named in `skip`.
void GatherAtomArrays(vtkPointData* atoms, vtkIdList* from, vtkPointData* out,
                      std::initializer_list<const char*> skip);

/// The atoms as spheres: centres (Å) and radii (Å), from the point array `radius_array` when
/// it is set and not empty, else the van der Waals radius of `AtomicNumber`, and `bead_radius`
/// for atoms without an element. Returns false, with the reason in `error`, when the named
/// array is missing. Radii are not checked (the Core functions do).
bool AtomSpheres(vtkPolyData* atoms, const char* radius_array, double bead_radius,
                 std::vector<std::array<double, 3>>& centres, std::vector<double>& radii,
                 std::string& error);
void SetFieldString(vtkPolyData* output, const char* name, const std::string& value);

}

#endif
