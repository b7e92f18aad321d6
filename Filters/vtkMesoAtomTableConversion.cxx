// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoAtomTableConversion.h"

#include "vtkMesoArrayNames.h"
#include "vtkMesoParallelFor.h"

#include "mesolens/molecules/atom_table.h"
#include "mesolens/molecules/elements.h"

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkIdList.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkSignedCharArray.h>
#include <vtkStringArray.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnsignedShortArray.h>

#include <algorithm>
#include <array>
#include <functional>
#include <cstring>
#include <numeric>
#include <type_traits>

namespace vtkMesoAtomTableConversion {

namespace {
template<typename ArrayT, typename ValueT>
void add_array(vtkPointData* data, const char* name, const std::vector<ValueT>& values)
{
  vtkNew<ArrayT> array;
  array->SetName(name);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    array->SetValue(static_cast<vtkIdType>(i), values[i]);
  }
  data->AddArray(array);
}

/// A string array of `count` values, `text_of(i)` each, written in place (SetValue would mark
/// the array changed once per value).
template<typename TextOf>
vtkSmartPointer<vtkStringArray> string_array(const char* name, std::size_t count,
                                             const TextOf& text_of)
{
  auto array = vtkSmartPointer<vtkStringArray>::New();
  array->SetName(name);
  array->SetNumberOfValues(static_cast<vtkIdType>(count));
  vtkStdString* values = array->GetPointer(0);
  for (std::size_t i = 0; i < count; ++i)
  {
    values[i] = text_of(i);
  }
  array->DataChanged();
  return array;
}

/// One-letter codes as strings; blank and NUL give the empty string.
vtkSmartPointer<vtkStringArray> code_array(const char* name, const std::vector<char>& codes)
{
  return string_array(name, codes.size(), [&codes](std::size_t i) {
    const char code = codes[i];
    return code != ' ' && code != '\0' ? std::string(1, code) : std::string();
  });
}

/// The per-atom text arrays of `table`, in the order ToPolyData adds them. They are built
/// concurrently, one array per task: for a protein they take most of the conversion's time
/// (32 bytes per atom and array, each constructed, written and later destroyed).
std::array<vtkSmartPointer<vtkStringArray>, 6> text_arrays(const mesolens::AtomTable& table)
{
  const auto names = [&](const char* name, const std::vector<std::string>& values) {
    return string_array(name, values.size(),
                        [&values](std::size_t i) -> const std::string& { return values[i]; });
  };
  const std::array<std::function<vtkSmartPointer<vtkStringArray>()>, 6> builders = {
    [&] { return names(vtkMesoArrayNames::AtomName, table.atom_names); },
    [&] {
      return string_array(vtkMesoArrayNames::Element, table.size(), [&table](std::size_t i) {
        return mesolens::element_symbol(table.atomic_numbers[i]);
      });
    },
    [&] { return names(vtkMesoArrayNames::ResidueName, table.residue_names); },
    [&] { return code_array(vtkMesoArrayNames::InsertionCode, table.insertion_codes); },
    [&] { return names(vtkMesoArrayNames::ChainId, table.chain_ids); },
    [&] { return code_array(vtkMesoArrayNames::AltLoc, table.alt_locs); },
  };
  std::array<vtkSmartPointer<vtkStringArray>, 6> arrays;
  mesolens::run_parallel(vtkMesoParallelFor::Get(), builders.size(),
                         [&](std::size_t begin, std::size_t end) {
                           for (std::size_t a = begin; a < end; ++a)
                           {
                             arrays[a] = builders[a]();
                           }
                         });
  return arrays;
}
} // namespace

void SetAtomVertices(vtkPolyData* output)
{
  const vtkIdType n = output->GetNumberOfPoints();
  vtkNew<vtkIdTypeArray> offsets;
  vtkNew<vtkIdTypeArray> ids;
  offsets->SetNumberOfValues(n + 1);
  ids->SetNumberOfValues(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    offsets->SetValue(i, i);
    ids->SetValue(i, i);
  }
  offsets->SetValue(n, n);
  vtkNew<vtkCellArray> vertices;
  vertices->SetData(offsets, ids);
  output->SetVerts(vertices);
}

void ToPolyData(const mesolens::AtomTable& table, double length_scale, vtkPolyData* output)
{
  output->Initialize();
  const vtkIdType n = static_cast<vtkIdType>(table.size());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  output->SetPoints(points);
  SetPositions(table.positions, {}, length_scale, output);

  SetAtomVertices(output);

  const vtkIdType bond_count = static_cast<vtkIdType>(table.bonds.size());
  vtkNew<vtkIdTypeArray> line_offsets;
  vtkNew<vtkIdTypeArray> line_ids;
  line_offsets->SetNumberOfValues(bond_count + 1);
  line_ids->SetNumberOfValues(2 * bond_count);
  for (vtkIdType b = 0; b < bond_count; ++b)
  {
    line_offsets->SetValue(b, 2 * b);
    line_ids->SetValue(2 * b, table.bonds[std::size_t(b)].first);
    line_ids->SetValue(2 * b + 1, table.bonds[std::size_t(b)].second);
  }
  line_offsets->SetValue(bond_count, 2 * bond_count);
  vtkNew<vtkCellArray> lines;
  lines->SetData(line_offsets, line_ids);
  output->SetLines(lines);

  vtkPointData* data = output->GetPointData();
  const auto texts = text_arrays(table);
  data->AddArray(texts[0]); // atom names
  data->AddArray(texts[1]); // elements
  // Not unsigned char: VTK would take an unsigned char active scalar for colours, not values.
  add_array<vtkUnsignedShortArray>(data, vtkMesoArrayNames::AtomicNumber, table.atomic_numbers);
  data->AddArray(texts[2]); // residue names
  add_array<vtkIntArray>(data, vtkMesoArrayNames::ResidueNumber, table.residue_numbers);
  data->AddArray(texts[3]); // insertion codes
  data->AddArray(texts[4]); // chain ids
  data->AddArray(texts[5]); // alternate locations
  add_array<vtkFloatArray>(data, vtkMesoArrayNames::Occupancy, table.occupancies);
  add_array<vtkFloatArray>(data, vtkMesoArrayNames::BFactor, table.b_factors);
  add_array<vtkUnsignedCharArray>(data, vtkMesoArrayNames::IsHetAtm, table.is_hetero);
  add_array<vtkIntArray>(data, vtkMesoArrayNames::SerialNumber, table.serials);
  add_array<vtkSignedCharArray>(data, vtkMesoArrayNames::FormalCharge, table.formal_charges);
  add_array<vtkUnsignedCharArray>(data, vtkMesoArrayNames::SecondaryStructure,
                                  table.secondary_structure);
  add_array<vtkIntArray>(data, vtkMesoArrayNames::SecondaryStructureId,
                         table.secondary_structure_ids);
  add_array<vtkIntArray>(data, vtkMesoArrayNames::ResidueIndex, table.residue_indices);
  add_array<vtkIntArray>(data, vtkMesoArrayNames::MoleculeId, table.molecule_ids);
  data->SetActiveScalars(vtkMesoArrayNames::AtomicNumber);
  SetPeriodicBox(table.box, length_scale, output);
}

std::string MissingArrayMessage(const std::string& missing)
{
  return "The atoms have no `" + missing + "` point array: read them with a MesoLens reader.";
}

bool FromPolyData(vtkPolyData* atoms, double length_scale, mesolens::AtomTable& table,
                  std::string* missing)
{
  table = mesolens::AtomTable();
  vtkPointData* data = atoms ? atoms->GetPointData() : nullptr;
  auto* names = data
    ? vtkStringArray::SafeDownCast(data->GetAbstractArray(vtkMesoArrayNames::AtomName))
    : nullptr;
  vtkDataArray* residues = data ? data->GetArray(vtkMesoArrayNames::ResidueIndex) : nullptr;
  if (!names || !residues)
  {
    if (missing)
    {
      *missing = !names ? "AtomName" : "ResidueIndex";
    }
    return false;
  }
  const vtkIdType n = atoms->GetNumberOfPoints();
  const std::size_t count = static_cast<std::size_t>(n);
  table.positions.resize(3 * count);
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    atoms->GetPoint(i, p);
    for (int d = 0; d < 3; ++d)
    {
      table.positions[std::size_t(3 * i + d)] = static_cast<float>(p[d] / length_scale);
    }
  }
  auto strings = [&](const char* name, std::vector<std::string>& values) {
    auto* array = vtkStringArray::SafeDownCast(data->GetAbstractArray(name));
    values.assign(count, std::string());
    for (vtkIdType i = 0; array && i < n && i < array->GetNumberOfValues(); ++i)
    {
      values[std::size_t(i)] = array->GetValue(i);
    }
  };
  auto numbers = [&](const char* name, auto& values, auto fallback) {
    vtkDataArray* array = data->GetArray(name);
    values.assign(count, fallback);
    for (vtkIdType i = 0; array && i < n && i < array->GetNumberOfTuples(); ++i)
    {
      values[std::size_t(i)] =
        static_cast<std::decay_t<decltype(fallback)>>(array->GetComponent(i, 0));
    }
  };
  strings(vtkMesoArrayNames::AtomName, table.atom_names);
  strings(vtkMesoArrayNames::ResidueName, table.residue_names);
  strings(vtkMesoArrayNames::ChainId, table.chain_ids);
  table.label_asym_ids.assign(count, std::string());
  std::vector<std::string> alternates;
  strings(vtkMesoArrayNames::AltLoc, alternates);
  table.alt_locs.assign(count, ' ');
  for (std::size_t i = 0; i < count; ++i)
  {
    table.alt_locs[i] = alternates[i].empty() ? ' ' : alternates[i][0];
  }
  std::vector<std::string> insertion_codes;
  strings(vtkMesoArrayNames::InsertionCode, insertion_codes);
  table.insertion_codes.assign(count, ' ');
  for (std::size_t i = 0; i < count; ++i)
  {
    table.insertion_codes[i] = insertion_codes[i].empty() ? ' ' : insertion_codes[i][0];
  }
  numbers(vtkMesoArrayNames::ResidueIndex, table.residue_indices, 0);
  numbers(vtkMesoArrayNames::MoleculeId, table.molecule_ids, 0);
  numbers(vtkMesoArrayNames::ResidueNumber, table.residue_numbers, 0);
  numbers(vtkMesoArrayNames::Occupancy, table.occupancies, 1.0f);
  numbers(vtkMesoArrayNames::AtomicNumber, table.atomic_numbers, std::uint8_t(0));
  numbers(vtkMesoArrayNames::SecondaryStructure, table.secondary_structure, std::uint8_t(0));
  numbers(vtkMesoArrayNames::SecondaryStructureId, table.secondary_structure_ids, -1);
  numbers(vtkMesoArrayNames::BFactor, table.b_factors, 0.0f);
  numbers(vtkMesoArrayNames::IsHetAtm, table.is_hetero, std::uint8_t(0));
  numbers(vtkMesoArrayNames::SerialNumber, table.serials, 0);
  numbers(vtkMesoArrayNames::FormalCharge, table.formal_charges, std::int8_t(0));
  return true;
}

void SetPositions(const std::vector<float>& positions, const std::vector<std::size_t>& kept,
                  double length_scale, vtkPolyData* output)
{
  const std::size_t n = kept.empty() ? positions.size() / 3 : kept.size();
  vtkPoints* points = output->GetPoints();
  points->SetNumberOfPoints(static_cast<vtkIdType>(n));
  auto* coordinates = vtkFloatArray::SafeDownCast(points->GetData());
  float* out = coordinates->GetPointer(0);
  const float scale = static_cast<float>(length_scale);
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::size_t source = kept.empty() ? i : kept[i];
    for (int k = 0; k < 3; ++k)
    {
      out[3 * i + std::size_t(k)] = positions[3 * source + std::size_t(k)] * scale;
    }
  }
  points->Modified();
}

void SetPeriodicBox(const mesolens::PeriodicBox& box, double length_scale, vtkPolyData* output)
{
  vtkFieldData* field = output->GetFieldData();
  field->RemoveArray(vtkMesoArrayNames::PeriodicBoxVectors);
  if (!box.is_set())
  {
    return;
  }
  vtkNew<vtkDoubleArray> vectors;
  vectors->SetName(vtkMesoArrayNames::PeriodicBoxVectors);
  vectors->SetNumberOfComponents(9);
  vectors->SetNumberOfTuples(1);
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      vectors->SetComponent(0, 3 * r + c,
                            box.vectors[std::size_t(r)][std::size_t(c)] * length_scale);
    }
  }
  field->AddArray(vectors);
}

void SetFieldValue(vtkPolyData* output, const char* name, double value)
{
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->InsertNextValue(value);
  output->GetFieldData()->RemoveArray(name);
  output->GetFieldData()->AddArray(array);
}

void GatherAtomArrays(vtkPointData* atoms, vtkIdList* from, vtkPointData* out,
                      std::initializer_list<const char*> skip)
{
  const vtkIdType count = from->GetNumberOfIds();
  for (int a = 0; a < atoms->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = atoms->GetArray(a);
    const char* name = array ? array->GetName() : nullptr;
    if (!array || !name ||
        std::any_of(skip.begin(), skip.end(), [&](const char* s) { return !std::strcmp(name, s); }))
    {
      continue;
    }
    vtkSmartPointer<vtkDataArray> gathered = vtk::TakeSmartPointer(array->NewInstance());
    gathered->SetName(name);
    gathered->SetNumberOfComponents(array->GetNumberOfComponents());
    gathered->SetNumberOfTuples(count);
    if (array->HasStandardMemoryLayout())
    {
      // Tuples as bytes: VTK's generic InsertTuples goes value by value through virtual calls
      // where its dispatch does not cover the array type (ParaView's VTK), 5x slower.
      const std::size_t bytes =
        std::size_t(array->GetDataTypeSize()) * std::size_t(array->GetNumberOfComponents());
      const auto* source = static_cast<const unsigned char*>(array->GetVoidPointer(0));
      auto* target = static_cast<unsigned char*>(gathered->GetVoidPointer(0));
      for (vtkIdType v = 0; v < count; ++v)
      {
        std::memcpy(target + std::size_t(v) * bytes, source + std::size_t(from->GetId(v)) * bytes,
                    bytes);
      }
    }
    else
    {
      vtkNew<vtkIdList> to; // rows 0, 1, ... of the gathered array
      to->SetNumberOfIds(count);
      std::iota(to->begin(), to->end(), vtkIdType(0));
      gathered->InsertTuples(to, from, array);
    }
    out->AddArray(gathered);
  }
}

bool AtomSpheres(vtkPolyData* atoms, const char* radius_array, double bead_radius,
                 std::vector<std::array<double, 3>>& centres, std::vector<double>& radii,
                 std::string& error)
{
  const vtkIdType n = atoms->GetNumberOfPoints();
  vtkDataArray* given = nullptr;
  if (radius_array && *radius_array)
  {
    given = atoms->GetPointData()->GetArray(radius_array);
    if (!given)
    {
      error = std::string("The atoms have no point array `") + radius_array + "` of radii.";
      return false;
    }
  }
  vtkDataArray* elements = atoms->GetPointData()->GetArray(vtkMesoArrayNames::AtomicNumber);
  centres.resize(static_cast<std::size_t>(n));
  radii.resize(static_cast<std::size_t>(n));
  for (vtkIdType a = 0; a < n; ++a)
  {
    double p[3];
    atoms->GetPoint(a, p);
    centres[std::size_t(a)] = { p[0], p[1], p[2] };
    double radius = bead_radius;
    if (given)
    {
      radius = given->GetComponent(a, 0);
    }
    else if (elements)
    {
      const int z = static_cast<int>(elements->GetComponent(a, 0));
      if (z > 0 && z <= mesolens::max_atomic_number)
      {
        radius = mesolens::van_der_waals_radius(z);
      }
    }
    radii[std::size_t(a)] = radius;
  }
  return true;
}

void SetFieldString(vtkPolyData* output, const char* name, const std::string& value)
{
  vtkNew<vtkStringArray> array;
  array->SetName(name);
  array->InsertNextValue(value);
  output->GetFieldData()->RemoveArray(name);
  output->GetFieldData()->AddArray(array);
}

}
