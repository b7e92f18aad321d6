// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoMembraneWarp.h"

#include "vtkMesoArrayNames.h"

#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkStringArray.h>

#include <algorithm>
#include <vector>

namespace names = vtkMesoArrayNames;

namespace {
template<typename Values>
void add(vtkFieldData* fields, const char* name, const Values& values, int components = 1)
{
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size() / std::size_t(components)));
  std::copy(values.begin(), values.end(), array->GetPointer(0));
  fields->AddArray(array);
}

void add(vtkFieldData* fields, const char* name, double value)
{
  add(fields, name, std::vector<double>{ value });
}

/// The first tuple of a `components`-component array, or nullptr.
const double* tuple(vtkFieldData* fields, const char* name, int components)
{
  vtkDataArray* array = fields->GetArray(name);
  if (!array || array->GetNumberOfComponents() != components || array->GetNumberOfTuples() < 1)
  {
    return nullptr;
  }
  return array->GetTuple(0);
}

/// Every value of an array with `components` components (empty when absent or shaped
/// otherwise), converted to T.
template<typename T>
std::vector<T> values(vtkFieldData* fields, const char* name, int components = 1)
{
  vtkDataArray* array = fields->GetArray(name);
  std::vector<T> result;
  if (!array || array->GetNumberOfComponents() != components)
  {
    return result;
  }
  const vtkIdType count = array->GetNumberOfTuples() * components;
  if (auto* doubles = vtkDoubleArray::FastDownCast(array)) // as Write() writes them
  {
    const double* first = doubles->GetPointer(0);
    result.reserve(static_cast<std::size_t>(count));
    for (vtkIdType i = 0; i < count; ++i)
    {
      result.push_back(static_cast<T>(first[i]));
    }
    return result;
  }
  result.resize(static_cast<std::size_t>(count));
  for (vtkIdType i = 0; i < count; ++i)
  {
    result[std::size_t(i)] =
      static_cast<T>(array->GetComponent(i / components, int(i % components)));
  }
  return result;
}
} // namespace

void vtkMesoMembraneWarp::Write(const mesolens::MembraneWarp& warp, vtkFieldData* fields)
{
  add(fields, names::GeodesicRadius, warp.geodesic_radius);
  add(fields, names::Tiles, double(warp.tiles));
  add(fields, names::TilesRequested, double(warp.tiles_requested));
  add(fields, names::TilesMapped, double(warp.tiles));
  add(fields, names::CutToDisk, warp.cut_to_disk ? 1.0 : 0.0);
  vtkNew<vtkStringArray> note;
  note->SetName(names::MappingNote);
  note->InsertNextValue(warp.note);
  fields->AddArray(note);
  add(fields, names::MappingMethod, double(static_cast<int>(warp.method)));
  add(fields, names::MembraneToMeshScale, warp.scale);
  add(fields, names::PatchOrigin, warp.origin, 2);
  add(fields, names::PatchCellA, warp.a, 2);
  add(fields, names::PatchCellB, warp.b, 2);
  add(fields, names::PatchCentreHeight, warp.centre_height);
  add(fields, names::LayerHalfThickness, warp.layer_half_thickness);
  add(fields, names::SeedUV, warp.seed_uv, 2);
  add(fields, names::SeedNormal, warp.seed_normal, 3);
  add(fields, names::RefinementLevels, double(warp.refinement_levels));
  if (!warp.polynomial_coefficients.empty())
  {
    add(fields, names::PolynomialCoefficients, warp.polynomial_coefficients, 30);
    add(fields, names::PolynomialSplits, warp.polynomial_splits);
    add(fields, names::PolynomialResidualRMS, warp.polynomial_rms_residual);
    add(fields, names::PolynomialResidualMax, warp.polynomial_max_residual);
    add(fields, names::PolynomialFallbackTiles, warp.tile_fallback);
  }
  if (!warp.instance_matrices.empty())
  {
    add(fields, names::InstanceMatrices, warp.instance_matrices, 16);
    add(fields, names::InstanceMoleculeId, warp.instance_molecules);
    add(fields, names::InstanceTileId, warp.instance_tiles);
  }
}

bool vtkMesoMembraneWarp::Read(vtkFieldData* fields, mesolens::MembraneWarp& warp)
{
  if (!fields)
  {
    return false;
  }
  const double* origin = tuple(fields, names::PatchOrigin, 2);
  const double* a = tuple(fields, names::PatchCellA, 2);
  const double* b = tuple(fields, names::PatchCellB, 2);
  const double* centre = tuple(fields, names::PatchCentreHeight, 1);
  const double* half_thickness = tuple(fields, names::LayerHalfThickness, 1);
  const double* tiles = tuple(fields, names::Tiles, 1);
  const double* method = tuple(fields, names::MappingMethod, 1);
  if (!origin || !a || !b || !centre || !half_thickness || !tiles || !method)
  {
    return false;
  }
  warp = {};
  warp.method = static_cast<mesolens::MappingMethod>(static_cast<int>(*method));
  warp.tiles = static_cast<int>(*tiles);
  warp.origin = { origin[0], origin[1] };
  warp.a = { a[0], a[1] };
  warp.b = { b[0], b[1] };
  warp.centre_height = *centre;
  warp.layer_half_thickness = *half_thickness;
  if (const double* requested = tuple(fields, names::TilesRequested, 1))
  {
    warp.tiles_requested = static_cast<int>(*requested);
  }
  if (const double* cut = tuple(fields, names::CutToDisk, 1))
  {
    warp.cut_to_disk = *cut != 0;
  }
  if (auto* note = vtkStringArray::SafeDownCast(fields->GetAbstractArray(names::MappingNote)))
  {
    warp.note = note->GetNumberOfValues() > 0 ? note->GetValue(0) : std::string();
  }
  if (const double* scale = tuple(fields, names::MembraneToMeshScale, 1))
  {
    warp.scale = *scale;
  }
  if (const double* radius = tuple(fields, names::GeodesicRadius, 1))
  {
    warp.geodesic_radius = *radius;
  }
  if (const double* seed = tuple(fields, names::SeedUV, 2))
  {
    warp.seed_uv = { seed[0], seed[1] };
  }
  if (const double* normal = tuple(fields, names::SeedNormal, 3))
  {
    warp.seed_normal = { normal[0], normal[1], normal[2] };
  }
  if (const double* levels = tuple(fields, names::RefinementLevels, 1))
  {
    warp.refinement_levels = static_cast<int>(*levels);
  }
  warp.polynomial_coefficients = values<double>(fields, names::PolynomialCoefficients, 30);
  warp.polynomial_splits = values<int>(fields, names::PolynomialSplits);
  warp.polynomial_rms_residual = values<double>(fields, names::PolynomialResidualRMS);
  warp.polynomial_max_residual = values<double>(fields, names::PolynomialResidualMax);
  warp.tile_fallback = values<std::uint8_t>(fields, names::PolynomialFallbackTiles);
  warp.instance_matrices = values<double>(fields, names::InstanceMatrices, 16);
  warp.instance_molecules = values<int>(fields, names::InstanceMoleculeId);
  warp.instance_tiles = values<int>(fields, names::InstanceTileId);
  return true;
}

std::vector<vtkAbstractArray*> vtkMesoMembraneWarp::Arrays(vtkFieldData* fields)
{
  static const char* const warp_names[] = {
    names::MappingMethod,
    names::Tiles,
    names::TilesRequested,
    names::TilesMapped,
    names::CutToDisk,
    names::MappingNote,
    names::MembraneToMeshScale,
    names::PatchOrigin,
    names::PatchCellA,
    names::PatchCellB,
    names::PatchCentreHeight,
    names::LayerHalfThickness,
    names::GeodesicRadius,
    names::SeedUV,
    names::SeedNormal,
    names::RefinementLevels,
    names::PolynomialCoefficients,
    names::PolynomialSplits,
    names::PolynomialResidualRMS,
    names::PolynomialResidualMax,
    names::PolynomialFallbackTiles,
    names::InstanceMatrices,
    names::InstanceMoleculeId,
    names::InstanceTileId,
  };
  std::vector<vtkAbstractArray*> arrays;
  for (const char* name : warp_names)
  {
    arrays.push_back(fields ? fields->GetAbstractArray(name) : nullptr);
  }
  return arrays;
}
