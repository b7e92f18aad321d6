// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoAtomGPUData.h"

#include "vtkMesoArrayNames.h"
#include "vtkMesoAssemblyInstances.h"
#include "vtkMesoElementLookupTable.h"
#include "vtkMesoMembraneWarp.h"
#include "vtkMesoIntValues.h"
#include "vtkMesoParallelFor.h"

#include "mesolens/molecules/elements.h"
#include "mesolens/common/errors.h"
#include "mesolens/mapping/membrane_warp.h"
#include "mesolens/molecules/molecule_groups.h"
#include "mesolens/mapping/polynomial_warp.h"
#include "mesolens/mapping/warped_cells.h"
#include "mesolens/protein/assembly.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkMapper.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkScalarsToColors.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <unordered_map>

namespace {
constexpr int element_count = 128;
constexpr int color_count = 256;
constexpr int nan_color = color_count - 1;

int element_of(vtkDataArray* numbers, vtkIdType atom)
{
  const double z = numbers ? numbers->GetComponent(atom, 0) : 0.0;
  // The last element is the hidden atoms'.
  return std::isfinite(z) ? static_cast<int>(std::clamp(z, 0.0, double(element_count - 2))) : 0;
}

/// The colour array of the mapper's settings, or nullptr for element colours.
vtkDataArray* color_array(vtkPolyData* atoms, vtkMapper* mapper)
{
  if (!mapper->GetScalarVisibility() ||
      mapper->GetScalarMode() != VTK_SCALAR_MODE_USE_POINT_FIELD_DATA)
  {
    return nullptr;
  }
  vtkPointData* points = atoms->GetPointData();
  if (mapper->GetArrayAccessMode() == VTK_GET_ARRAY_BY_ID)
  {
    return points->GetArray(mapper->GetArrayId());
  }
  const char* name = mapper->GetArrayName();
  return name && *name ? points->GetArray(name) : nullptr;
}

/// Corners of a box: x from bounds[0..1], y [2..3], z [4..5].
std::array<double, 3> corner(const double bounds[6], int index)
{
  return { bounds[(index & 1) ? 1 : 0], bounds[(index & 2) ? 3 : 2], bounds[(index & 4) ? 5 : 4] };
}

void grow(double bounds[6], const double p[3])
{
  for (int d = 0; d < 3; ++d)
  {
    bounds[2 * d] = std::min(bounds[2 * d], p[d]);
    bounds[2 * d + 1] = std::max(bounds[2 * d + 1], p[d]);
  }
}

/// Bounds of the polynomial-warped tiles: each piece's polynomial on a 5 x 5 x 5 grid over its
/// part of the patch's (s, t, h) box. `warp` is drawable (mesolens::check_drawable).
void polynomial_bounds(vtkPolyData* atoms, const mesolens::MembraneWarp& warp, double bounds[6])
{
  double patch_bounds[6];
  atoms->GetBounds(patch_bounds);
  const mesolens::MembranePatch patch = warp.frame();
  double local[6] = { 1e300, -1e300, 1e300, -1e300, 1e300, -1e300 };
  for (int c = 0; c < 8; ++c)
  {
    const auto p = corner(patch_bounds, c);
    const float pf[3] = { float(p[0]), float(p[1]), float(p[2]) };
    const auto q = mesolens::polynomial_coordinates(patch, warp.layer_half_thickness, pf);
    grow(local, q.data());
  }
  const std::vector<std::size_t> first = mesolens::polynomial_first_pieces(warp);
  // Each piece over its own part of the tile's (s, t) box; the edge pieces also reach the
  // atoms beyond the cell.
  auto piece_range = [](int piece, int m, double low, double high, double range[2]) {
    const double from = piece == 0 ? std::min(low, -1.0) : -1 + 2.0 * piece / m;
    const double to = piece == m - 1 ? std::max(high, 1.0) : -1 + 2.0 * (piece + 1) / m;
    range[0] = (from + 1) * m - 2 * piece - 1; // the piece's own coordinate
    range[1] = (to + 1) * m - 2 * piece - 1;
  };
  constexpr int steps = 5;
  for (std::size_t tile = 0; tile + 1 < first.size(); ++tile)
  {
    const int m = warp.polynomial_splits.empty() ? 1 : warp.polynomial_splits[tile];
    for (int piece = 0; piece < m * m; ++piece)
    {
      mesolens::QuadraticWarp polynomial{};
      std::copy_n(warp.polynomial_coefficients.data() + 30 * (first[tile] + std::size_t(piece)), 30,
                  polynomial.data());
      double s_range[2], t_range[2];
      piece_range(piece % m, m, local[0], local[1], s_range);
      piece_range(piece / m, m, local[2], local[3], t_range);
      for (int i = 0; i < steps * steps * steps; ++i)
      {
        const double f[3] = { double(i % steps) / (steps - 1),
                              double(i / steps % steps) / (steps - 1),
                              double(i / (steps * steps)) / (steps - 1) };
        const auto x = mesolens::evaluate_quadratic(
          polynomial, s_range[0] + f[0] * (s_range[1] - s_range[0]),
          t_range[0] + f[1] * (t_range[1] - t_range[0]), local[4] + f[2] * (local[5] - local[4]));
        grow(bounds, x.data());
      }
    }
  }
}

/// Molecule slot per atom: the order of the instances of tile 0 (first appearance in the patch).
bool molecule_slots(vtkPolyData* atoms, const mesolens::MembraneWarp& warp,
                    std::vector<unsigned short>& slots, int& molecules_per_tile,
                    std::string& problem)
{
  vtkDataArray* ids = atoms->GetPointData()->GetArray(vtkMesoArrayNames::MoleculeId);
  if (!ids)
  {
    problem = "molecule instancing needs the patch's MoleculeId";
    return false;
  }
  // The slot of each of the patch's molecules: its instance's place among tile 0's.
  std::unordered_map<int, int> slot_of;
  for (std::size_t i = 0; i < mesolens::molecules_per_tile(warp); ++i)
  {
    slot_of.emplace(warp.instance_molecules[i], static_cast<int>(i));
  }
  molecules_per_tile = static_cast<int>(slot_of.size());
  if (molecules_per_tile == 0 || molecules_per_tile > 65536)
  {
    problem = "molecule instancing supports 1 to 65536 molecules per tile, the warp input has " +
      std::to_string(molecules_per_tile);
    return false;
  }
  const vtkIdType n = atoms->GetNumberOfPoints();
  std::vector<int> id_copy;
  const mesolens::MoleculeGroups groups =
    mesolens::group_molecules(vtkMesoIntValues(ids, id_copy), static_cast<std::size_t>(n));
  slots.resize(static_cast<std::size_t>(n));
  for (std::size_t m = 0; m < groups.count(); ++m)
  {
    const auto found = slot_of.find(groups.ids[m]);
    if (found == slot_of.end())
    {
      problem = "patch atom " + std::to_string(groups.atoms[groups.first[m]]) +
        " belongs to molecule " + std::to_string(groups.ids[m]) +
        ", which the warp input does not place: is it the patch that was mapped?";
      return false;
    }
    for (const std::uint32_t a : groups.atoms_of(m))
    {
      slots[a] = static_cast<unsigned short>(found->second);
    }
  }
  return true;
}
/// The first `motions` of an instancing warp's motions as texels: the first 3 rows (12 floats)
/// of each 4 x 4 matrix.
std::vector<float> motion_texels(const mesolens::MembraneWarp& warp, std::size_t motions)
{
  std::vector<float> texels(12 * motions);
  for (std::size_t m = 0; m < motions; ++m)
  {
    for (std::size_t k = 0; k < 12; ++k)
    {
      texels[12 * m + k] = static_cast<float>(warp.instance_matrices[16 * m + k]);
    }
  }
  return texels;
}

/// Whether a warp input is an assembly's copies (vtkMesoStructureReader's output 1) rather than
/// a membrane mapping's output.
bool is_assembly(vtkPolyData* warp_data)
{
  return warp_data->GetPointData()->GetArray(vtkMesoArrayNames::AssemblyMatrix) != nullptr;
}

/// An assembly's copies as an instancing warp over the asymmetric unit (`atoms`): a tile per
/// copy, a motion per atom class (mesolens::assembly_atom_classes) in each, the copy's matrix.
/// `slots`: each atom's class (input order); `hidden`: a bit per class and copy (copy c's class
/// k is bit c classes + k), set where the copy's atom set leaves the class out.
bool assembly_warp(vtkPolyData* atoms, vtkPolyData* copies, mesolens::MembraneWarp& warp,
                   std::vector<unsigned short>& slots, int& classes_per_copy,
                   std::vector<std::uint32_t>& hidden, std::string& problem)
{
  mesolens::AssemblyInstances instances;
  if (!vtkMesoAssemblyInstances::Read(copies, instances))
  {
    problem = "the assembly input is not a vtkMesoStructureReader's output 1 (its copies' "
              "arrays are missing or inconsistent)";
    return false;
  }
  if (instances.instances.empty())
  {
    problem = "the assembly has no copies";
    return false;
  }
  const auto n = static_cast<std::size_t>(atoms->GetNumberOfPoints());
  mesolens::AssemblyAtomClasses classes;
  try
  {
    classes = mesolens::assembly_atom_classes(instances, n);
  }
  catch (const mesolens::Error& e)
  {
    problem = std::string(e.what()) +
      " (draw the reader's output 0 with ExpandAssembly off, the asymmetric unit)";
    return false;
  }
  if (classes.count > 65536)
  {
    problem = "the assembly's atom sets split the asymmetric unit into " +
      std::to_string(classes.count) + " groups, more than the 65536 an instanced draw holds";
    return false;
  }
  const std::size_t copy_count = instances.instances.size();
  warp = {};
  warp.method = mesolens::MappingMethod::MoleculeInstancing;
  warp.copy_tiles = copy_count;
  warp.a = { 1, 0 };
  warp.b = { 0, 1 };
  warp.instance_matrices.reserve(16 * copy_count * classes.count);
  hidden.assign((copy_count * classes.count + 31) / 32, 0u);
  bool any_hidden = false;
  for (std::size_t c = 0; c < copy_count; ++c)
  {
    const mesolens::AssemblyMatrix& m = instances.instances[c].matrix;
    for (const double value : m)
    {
      if (!std::isfinite(value) || std::abs(value) > 3.4e38)
      {
        problem = "copy " + std::to_string(c) + "'s matrix is not finite in float";
        return false;
      }
    }
    for (std::size_t k = 0; k < classes.count; ++k)
    {
      warp.instance_matrices.insert(warp.instance_matrices.end(), m.begin(), m.end());
      warp.instance_matrices.insert(warp.instance_matrices.end(), { 0.0, 0.0, 0.0, 1.0 });
      warp.instance_molecules.push_back(static_cast<int>(k));
      warp.instance_tiles.push_back(static_cast<int>(c));
      if (!classes.shows(instances, c, k))
      {
        const std::size_t bit = c * classes.count + k;
        hidden[bit / 32] |= 1u << (bit % 32);
        any_hidden = true;
      }
    }
  }
  if (!any_hidden)
  {
    hidden.clear();
  }
  slots.resize(n);
  for (std::size_t a = 0; a < n; ++a)
  {
    slots[a] = static_cast<unsigned short>(classes.class_of_atom[a]);
  }
  classes_per_copy = static_cast<int>(classes.count);
  return true;
}
} // namespace

std::vector<float> vtkMesoAtomGPUData::StyleRadii(const Style& style)
{
  std::vector<float> radii(element_count);
  for (int z = 0; z < element_count; ++z)
  {
    double r = z == 0 || z > mesolens::max_atomic_number ? 1.0 : mesolens::van_der_waals_radius(z);
    if (style.Style == 1)
    {
      r *= style.BallScale;
    }
    else if (style.Style == 2)
    {
      r = style.BondRadius;
    }
    radii[std::size_t(z)] = static_cast<float>(r * style.RadiusScale);
  }
  radii[vtkMesoAtomGPUData::HiddenElement] = 0.0f;
  return radii;
}

void vtkMesoAtomGPUData::Clear()
{
  this->AtomCount = 0;
  this->TileCount = 1;
  this->PositionData = nullptr;
  this->PositionStorage.clear();
  this->Cells = {};
  this->SlotOfAtom.clear();
  this->CellBoxes.clear();
  this->Types.clear();
  this->MoleculeSlots.clear();
  this->Bonds.clear();
  this->ClearWarp();
  this->TypesKey = {};
  this->BondsKey = {};
  this->MaskKey = {};
  this->PositionsKey = {};
  this->UnmaskedTypes.clear();
  this->HiddenAtoms = 0;
}

bool vtkMesoAtomGPUData::Update(vtkPolyData* atoms, vtkPolyData* warp, const Style& style,
                                vtkMapper* mapper, std::size_t atoms_per_cell,
                                const char* mask_name)
{
  this->Radii = StyleRadii(style);
  this->BondRadius = static_cast<float>(style.BondRadius * style.RadiusScale);
  if (!warp)
  {
    this->ClearWarp();
  }
  if (!atoms || !atoms->GetPoints() || atoms->GetNumberOfPoints() == 0)
  {
    this->Clear();
    return false;
  }
  const vtkIdType n = atoms->GetNumberOfPoints();
  if (n > std::numeric_limits<int>::max() / 3)
  {
    vtkErrorWithObjectMacro(mapper, "Cannot draw " << n << " atoms: at most 715827882 per mapper");
    this->Clear();
    return false;
  }
  this->AtomCount = n;
  vtkDataArray* mask =
    mask_name && *mask_name ? atoms->GetPointData()->GetArray(mask_name) : nullptr;
  if (!this->UpdatePositions(atoms, mapper, atoms_per_cell) || !this->UpdateBonds(atoms, mapper))
  {
    this->Clear();
    return false;
  }
  this->UpdateTypes(atoms, mapper, mask);
  this->LargestPresentRadius = 0;
  for (std::size_t z = 0; z < this->ElementPresent.size(); ++z)
  {
    this->LargestPresentRadius =
      std::max(this->LargestPresentRadius, this->ElementPresent[z] ? this->Radii[z] : 0.0f);
  }
  if (warp &&
      (!this->ReadWarp(atoms, warp, mapper) || !this->ReadMoleculeMask(warp, mapper, mask_name)))
  {
    this->Clear();
    return false;
  }
  return true;
}

void vtkMesoAtomGPUData::ClearWarp()
{
  this->TileCount = 1;
  this->MoleculeSlots.clear();
  this->WarpMethod = NoWarp;
  this->WarpTexels.clear();
  this->WarpedAtoms.reset();
  this->WarpKey.clear();
  this->PatchMolecules = 0;
  this->MoleculeSizes.clear();
  this->MoleculeMask.clear();
  this->MoleculeMaskKey = {};
  this->AssemblyCopies = false;
}

bool vtkMesoAtomGPUData::UpdatePositions(vtkPolyData* atoms, vtkMapper* mapper,
                                         std::size_t atoms_per_cell)
{
  // Float coordinates go up as they are (when not regrouped); others are converted once.
  vtkDataArray* coordinates = atoms->GetPoints()->GetData();
  // The same coordinates, unchanged (a new mask or colour on the same atoms): nothing to do.
  // (The cell size takes the mapper time's place in the key.)
  const ArrayKey key{ coordinates, coordinates->GetMTime(), nullptr,
                      0,           atoms_per_cell,          this->AtomCount };
  if (key == this->PositionsKey && this->PositionData)
  {
    return true;
  }
  this->PositionsKey = {};
  ++this->PositionsVersion;
  const std::size_t values = 3 * static_cast<std::size_t>(this->AtomCount);
  const float* input = nullptr;
  std::vector<float> converted;
  if (auto* floats = vtkFloatArray::FastDownCast(coordinates))
  {
    input = floats->GetPointer(0);
  }
  else
  {
    converted.resize(values);
    for (vtkIdType i = 0; i < this->AtomCount; ++i)
    {
      double p[3];
      coordinates->GetTuple(i, p);
      for (int d = 0; d < 3; ++d)
      {
        converted[std::size_t(3 * i + d)] = static_cast<float>(p[d]);
      }
    }
    input = converted.data();
  }
  for (std::size_t i = 0; i < values; ++i)
  {
    if (!std::isfinite(input[i]))
    {
      vtkErrorWithObjectMacro(
        mapper, "Cannot draw the atoms: atom " << i / 3 << " has a non-finite position");
      return false;
    }
  }
  if (atoms_per_cell == 0)
  {
    this->Cells = {};
    this->SlotOfAtom.clear();
    this->CellBoxes.clear();
    if (converted.empty())
    {
      this->PositionStorage.clear();
      this->PositionData = input;
    }
    else
    {
      this->PositionStorage = std::move(converted);
      this->PositionData = this->PositionStorage.data();
    }
    this->PositionsKey = key;
    return true;
  }
  // New cells for new atoms, or when a trajectory's atoms have spread their cells by half.
  const auto n = static_cast<std::size_t>(this->AtomCount);
  this->PositionStorage.resize(values);
  bool regroup = this->Cells.atom_of_slot.size() != n;
  if (!regroup)
  {
    mesolens::gather_cell_positions({ input, n }, this->Cells, this->PositionStorage,
                                    this->CellBoxes, vtkMesoParallelFor::Get());
    regroup = mesolens::total_cell_diagonal(this->CellBoxes) > 1.5 * this->GroupedDiagonal;
  }
  if (regroup)
  {
    this->Cells = mesolens::group_atoms_into_cells({ input, n }, atoms_per_cell);
    this->SlotOfAtom.resize(n);
    for (std::size_t slot = 0; slot < n; ++slot)
    {
      this->SlotOfAtom[this->Cells.atom_of_slot[slot]] = static_cast<std::uint32_t>(slot);
    }
    mesolens::gather_cell_positions({ input, n }, this->Cells, this->PositionStorage,
                                    this->CellBoxes, vtkMesoParallelFor::Get());
    this->GroupedDiagonal = mesolens::total_cell_diagonal(this->CellBoxes);
    ++this->CellsVersion;
    // The per-atom tables follow the new slot order.
    this->TypesKey = {};
    this->BondsKey = {};
    this->MaskKey = {};
  }
  this->PositionData = this->PositionStorage.data();
  this->PositionsKey = key;
  return true;
}

void vtkMesoAtomGPUData::UpdateTypes(vtkPolyData* atoms, vtkMapper* mapper, vtkDataArray* mask)
{
  vtkDataArray* numbers = atoms->GetPointData()->GetArray(vtkMesoArrayNames::AtomicNumber);
  vtkDataArray* scalars = color_array(atoms, mapper);
  vtkScalarsToColors* table = scalars ? mapper->GetLookupTable() : nullptr;
  if (table && !mapper->GetUseLookupTableScalarRange())
  {
    // Before the key: setting the range modifies the table, and so the mapper's time.
    table->SetRange(mapper->GetScalarRange());
  }
  // The same arrays, unchanged, under the same settings: the types stay (a new time step).
  const ArrayKey key{ numbers,
                      numbers ? numbers->GetMTime() : 0,
                      scalars,
                      scalars ? scalars->GetMTime() : 0,
                      mapper->GetMTime(),
                      this->AtomCount };
  if (!(key == this->TypesKey))
  {
    this->TypesKey = key;
    this->ComputeTypes(mapper, numbers, scalars, table);
    this->MaskKey = {};
  }
  // The mask over the types: a new mask costs a copy of the type bytes.
  const ArrayKey mask_key{ mask, mask ? mask->GetMTime() : 0, nullptr, 0, 0, this->AtomCount };
  if (mask_key == this->MaskKey)
  {
    return;
  }
  this->MaskKey = mask_key;
  ++this->TypesVersion;
  this->Types = this->UnmaskedTypes;
  this->HiddenAtoms = 0;
  if (!mask)
  {
    return;
  }
  auto* bytes = vtkUnsignedCharArray::FastDownCast(mask);
  for (vtkIdType i = 0; i < this->AtomCount; ++i)
  {
    if (bytes ? bytes->GetValue(i) == 0 : mask->GetComponent(i, 0) == 0.0)
    {
      this->Types[2 * this->SlotOf(i)] = HiddenElement;
      ++this->HiddenAtoms;
    }
  }
}

void vtkMesoAtomGPUData::ComputeTypes(vtkMapper* mapper, vtkDataArray* numbers,
                                      vtkDataArray* scalars, vtkScalarsToColors* table)
{
  const vtkIdType n = this->AtomCount;
  this->UnmaskedTypes.resize(2 * static_cast<std::size_t>(n));
  this->ElementPresent.assign(element_count, false);
  this->ColorTable.assign(4 * color_count, 0.6f);
  if (table)
  {
    const double* range = table->GetRange();
    const double low = range[0];
    const double width = range[1] > range[0] ? range[1] - range[0] : 1.0;
    const int component =
      std::clamp(mapper->GetArrayComponent(), 0, scalars->GetNumberOfComponents() - 1);
    for (int bin = 0; bin < color_count; ++bin)
    {
      const double value = bin == nan_color ? std::numeric_limits<double>::quiet_NaN()
                                            : low + (bin + 0.5) / (color_count - 1) * width;
      const unsigned char* rgba = table->MapValue(value);
      for (int c = 0; c < 4; ++c)
      {
        this->ColorTable[std::size_t(4 * bin + c)] = rgba[c] / 255.0f;
      }
    }
    for (vtkIdType i = 0; i < n; ++i)
    {
      const double value = scalars->GetComponent(i, component);
      int bin = nan_color;
      if (std::isfinite(value))
      {
        bin = static_cast<int>(
          std::clamp((value - low) / width * (color_count - 1), 0.0, double(color_count - 2)));
      }
      const std::size_t slot = this->SlotOf(i);
      const int z = element_of(numbers, i);
      this->ElementPresent[std::size_t(z)] = true;
      this->UnmaskedTypes[2 * slot] = static_cast<unsigned char>(z);
      this->UnmaskedTypes[2 * slot + 1] = static_cast<unsigned char>(bin);
    }
    return;
  }
  vtkNew<vtkMesoElementLookupTable> elements;
  for (int z = 0; z <= mesolens::max_atomic_number && z < element_count; ++z)
  {
    double rgba[4];
    elements->GetTableValue(z, rgba);
    for (int c = 0; c < 4; ++c)
    {
      this->ColorTable[std::size_t(4 * z + c)] = static_cast<float>(rgba[c]);
    }
  }
  for (vtkIdType i = 0; i < n; ++i)
  {
    const std::size_t slot = this->SlotOf(i);
    const auto z = static_cast<unsigned char>(element_of(numbers, i));
    this->ElementPresent[z] = true;
    this->UnmaskedTypes[2 * slot] = z;
    this->UnmaskedTypes[2 * slot + 1] = z;
  }
}

bool vtkMesoAtomGPUData::UpdateBonds(vtkPolyData* atoms, vtkMapper* mapper)
{
  vtkCellArray* lines = atoms->GetLines();
  const ArrayKey key{ lines, lines ? lines->GetMTime() : 0, nullptr, 0, 0, this->AtomCount };
  if (key == this->BondsKey)
  {
    return true;
  }
  this->BondsKey = key;
  ++this->BondsVersion;
  this->Bonds.clear();
  if (!lines)
  {
    return true;
  }
  const vtkIdType n = this->AtomCount;
  auto cells = vtk::TakeSmartPointer(lines->NewIterator());
  for (cells->GoToFirstCell(); !cells->IsDoneWithTraversal(); cells->GoToNextCell())
  {
    vtkIdType size = 0;
    const vtkIdType* ids = nullptr;
    cells->GetCurrentCell(size, ids);
    for (vtkIdType k = 0; k + 1 < size; ++k)
    {
      if (ids[k] < 0 || ids[k] >= n || ids[k + 1] < 0 || ids[k + 1] >= n)
      {
        vtkErrorWithObjectMacro(mapper,
                                "Cannot draw the bonds: line "
                                  << cells->GetCurrentCellId() << " refers to atom "
                                  << std::max(ids[k], ids[k + 1]) << " of " << n);
        return false;
      }
      this->Bonds.push_back(static_cast<unsigned int>(this->SlotOf(ids[k])));
      this->Bonds.push_back(static_cast<unsigned int>(this->SlotOf(ids[k + 1])));
    }
  }
  return true;
}

bool vtkMesoAtomGPUData::ReadWarp(vtkPolyData* atoms, vtkPolyData* warp_data, vtkMapper* mapper)
{
  if (is_assembly(warp_data))
  {
    return this->ReadAssembly(atoms, warp_data, mapper);
  }
  mesolens::MembraneWarp warp;
  if (!vtkMesoMembraneWarp::Read(warp_data->GetFieldData(), warp))
  {
    vtkErrorWithObjectMacro(mapper,
                            "Cannot warp the atoms: the warp input is not the output of "
                            "a vtkMesoMembraneMapping (its patch fields are missing)");
    return false;
  }
  const auto tiles = static_cast<vtkIdType>(warp.tile_count());
  // The mapping's own output has TileId.
  if (atoms->GetPointData()->GetArray(vtkMesoArrayNames::TileId))
  {
    vtkErrorWithObjectMacro(mapper,
                            "Cannot warp the atoms: the mapper's input must be the "
                            "membrane patch that was mapped, not the mapped atoms");
    return false;
  }
  try
  {
    mesolens::check_drawable(warp);
  }
  catch (const mesolens::Error& e)
  {
    vtkErrorWithObjectMacro(mapper, "Cannot warp the atoms: " << e.what());
    return false;
  }
  // The same warp of the same patch (a new mask of its molecules): nothing to read again.
  vtkDataArray* ids = atoms->GetPointData()->GetArray(vtkMesoArrayNames::MoleculeId);
  std::vector<std::pair<const void*, vtkMTimeType>> key{
    { ids, ids ? ids->GetMTime() : 0 },
    { nullptr, this->PositionsVersion },
    { nullptr, this->CellsVersion },
    { nullptr, static_cast<vtkMTimeType>(this->AtomCount) },
  };
  for (vtkAbstractArray* array : vtkMesoMembraneWarp::Arrays(warp_data->GetFieldData()))
  {
    key.emplace_back(array, array ? array->GetMTime() : 0);
  }
  if (key == this->WarpKey && this->WarpMethod != NoWarp)
  {
    return true;
  }
  this->ClearWarp();
  if (!this->ReadPatchMolecules(atoms, warp, mapper))
  {
    return false;
  }
  const double determinant = warp.a[0] * warp.b[1] - warp.a[1] * warp.b[0];
  this->TileCount = tiles;
  this->PatchOrigin[0] = static_cast<float>(warp.origin[0]);
  this->PatchOrigin[1] = static_cast<float>(warp.origin[1]);
  this->PatchToFractional[0] = static_cast<float>(warp.b[1] / determinant);
  this->PatchToFractional[1] = static_cast<float>(-warp.a[1] / determinant);
  this->PatchToFractional[2] = static_cast<float>(-warp.b[0] / determinant);
  this->PatchToFractional[3] = static_cast<float>(warp.a[0] / determinant);
  this->PatchCentreHeight = static_cast<float>(warp.centre_height);
  this->InverseLayerHalfThickness = static_cast<float>(1.0 / warp.layer_half_thickness);

  if (warp.method == mesolens::MappingMethod::Polynomial)
  {
    // A header texel per tile (its first piece, its pieces per side), then 10 per piece.
    const std::vector<std::size_t> first = mesolens::polynomial_first_pieces(warp);
    const auto pieces = static_cast<vtkIdType>(first.back());
    this->TileCountForHeader = static_cast<int>(tiles);
    this->WarpTexels.assign(static_cast<std::size_t>(4 * (tiles + 10 * pieces)), 0.0f);
    for (vtkIdType tile = 0; tile < tiles; ++tile)
    {
      this->WarpTexels[std::size_t(4 * tile)] = static_cast<float>(first[std::size_t(tile)]);
      this->WarpTexels[std::size_t(4 * tile + 1)] = static_cast<float>(
        warp.polynomial_splits.empty() ? 1 : warp.polynomial_splits[std::size_t(tile)]);
    }
    for (vtkIdType piece = 0; piece < pieces; ++piece)
    {
      for (int term = 0; term < 10; ++term)
      {
        for (int d = 0; d < 3; ++d)
        {
          this->WarpTexels[std::size_t(4 * tiles + 40 * piece + 4 * term + d)] = static_cast<float>(
            warp.polynomial_coefficients[std::size_t(30 * piece + 10 * d + term)]);
        }
      }
    }
  }
  else
  {
    this->WarpTexels = motion_texels(warp, std::size_t(tiles * this->MoleculesPerTile));
  }
  this->WarpMethod = static_cast<int>(warp.method);
  ++this->WarpVersion;
  this->Warp = std::move(warp);
  this->WarpKey = std::move(key);
  return this->CarryCellsIntoTiles(mapper);
}

bool vtkMesoAtomGPUData::ReadAssembly(vtkPolyData* atoms, vtkPolyData* copies, vtkMapper* mapper)
{
  // The same copies of the same atoms (a new colour or mask): nothing to read again.
  vtkPointData* data = copies->GetPointData();
  vtkFieldData* fields = copies->GetFieldData();
  std::vector<std::pair<const void*, vtkMTimeType>> key{
    { nullptr, this->PositionsVersion },
    { nullptr, this->CellsVersion },
    { nullptr, static_cast<vtkMTimeType>(this->AtomCount) },
  };
  for (vtkAbstractArray* array :
       { data->GetAbstractArray(vtkMesoArrayNames::AssemblyMatrix),
         data->GetAbstractArray(vtkMesoArrayNames::AssemblyAtomSet),
         fields->GetAbstractArray(vtkMesoArrayNames::AssemblyAtomSetOffsets),
         fields->GetAbstractArray(vtkMesoArrayNames::AssemblyAtomSetAtoms) })
  {
    key.emplace_back(array, array ? array->GetMTime() : 0);
  }
  if (key == this->WarpKey && this->WarpMethod != NoWarp)
  {
    return true;
  }
  this->ClearWarp();
  mesolens::MembraneWarp warp;
  std::vector<unsigned short> class_of_atom;
  std::vector<std::uint32_t> hidden;
  int classes = 0;
  std::string problem;
  if (!assembly_warp(atoms, copies, warp, class_of_atom, classes, hidden, problem))
  {
    vtkErrorWithObjectMacro(mapper, "Cannot draw the assembly: " << problem);
    return false;
  }
  this->AssemblyCopies = true;
  this->TileCount = static_cast<vtkIdType>(warp.tile_count());
  this->MoleculesPerTile = classes;
  this->SetMoleculeSlots(class_of_atom);
  this->WarpTexels = motion_texels(warp, warp.instance_tiles.size());
  // The classes a copy's atom set leaves out are hidden in that copy, as a cutaway hides a
  // mapped membrane's molecules.
  this->MoleculeMask = std::move(hidden);
  ++this->MoleculeMaskVersion;
  this->HiddenInTiles = 0;
  for (std::size_t bit = 0; bit < 32 * this->MoleculeMask.size(); ++bit)
  {
    if (this->MoleculeMask[bit / 32] & (1u << (bit % 32)))
    {
      this->HiddenInTiles += this->MoleculeSizes[bit % std::size_t(classes)];
    }
  }
  this->WarpMethod = static_cast<int>(warp.method);
  ++this->WarpVersion;
  this->Warp = std::move(warp);
  this->WarpKey = std::move(key);
  return this->CarryCellsIntoTiles(mapper);
}

bool vtkMesoAtomGPUData::CarryCellsIntoTiles(vtkMapper* mapper)
{
  if (this->Cells.cell_start.empty())
  {
    return true;
  }
  // Draw-list entries count tile x atoms in 32 bits: beyond, every atom is drawn.
  if (double(this->AtomCount) * double(this->TileCount) >
      double(std::numeric_limits<std::uint32_t>::max()))
  {
    return true;
  }
  try
  {
    // The GPU sums the warp's 10 terms in float: at most about 5 roundings of the largest
    // coordinate.
    this->WarpedAtoms = std::make_unique<mesolens::WarpedCellAtoms>(
      this->Warp, this->Cells, this->CellBoxes,
      mesolens::PointSpan<const float>(this->PositionData, std::size_t(this->AtomCount)),
      this->MoleculeSlots, this->Types, 2, this->Radii, 8 * std::numeric_limits<float>::epsilon(),
      vtkMesoParallelFor::Get());
  }
  catch (const mesolens::Error& e)
  {
    vtkErrorWithObjectMacro(mapper, "Cannot warp the atoms: " << e.what());
    return false;
  }
  return true;
}

bool vtkMesoAtomGPUData::ReadPatchMolecules(vtkPolyData* atoms, const mesolens::MembraneWarp& warp,
                                            vtkMapper* mapper)
{
  std::vector<unsigned short> slot_of_atom;
  if (warp.method == mesolens::MappingMethod::MoleculeInstancing)
  {
    std::string problem;
    if (!molecule_slots(atoms, warp, slot_of_atom, this->MoleculesPerTile, problem))
    {
      vtkErrorWithObjectMacro(mapper, "Cannot warp the atoms: " << problem);
      return false;
    }
  }
  else if (vtkDataArray* ids = atoms->GetPointData()->GetArray(vtkMesoArrayNames::MoleculeId))
  {
    // The molecules in order of first appearance, as the mapping numbers its molecule centres.
    std::vector<int> id_copy;
    const mesolens::MoleculeGroups groups = mesolens::group_molecules(
      vtkMesoIntValues(ids, id_copy), static_cast<std::size_t>(this->AtomCount));
    if (groups.count() > 65536)
    {
      return true; // no masks of its molecules: their slots would not fit 16 bits
    }
    this->MoleculesPerTile = static_cast<int>(groups.count());
    slot_of_atom.resize(groups.of_atom.size());
    for (std::size_t a = 0; a < slot_of_atom.size(); ++a)
    {
      slot_of_atom[a] = static_cast<unsigned short>(groups.of_atom[a]);
    }
  }
  else
  {
    return true; // no molecules
  }
  this->SetMoleculeSlots(slot_of_atom);
  return true;
}

void vtkMesoAtomGPUData::SetMoleculeSlots(const std::vector<unsigned short>& slot_of_atom)
{
  this->PatchMolecules = static_cast<vtkIdType>(this->MoleculesPerTile);
  this->MoleculeSizes.assign(std::size_t(this->MoleculesPerTile), 0);
  this->MoleculeSlots.resize(slot_of_atom.size());
  for (std::size_t atom = 0; atom < slot_of_atom.size(); ++atom)
  {
    this->MoleculeSlots[this->SlotOf(vtkIdType(atom))] = slot_of_atom[atom];
    ++this->MoleculeSizes[slot_of_atom[atom]];
  }
  ++this->MoleculeSlotsVersion;
}

bool vtkMesoAtomGPUData::ReadMoleculeMask(vtkPolyData* warp_data, vtkMapper* mapper,
                                          const char* mask_name)
{
  if (this->AssemblyCopies)
  {
    return true; // the copies' atom sets made the mask
  }
  const vtkIdType points = warp_data->GetNumberOfPoints();
  const vtkIdType expected = this->TileCount * this->PatchMolecules;
  if (points > 0 && points != expected)
  {
    vtkErrorWithObjectMacro(
      mapper,
      "Cannot warp the atoms: the warp input holds "
        << points << " points, not one per molecule and tile of the patch (" << expected
        << "): connect the output 0 of a vtkMesoMembraneMapping that ran with OutputAtoms off "
           "(or a vtkMesoStructuredCutaway of it), and the patch it mapped to the mapper's input");
    return false;
  }
  vtkDataArray* visible = points > 0 && mask_name && *mask_name
    ? warp_data->GetPointData()->GetArray(mask_name)
    : nullptr;
  const ArrayKey key{ visible, visible ? visible->GetMTime() : 0, nullptr, 0, 0, expected };
  if (key == this->MoleculeMaskKey)
  {
    return true;
  }
  this->MoleculeMaskKey = key;
  ++this->MoleculeMaskVersion;
  this->MoleculeMask.clear();
  this->HiddenInTiles = 0;
  if (!visible)
  {
    return true;
  }
  // A bit per molecule and tile, set where it is hidden.
  this->MoleculeMask.assign(static_cast<std::size_t>((expected + 31) / 32), 0u);
  auto* bytes = vtkUnsignedCharArray::FastDownCast(visible);
  for (vtkIdType i = 0; i < expected; ++i)
  {
    if (bytes ? bytes->GetValue(i) == 0 : visible->GetComponent(i, 0) == 0.0)
    {
      this->MoleculeMask[std::size_t(i / 32)] |= 1u << (i % 32);
      this->HiddenInTiles += this->MoleculeSizes[std::size_t(i % this->PatchMolecules)];
    }
  }
  return true;
}

double vtkMesoAtomGPUData::LargestRadius(vtkPolyData* atoms, const Style& style)
{
  const std::vector<float> radii = StyleRadii(style);
  vtkDataArray* numbers =
    atoms ? atoms->GetPointData()->GetArray(vtkMesoArrayNames::AtomicNumber) : nullptr;
  if (!numbers)
  {
    return radii[0];
  }
  std::vector<bool> present(element_count, false);
  for (vtkIdType i = 0; i < numbers->GetNumberOfTuples(); ++i)
  {
    present[std::size_t(element_of(numbers, i))] = true;
  }
  double largest = 0;
  for (int z = 0; z < element_count; ++z)
  {
    if (present[std::size_t(z)])
    {
      largest = std::max(largest, double(radii[std::size_t(z)]));
    }
  }
  return largest;
}

void vtkMesoAtomGPUData::PaddedBounds(vtkPolyData* atoms, vtkPolyData* warp_data, double pad,
                                      double bounds[6])
{
  if (!atoms || atoms->GetNumberOfPoints() == 0)
  {
    return;
  }
  if (warp_data)
  {
    // A warp that cannot be drawn leaves the bounds as they are.
    mesolens::MembraneWarp warp;
    std::vector<unsigned short> assembly_slots;
    int assembly_classes = 0;
    if (is_assembly(warp_data))
    {
      std::vector<std::uint32_t> hidden;
      std::string problem;
      if (!assembly_warp(atoms, warp_data, warp, assembly_slots, assembly_classes, hidden, problem))
      {
        return;
      }
    }
    else if (!vtkMesoMembraneWarp::Read(warp_data->GetFieldData(), warp))
    {
      return;
    }
    try
    {
      mesolens::check_drawable(warp);
    }
    catch (const mesolens::Error&)
    {
      return;
    }
    double warped[6] = { 1e300, -1e300, 1e300, -1e300, 1e300, -1e300 };
    if (warp.method == mesolens::MappingMethod::Polynomial)
    {
      polynomial_bounds(atoms, warp, warped);
    }
    else
    {
      std::vector<unsigned short> slots = std::move(assembly_slots);
      int molecules = assembly_classes;
      std::string problem;
      if (molecules == 0 && !molecule_slots(atoms, warp, slots, molecules, problem))
      {
        return;
      }
      // Each molecule's box, moved by each of its motions.
      std::vector<std::array<double, 6>> boxes(std::size_t(molecules),
                                               { 1e300, -1e300, 1e300, -1e300, 1e300, -1e300 });
      for (vtkIdType a = 0; a < atoms->GetNumberOfPoints(); ++a)
      {
        grow(boxes[slots[std::size_t(a)]].data(), atoms->GetPoint(a));
      }
      for (std::size_t m = 0; m < warp.instance_molecules.size(); ++m)
      {
        const double* matrix = warp.instance_matrices.data() + 16 * m;
        const auto& box = boxes[m % std::size_t(molecules)];
        for (int c = 0; c < 8; ++c)
        {
          const auto p = corner(box.data(), c);
          double x[3];
          for (int r = 0; r < 3; ++r)
          {
            x[r] = matrix[4 * r] * p[0] + matrix[4 * r + 1] * p[1] + matrix[4 * r + 2] * p[2] +
              matrix[4 * r + 3];
          }
          grow(warped, x);
        }
      }
    }
    std::copy(warped, warped + 6, bounds);
  }
  for (int d = 0; d < 3; ++d)
  {
    bounds[2 * d] -= pad;
    bounds[2 * d + 1] += pad;
  }
}
