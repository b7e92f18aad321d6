// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoMembraneMapping.h"

#include "vtkMesoAtomTableConversion.h"

#include "vtkMesoParallelFor.h"
#include "vtkMesoSurfaceConversion.h"

#include "mesolens/elements.h"
#include "mesolens/errors.h"
#include "mesolens/membrane_mapping.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkIdTypeArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <algorithm>
#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkMesoMembraneMapping);

namespace {
/// What the cached disk and its parameterization were built from.
struct ChartKey
{
  vtkMTimeType surface = 0;
  std::array<double, 3> seed{};
  double tolerance = 0;
  double radius = 0;
  int min_triangles = 0;
  int max_levels = 0;
  bool operator==(const ChartKey& o) const
  {
    return surface == o.surface && seed == o.seed && tolerance == o.tolerance &&
      radius == o.radius && min_triangles == o.min_triangles && max_levels == o.max_levels;
  }
};

/// The membrane input as Core sees it, with its own copies of the arrays it points into.
struct PatchData
{
  std::vector<float> positions;
  std::vector<int> molecule_ids;
  std::vector<float> masses;
  std::vector<std::array<std::uint32_t, 2>> bonds;
  mesolens::MembranePatch patch;
  double width = 0; ///< larger cell vector length, membrane units
};

PatchData read_patch(vtkPolyData* atoms)
{
  PatchData data;
  const vtkIdType n = atoms->GetNumberOfPoints();
  if (n == 0)
  {
    throw mesolens::InvalidInput("the membrane input has no atoms");
  }
  data.positions.resize(3 * static_cast<std::size_t>(n));
  double low[2] = { VTK_DOUBLE_MAX, VTK_DOUBLE_MAX };
  double high[2] = { -VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  double height = 0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    atoms->GetPoint(i, p);
    for (int d = 0; d < 3; ++d)
    {
      data.positions[3 * std::size_t(i) + std::size_t(d)] = static_cast<float>(p[d]);
    }
    for (int d = 0; d < 2; ++d)
    {
      low[d] = std::min(low[d], p[d]);
      high[d] = std::max(high[d], p[d]);
    }
    height += p[2] / double(n);
  }
  mesolens::MembranePatch& patch = data.patch;
  patch.positions = data.positions.data();
  patch.atom_count = static_cast<std::size_t>(n);
  patch.centre_height = height;
  vtkDataArray* box = atoms->GetFieldData()->GetArray("PeriodicBoxVectors");
  if (box && box->GetNumberOfComponents() == 9)
  {
    patch.origin = { 0, 0 };
    patch.a = { box->GetComponent(0, 0), box->GetComponent(0, 1) };
    patch.b = { box->GetComponent(0, 3), box->GetComponent(0, 4) };
  }
  else
  {
    // No periodic box: the atoms' x-y extent is the cell.
    patch.origin = { low[0], low[1] };
    patch.a = { high[0] - low[0], 0 };
    patch.b = { 0, high[1] - low[1] };
  }
  data.width = std::max(std::hypot(patch.a[0], patch.a[1]), std::hypot(patch.b[0], patch.b[1]));
  if (vtkDataArray* molecules = atoms->GetPointData()->GetArray("MoleculeId"))
  {
    data.molecule_ids.resize(static_cast<std::size_t>(n));
    for (vtkIdType i = 0; i < n; ++i)
    {
      data.molecule_ids[std::size_t(i)] = static_cast<int>(molecules->GetComponent(i, 0));
    }
    patch.molecule_ids = data.molecule_ids.data();
  }
  if (vtkDataArray* elements = atoms->GetPointData()->GetArray("AtomicNumber"))
  {
    data.masses.resize(static_cast<std::size_t>(n));
    for (vtkIdType i = 0; i < n; ++i)
    {
      data.masses[std::size_t(i)] =
        mesolens::atomic_mass(static_cast<int>(elements->GetComponent(i, 0)));
    }
    patch.masses = data.masses.data();
  }
  auto lines = vtk::TakeSmartPointer(atoms->GetLines()->NewIterator());
  for (lines->GoToFirstCell(); !lines->IsDoneWithTraversal(); lines->GoToNextCell())
  {
    vtkIdType size = 0;
    const vtkIdType* ids = nullptr;
    lines->GetCurrentCell(size, ids);
    for (vtkIdType k = 0; k + 1 < size; ++k)
    {
      data.bonds.push_back({ std::uint32_t(ids[k]), std::uint32_t(ids[k + 1]) });
    }
  }
  return data;
}

void add_field(vtkPolyData* output, const char* name, const std::vector<double>& values,
               int components = 1)
{
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size() / std::size_t(components)));
  std::copy(values.begin(), values.end(), array->GetPointer(0));
  output->GetFieldData()->AddArray(array);
}

/// Output 0: the mapped atoms, bonds and arrays, k^2 copies of the patch.
void build_atoms(vtkPolyData* atoms, const PatchData& data, const mesolens::MappedMembrane& mapped,
                 const std::vector<double>& bond_changes, vtkPolyData* output)
{
  const vtkIdType n = atoms->GetNumberOfPoints();
  const vtkIdType tiles = static_cast<vtkIdType>(mapped.positions.size() / (3 * std::size_t(n)));
  const vtkIdType total = n * tiles;
  vtkNew<vtkDoubleArray> coordinates;
  coordinates->SetNumberOfComponents(3);
  coordinates->SetNumberOfTuples(total);
  std::copy(mapped.positions.begin(), mapped.positions.end(), coordinates->GetPointer(0));
  vtkNew<vtkPoints> points;
  points->SetData(coordinates);
  output->SetPoints(points);

  vtkMesoAtomTableConversion::SetAtomVertices(output);
  const vtkIdType bonds = static_cast<vtkIdType>(data.bonds.size());
  vtkNew<vtkIdTypeArray> line_offsets;
  vtkNew<vtkIdTypeArray> line_ids;
  line_offsets->SetNumberOfValues(bonds * tiles + 1);
  line_ids->SetNumberOfValues(2 * bonds * tiles);
  for (vtkIdType t = 0; t < tiles; ++t)
  {
    for (vtkIdType b = 0; b < bonds; ++b)
    {
      const vtkIdType cell = t * bonds + b;
      line_offsets->SetValue(cell, 2 * cell);
      line_ids->SetValue(2 * cell, t * n + data.bonds[std::size_t(b)][0]);
      line_ids->SetValue(2 * cell + 1, t * n + data.bonds[std::size_t(b)][1]);
    }
  }
  line_offsets->SetValue(bonds * tiles, 2 * bonds * tiles);
  vtkNew<vtkCellArray> lines;
  lines->SetData(line_offsets, line_ids);
  output->SetLines(lines);

  // The patch's point arrays, once per tile, and the tile of every atom.
  vtkPointData* in = atoms->GetPointData();
  vtkPointData* out = output->GetPointData();
  out->CopyAllocate(in, total);
  for (vtkIdType t = 0; t < tiles; ++t)
  {
    for (vtkIdType i = 0; i < n; ++i)
    {
      out->CopyData(in, i, t * n + i);
    }
  }
  vtkNew<vtkIntArray> tile_ids;
  tile_ids->SetName("TileId");
  tile_ids->SetNumberOfValues(total);
  for (vtkIdType i = 0; i < total; ++i)
  {
    tile_ids->SetValue(i, static_cast<int>(i / n));
  }
  out->AddArray(tile_ids);
  if (in->GetArray("AtomicNumber"))
  {
    out->SetActiveScalars("AtomicNumber");
  }
  vtkNew<vtkFloatArray> change;
  change->SetName("BondLengthChange");
  change->SetNumberOfValues(total + bonds * tiles);
  for (vtkIdType i = 0; i < total; ++i)
  {
    change->SetValue(i, 0.0f);
  }
  for (std::size_t i = 0; i < bond_changes.size(); ++i)
  {
    change->SetValue(total + static_cast<vtkIdType>(i), static_cast<float>(bond_changes[i]));
  }
  output->GetCellData()->AddArray(change);
}
} // namespace

struct vtkMesoMembraneMapping::State
{
  vtkMesoSurfaceConversion::GeodesicDiskBuilder Builder;
  bool HasChart = false;
  ChartKey Key;
  mesolens::GeodesicDisk Disk;
  mesolens::DiskParameterization Map;
  std::unique_ptr<mesolens::SurfaceChart> Chart;
  std::array<double, 2> SeedUV{};
};

vtkMesoMembraneMapping::vtkMesoMembraneMapping()
  : Internal(new State)
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(2);
}

vtkMesoMembraneMapping::~vtkMesoMembraneMapping() = default;

int vtkMesoMembraneMapping::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

int vtkMesoMembraneMapping::RequestInformation(vtkInformation*, vtkInformationVector** inputVector,
                                               vtkInformationVector* outputVector)
{
  // The membrane (input 1) may be a trajectory: its time steps are the output's.
  vtkInformation* membrane = inputVector[1]->GetInformationObject(0);
  for (int port = 0; port < 2; ++port)
  {
    vtkInformation* out = outputVector->GetInformationObject(port);
    out->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
    out->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
    if (port == 0 && membrane && membrane->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()))
    {
      out->CopyEntry(membrane, vtkStreamingDemandDrivenPipeline::TIME_STEPS());
      out->CopyEntry(membrane, vtkStreamingDemandDrivenPipeline::TIME_RANGE());
    }
  }
  return 1;
}

int vtkMesoMembraneMapping::RequestData(vtkInformation*, vtkInformationVector** inputVector,
                                        vtkInformationVector* outputVector)
{
  vtkPolyData* surface = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* atoms = vtkPolyData::GetData(inputVector[1]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkPolyData* disk_output = vtkPolyData::GetData(outputVector, 1);
  output->Initialize();
  disk_output->Initialize();
  State& state = *this->Internal;
  try
  {
    if (this->Tiles < 1)
    {
      throw mesolens::InvalidInput("Tiles must be at least 1, got " + std::to_string(this->Tiles));
    }
    if (!(this->MembraneToMeshScale > 0) || !std::isfinite(this->MembraneToMeshScale))
    {
      throw mesolens::InvalidInput("MembraneToMeshScale must be positive");
    }
    if (!surface || !atoms)
    {
      throw mesolens::InvalidInput(
        "both the surface (input 0) and the membrane (input 1) are needed");
    }
    PatchData data = read_patch(atoms);
    const double scale = this->MembraneToMeshScale;
    const double radius = this->RadiusFactor * this->Tiles * data.width * scale;
    ChartKey key;
    key.surface = surface->GetMTime();
    key.seed = { this->SeedPoint[0], this->SeedPoint[1], this->SeedPoint[2] };
    key.tolerance = this->SeedTolerance;
    key.radius = radius;
    key.min_triangles = this->MinimumDiskTriangles;
    key.max_levels = this->MaximumRefinementLevels;
    if (!state.HasChart || !(state.Key == key))
    {
      state.HasChart = false;
      state.Builder.SetSurface(surface, key.surface);
      this->UpdateProgress(0.2);
      mesolens::GeodesicDiskParams params;
      params.radius = radius;
      params.min_triangles = static_cast<std::size_t>(this->MinimumDiskTriangles);
      params.max_refinement_levels = this->MaximumRefinementLevels;
      state.Disk = state.Builder.Disk(this->SeedPoint, this->SeedTolerance, params);
      this->UpdateProgress(0.4);
      state.Map = mesolens::harmonic_parameterization(state.Disk.mesh, radius);
      state.Chart = std::make_unique<mesolens::SurfaceChart>(state.Disk.mesh, state.Map.uv);
      state.SeedUV = state.Chart->uv_of(state.Disk.seed);
      state.Key = key;
      state.HasChart = true;
    }
    this->UpdateProgress(0.6);
    mesolens::MappingParams params;
    params.method = static_cast<mesolens::MappingMethod>(this->MappingMethod);
    params.tiles = this->Tiles;
    params.scale = scale;
    params.centre_uv = state.SeedUV;
    params.layer_half_thickness = this->LayerHalfThickness;
    params.samples = this->PolynomialSamples;
    params.map_atoms = this->OutputAtoms;
    const mesolens::MappedMembrane mapped =
      mesolens::map_membrane(*state.Chart, data.patch, params, vtkMesoParallelFor::Get());
    const std::vector<double> changes =
      mesolens::bond_length_changes(data.patch, mapped, data.bonds, scale);
    if (!mapped.positions.empty())
    {
      build_atoms(atoms, data, mapped, changes, output);
    }
    const mesolens::MembranePatch& patch = data.patch;
    add_field(output, "GeodesicRadius", { radius });
    add_field(output, "Tiles", { double(this->Tiles) });
    add_field(output, "MappingMethod", { double(this->MappingMethod) });
    add_field(output, "MembraneToMeshScale", { scale });
    add_field(output, "PatchOrigin", { patch.origin[0], patch.origin[1] }, 2);
    add_field(output, "PatchCellA", { patch.a[0], patch.a[1] }, 2);
    add_field(output, "PatchCellB", { patch.b[0], patch.b[1] }, 2);
    add_field(output, "PatchCentreHeight", { patch.centre_height });
    add_field(output, "LayerHalfThickness", { this->LayerHalfThickness });
    add_field(output, "SeedUV", { state.SeedUV[0], state.SeedUV[1] }, 2);
    add_field(output, "RefinementLevels", { double(state.Disk.refinement_levels) });
    if (!mapped.polynomial_coefficients.empty())
    {
      add_field(output, "PolynomialCoefficients", mapped.polynomial_coefficients, 30);
      add_field(output, "PolynomialResidualRMS", mapped.polynomial_rms_residual);
      add_field(output, "PolynomialResidualMax", mapped.polynomial_max_residual);
    }
    if (!mapped.instance_matrices.empty())
    {
      add_field(output, "InstanceMatrices", mapped.instance_matrices, 16);
      add_field(
        output, "InstanceMoleculeId",
        std::vector<double>(mapped.instance_molecules.begin(), mapped.instance_molecules.end()));
      add_field(output, "InstanceTileId",
                std::vector<double>(mapped.instance_tiles.begin(), mapped.instance_tiles.end()));
    }
    if (atoms->GetInformation()->Has(vtkDataObject::DATA_TIME_STEP()))
    {
      output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(),
                                    atoms->GetInformation()->Get(vtkDataObject::DATA_TIME_STEP()));
    }
    vtkMesoSurfaceConversion::FromTriangleMesh(state.Disk.mesh, disk_output);
    vtkMesoSurfaceConversion::AddDiskArrays(state.Disk, radius, disk_output);
    vtkMesoSurfaceConversion::AddParameterizationArrays(state.Map, radius, disk_output);
  }
  catch (const mesolens::Error& e)
  {
    vtkErrorMacro("Cannot map the membrane: " << e.what());
    output->Initialize();
    disk_output->Initialize();
    state.HasChart = false;
    return 0;
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkMesoMembraneMapping::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  static const char* methods[] = { "DISPLACEMENT", "MOLECULE_INSTANCING", "POLYNOMIAL" };
  os << indent << "MappingMethod: " << methods[this->MappingMethod] << "\n";
  os << indent << "SeedPoint: (" << this->SeedPoint[0] << ", " << this->SeedPoint[1] << ", "
     << this->SeedPoint[2] << ")\n";
  os << indent << "SeedTolerance: " << this->SeedTolerance << "\n";
  os << indent << "Tiles: " << this->Tiles << "\n";
  os << indent << "MembraneToMeshScale: " << this->MembraneToMeshScale << "\n";
  os << indent << "RadiusFactor: " << this->RadiusFactor << "\n";
  os << indent << "LayerHalfThickness: " << this->LayerHalfThickness << "\n";
  os << indent << "PolynomialSamples: " << this->PolynomialSamples << "\n";
  os << indent << "MinimumDiskTriangles: " << this->MinimumDiskTriangles << "\n";
  os << indent << "MaximumRefinementLevels: " << this->MaximumRefinementLevels << "\n";
  os << indent << "OutputAtoms: " << (this->OutputAtoms ? "on" : "off") << "\n";
}
