// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoMembraneMapping.h"

#include "vtkMesoArrayNames.h"
#include "vtkMesoAtomPieces.h"
#include "vtkMesoAtomTableConversion.h"
#include "vtkMesoMembraneWarp.h"

#include "vtkMesoParallelFor.h"
#include "vtkMesoStamp.h"
#include "vtkMesoSurfaceConversion.h"

#include "mesolens/molecules/elements.h"
#include "mesolens/common/errors.h"
#include "mesolens/mapping/chart_lattice.h"
#include "mesolens/mapping/membrane_mapper.h"
#include "mesolens/mapping/membrane_warp.h"
#include "mesolens/molecules/molecule_groups.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkSmartPointer.h>
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
#include <string>
#include <tuple>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkMesoMembraneMapping);

namespace {
/// The membrane input as Core sees it, with its own copies of the arrays it points into.
struct PatchData
{
  std::vector<float> positions;
  std::vector<int> molecule_ids;
  std::vector<float> masses;
  std::vector<std::array<std::uint32_t, 2>> bonds;
  mesolens::MembranePatch patch;
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
  patch.positions = data.positions;
  patch.centre_height = height;
  vtkDataArray* box = atoms->GetFieldData()->GetArray(vtkMesoArrayNames::PeriodicBoxVectors);
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
  if (vtkDataArray* molecules = atoms->GetPointData()->GetArray(vtkMesoArrayNames::MoleculeId))
  {
    data.molecule_ids.resize(static_cast<std::size_t>(n));
    for (vtkIdType i = 0; i < n; ++i)
    {
      data.molecule_ids[std::size_t(i)] = static_cast<int>(molecules->GetComponent(i, 0));
    }
    patch.molecule_ids = data.molecule_ids.data();
  }
  if (vtkDataArray* elements = atoms->GetPointData()->GetArray(vtkMesoArrayNames::AtomicNumber))
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

/// Output index of every copied atom (tile-major), -1 where a cut tile dropped it; and the count
/// kept.
std::vector<vtkIdType> kept_atoms(const mesolens::MappedMembrane& mapped, vtkIdType copies,
                                  vtkIdType& total)
{
  std::vector<vtkIdType> kept(static_cast<std::size_t>(copies));
  total = 0;
  for (vtkIdType i = 0; i < copies; ++i)
  {
    const bool mapped_here = mapped.atom_mapped.empty() || mapped.atom_mapped[std::size_t(i)];
    kept[std::size_t(i)] = mapped_here ? total++ : -1;
  }
  return kept;
}

/// The mapped atoms' point arrays: the patch's, once per tile, with TileId, and MoleculeId made
/// unique over the tiles (tile t's molecule m becomes t (largest id + 1) + m), t counted over
/// every process's tiles. Kept, the same
/// array objects, while the patch's arrays, the tiles and the kept atoms stay: a new frame then
/// changes only the positions, and what groups atoms by their arrays downstream (the cutaway)
/// keeps its work.
struct TileArrays
{
  std::vector<vtkMesoStamp> From;
  std::vector<vtkIdType> Kept;
  vtkIdType FirstTile = 0;
  vtkSmartPointer<vtkPointData> Arrays;

  vtkPointData* For(vtkPolyData* atoms, const PatchData& data, const std::vector<vtkIdType>& kept,
                    vtkIdType total, vtkIdType first_tile)
  {
    vtkPointData* in = atoms->GetPointData();
    std::vector<vtkMesoStamp> from;
    for (int a = 0; a < in->GetNumberOfArrays(); ++a)
    {
      from.push_back(vtkMesoStamp::Of(in->GetAbstractArray(a)));
    }
    if (this->Arrays && from == this->From && kept == this->Kept && first_tile == this->FirstTile)
    {
      return this->Arrays;
    }
    const vtkIdType n = atoms->GetNumberOfPoints();
    const auto copies = static_cast<vtkIdType>(kept.size());
    this->Arrays = vtkSmartPointer<vtkPointData>::New();
    vtkPointData* out = this->Arrays;
    out->CopyAllocate(in, total);
    vtkNew<vtkIntArray> tile_ids;
    tile_ids->SetName(vtkMesoArrayNames::TileId);
    tile_ids->SetNumberOfValues(total);
    for (vtkIdType i = 0; i < copies; ++i)
    {
      if (kept[std::size_t(i)] >= 0)
      {
        out->CopyData(in, i % n, kept[std::size_t(i)]);
        tile_ids->SetValue(kept[std::size_t(i)], static_cast<int>(first_tile + i / n));
      }
    }
    out->AddArray(tile_ids);
    if (!data.molecule_ids.empty())
    {
      const int stride = *std::max_element(data.molecule_ids.begin(), data.molecule_ids.end()) + 1;
      vtkNew<vtkIntArray> molecules;
      molecules->SetName(vtkMesoArrayNames::MoleculeId);
      molecules->SetNumberOfValues(total);
      for (vtkIdType i = 0; i < copies; ++i)
      {
        if (kept[std::size_t(i)] >= 0)
        {
          molecules->SetValue(kept[std::size_t(i)],
                              static_cast<int>(first_tile + i / n) * stride +
                                data.molecule_ids[std::size_t(i % n)]);
        }
      }
      out->RemoveArray(vtkMesoArrayNames::MoleculeId);
      out->AddArray(molecules);
    }
    if (in->GetArray(vtkMesoArrayNames::AtomicNumber))
    {
      out->SetActiveScalars(vtkMesoArrayNames::AtomicNumber);
    }
    this->From = std::move(from);
    this->Kept = kept;
    this->FirstTile = first_tile;
    return out;
  }
};

/// Output 0: the mapped atoms, bonds and arrays, k^2 copies of the patch (or this piece's share
/// of them; atoms a cut tile dropped left out), with each bond's BondLengthChange (0 for the atoms'
/// vertices).
void build_atoms(vtkPolyData* atoms, const PatchData& data, const mesolens::MappedMembrane& mapped,
                 const std::vector<double>& bond_changes, TileArrays& arrays, vtkPolyData* output)
{
  const vtkIdType n = atoms->GetNumberOfPoints();
  const vtkIdType tiles = static_cast<vtkIdType>(mapped.positions.size() / (3 * std::size_t(n)));
  vtkIdType total = 0;
  const std::vector<vtkIdType> kept = kept_atoms(mapped, n * tiles, total);
  vtkNew<vtkDoubleArray> coordinates;
  coordinates->SetNumberOfComponents(3);
  coordinates->SetNumberOfTuples(total);
  for (vtkIdType i = 0; i < n * tiles; ++i)
  {
    if (kept[std::size_t(i)] >= 0)
    {
      coordinates->SetTypedTuple(kept[std::size_t(i)], mapped.positions.data() + 3 * i);
    }
  }
  vtkNew<vtkPoints> points;
  points->SetData(coordinates);
  output->SetPoints(points);
  vtkMesoAtomTableConversion::SetAtomVertices(output);

  vtkNew<vtkCellArray> lines;
  std::vector<float> kept_changes;
  const std::size_t bonds = data.bonds.size();
  for (vtkIdType t = 0; t < tiles; ++t)
  {
    for (std::size_t b = 0; b < bonds; ++b)
    {
      const vtkIdType from = kept[std::size_t(t * n + data.bonds[b][0])];
      const vtkIdType to = kept[std::size_t(t * n + data.bonds[b][1])];
      if (from >= 0 && to >= 0)
      {
        const vtkIdType ends[2] = { from, to };
        lines->InsertNextCell(2, ends);
        kept_changes.push_back(static_cast<float>(bond_changes[std::size_t(t) * bonds + b]));
      }
    }
  }
  output->SetLines(lines);
  output->GetPointData()->ShallowCopy(
    arrays.For(atoms, data, kept, total, static_cast<vtkIdType>(mapped.first_atom_tile)));

  vtkNew<vtkFloatArray> change;
  change->SetName(vtkMesoArrayNames::BondLengthChange);
  change->SetNumberOfValues(total + static_cast<vtkIdType>(kept_changes.size()));
  for (vtkIdType i = 0; i < total; ++i)
  {
    change->SetValue(i, 0.0f);
  }
  for (std::size_t i = 0; i < kept_changes.size(); ++i)
  {
    change->SetValue(total + static_cast<vtkIdType>(i), kept_changes[i]);
  }
  output->GetCellData()->AddArray(change);
}

/// Output 0 without atoms (OutputAtoms off): a vertex per molecule and tile at the molecule's
/// centre as the renderer warps it, tile-major, the molecules in the patch's order; point arrays
/// MoleculeId (made unique over the tiles as the mapped atoms'), TileId and, when the patch has
/// it, ResidueName (of each molecule's first atom). The arrays are kept, the same objects, while
/// the patch's ids and names and the tiles stay, so a cutaway of these molecules keeps its work
/// over the frames.
struct MoleculeArrays
{
  std::vector<vtkMesoStamp> From;
  std::size_t Tiles = 0;
  vtkSmartPointer<vtkPointData> Arrays;

  vtkPointData* For(vtkPolyData* atoms, const PatchData& data,
                    const mesolens::MoleculeGroups& groups, std::size_t tiles)
  {
    vtkPointData* in = atoms->GetPointData();
    vtkAbstractArray* names = in->GetAbstractArray(vtkMesoArrayNames::ResidueName);
    const std::vector<vtkMesoStamp> from{
      vtkMesoStamp::Of(in->GetAbstractArray(vtkMesoArrayNames::MoleculeId)), vtkMesoStamp::Of(names)
    };
    if (this->Arrays && from == this->From && tiles == this->Tiles)
    {
      return this->Arrays;
    }
    const std::size_t molecules = groups.count();
    const auto total = static_cast<vtkIdType>(tiles * molecules);
    const int stride = *std::max_element(data.molecule_ids.begin(), data.molecule_ids.end()) + 1;
    vtkNew<vtkIntArray> ids;
    ids->SetName(vtkMesoArrayNames::MoleculeId);
    ids->SetNumberOfValues(total);
    vtkNew<vtkIntArray> tile_ids;
    tile_ids->SetName(vtkMesoArrayNames::TileId);
    tile_ids->SetNumberOfValues(total);
    vtkSmartPointer<vtkAbstractArray> first_names;
    if (names)
    {
      first_names = vtk::TakeSmartPointer(names->NewInstance());
      first_names->SetName(vtkMesoArrayNames::ResidueName);
      first_names->SetNumberOfComponents(names->GetNumberOfComponents());
      first_names->SetNumberOfTuples(total);
    }
    for (std::size_t tile = 0; tile < tiles; ++tile)
    {
      for (std::size_t m = 0; m < molecules; ++m)
      {
        const auto point = static_cast<vtkIdType>(tile * molecules + m);
        ids->SetValue(point, static_cast<int>(tile) * stride + groups.ids[m]);
        tile_ids->SetValue(point, static_cast<int>(tile));
        if (first_names)
        {
          first_names->SetTuple(point, groups.atoms[groups.first[m]], names);
        }
      }
    }
    this->Arrays = vtkSmartPointer<vtkPointData>::New();
    this->Arrays->AddArray(ids);
    this->Arrays->AddArray(tile_ids);
    if (first_names)
    {
      this->Arrays->AddArray(first_names);
    }
    this->From = from;
    this->Tiles = tiles;
    return this->Arrays;
  }
};

void build_molecule_centres(vtkPolyData* atoms, const PatchData& data,
                            const mesolens::MembraneWarp& warp, MoleculeArrays& arrays,
                            vtkPolyData* output)
{
  const mesolens::MoleculeGroups groups =
    mesolens::group_molecules(data.molecule_ids.data(), data.patch.atom_count());
  const std::vector<double> centres =
    mesolens::warped_molecule_centres(warp, data.patch, groups, vtkMesoParallelFor::Get());
  vtkNew<vtkDoubleArray> coordinates;
  coordinates->SetNumberOfComponents(3);
  coordinates->SetNumberOfTuples(static_cast<vtkIdType>(centres.size() / 3));
  std::copy(centres.begin(), centres.end(), coordinates->GetPointer(0));
  vtkNew<vtkPoints> points;
  points->SetData(coordinates);
  output->SetPoints(points);
  vtkMesoAtomTableConversion::SetAtomVertices(output);
  output->GetPointData()->ShallowCopy(arrays.For(atoms, data, groups, warp.tile_count()));
}

/// Whether a renderer can draw the patch by `warp` (mesolens::check_drawable).
bool drawable(const mesolens::MembraneWarp& warp)
{
  try
  {
    mesolens::check_drawable(warp);
    return true;
  }
  catch (const mesolens::Error&)
  {
    return false;
  }
}

/// Outputs 1 and 2: the parameterized disk and, when lattice_edge > 0, the lattice of that edge
/// laid on it.
void build_chart_outputs(const mesolens::MappingChart& chart, double lattice_edge,
                         vtkPolyData* disk_output, vtkPolyData* lattice_output)
{
  vtkMesoSurfaceConversion::FromTriangleMesh(chart.disk.mesh, disk_output);
  vtkMesoSurfaceConversion::AddDiskArrays(chart.disk, chart.radius, disk_output);
  vtkMesoSurfaceConversion::AddParameterizationArrays(chart.parameterization, chart.radius,
                                                      disk_output);
  if (lattice_edge > 0)
  {
    vtkMesoSurfaceConversion::FromTriangleMesh(
      mesolens::chart_lattice(chart.chart, chart.parameterization.uv, lattice_edge),
      lattice_output);
  }
}

/// What the filter's settings ask of the mapper (centre_uv and cut_to_disk are the mapper's).
mesolens::MapRequest map_request(vtkMesoMembraneMapping* filter)
{
  mesolens::MapRequest request;
  mesolens::MappingParams& mapping = request.mapping;
  mapping.method = static_cast<mesolens::MappingMethod>(filter->GetMappingMethod());
  mapping.tiles = filter->GetTiles();
  mapping.scale = filter->GetMembraneToMeshScale();
  mapping.layer_half_thickness = filter->GetLayerHalfThickness();
  mapping.samples = filter->GetPolynomialSamples();
  mapping.max_polynomial_residual = filter->GetMaximumPolynomialResidual();
  mapping.map_atoms = filter->GetOutputAtoms();
  request.radius_factor = filter->GetRadiusFactor();
  request.max_stretch = filter->GetMaximumStretch();
  request.min_disk_triangles = static_cast<std::size_t>(filter->GetMinimumDiskTriangles());
  request.max_disk_triangles = static_cast<std::size_t>(filter->GetMaximumDiskTriangles());
  request.fit_what_fits = filter->GetMapWhatFits();
  return request;
}

} // namespace

struct vtkMesoMembraneMapping::State
{
  vtkMesoSurfaceConversion::SurfaceMapper Mapper;
  TileArrays MappedArrays;
  MoleculeArrays CentreArrays;
};

vtkMesoMembraneMapping::vtkMesoMembraneMapping()
  : Internal(new State)
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(3);
  const mesolens::MapRequest defaults;
  this->MappingMethod = static_cast<int>(defaults.mapping.method);
  this->Tiles = defaults.mapping.tiles;
  this->MembraneToMeshScale = defaults.mapping.scale;
  this->LayerHalfThickness = defaults.mapping.layer_half_thickness;
  this->PolynomialSamples = defaults.mapping.samples;
  this->MaximumPolynomialResidual = defaults.mapping.max_polynomial_residual;
  this->OutputAtoms = defaults.mapping.map_atoms;
  this->RadiusFactor = defaults.radius_factor;
  this->MaximumStretch = defaults.max_stretch;
  this->MinimumDiskTriangles = static_cast<int>(defaults.min_disk_triangles);
  this->MaximumDiskTriangles = static_cast<int>(defaults.max_disk_triangles);
  this->MapWhatFits = defaults.fit_what_fits;
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
  for (int port = 0; port < 3; ++port)
  {
    vtkInformation* out = outputVector->GetInformationObject(port);
    // Pieces share the tiles' atoms; each maps from the whole surface and patch.
    out->Set(vtkAlgorithm::CAN_HANDLE_PIECE_REQUEST(), 1);
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

int vtkMesoMembraneMapping::RequestUpdateExtent(vtkInformation*, vtkInformationVector** inputVector,
                                                vtkInformationVector* outputVector)
{
  vtkMesoAtomPieces::RequestWholeInputsWhenStreaming(inputVector, 2, outputVector);
  return 1;
}

int vtkMesoMembraneMapping::RequestData(vtkInformation*, vtkInformationVector** inputVector,
                                        vtkInformationVector* outputVector)
{
  // On many processes every one maps from the whole surface and patch (both small), whatever
  // pieces of them its readers gave it.
  using Gathered = vtkMesoAtomPieces::GatheredInput;
  const Gathered whole_surface(inputVector[0], outputVector, Gathered::KeepWhole);
  const Gathered whole_patch(inputVector[1], outputVector, Gathered::KeepWhole);
  vtkPolyData* surface = inputVector[0]->GetInformationObject(0) ? whole_surface.Whole() : nullptr;
  vtkPolyData* atoms = inputVector[1]->GetInformationObject(0) ? whole_patch.Whole() : nullptr;
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkPolyData* disk_output = vtkPolyData::GetData(outputVector, 1);
  vtkPolyData* lattice_output = vtkPolyData::GetData(outputVector, 2);
  output->Initialize();
  disk_output->Initialize();
  lattice_output->Initialize();
  try
  {
    if (!surface || !atoms)
    {
      throw mesolens::InvalidInput(
        "both the surface (input 0) and the membrane (input 1) are needed");
    }
    PatchData data = read_patch(atoms);
    const mesolens::MembraneMapper& mapper =
      this->Internal->Mapper.For(surface, whole_surface.Version());
    this->UpdateProgress(0.2);
    mesolens::MapRequest request = map_request(this);
    std::tie(request.piece, request.pieces) =
      vtkMesoAtomPieces::Requested(outputVector->GetInformationObject(0));
    if (request.piece > 0 && !this->OutputAtoms)
    {
      return 1; // the warp (for the GPU) and the chart are piece 0's
    }
    const mesolens::SurfacePoint seed = mapper.seed_near(
      { this->SeedPoint[0], this->SeedPoint[1], this->SeedPoint[2] }, this->SeedTolerance);
    mesolens::MapResult result = mapper.map(seed, data.patch, request, vtkMesoParallelFor::Get());
    this->UpdateProgress(0.8);
    if (!result.note.empty())
    {
      vtkWarningMacro("" << result.note);
    }
    const mesolens::MappedMembrane& mapped = result.mapped;
    if (!mapped.positions.empty())
    {
      build_atoms(
        atoms, data, mapped,
        mesolens::bond_length_changes(data.patch, mapped, data.bonds, request.mapping.scale),
        this->Internal->MappedArrays, output);
    }
    const std::shared_ptr<const mesolens::MappingChart> chart = result.chart;
    const bool mapped_atoms = !mapped.positions.empty();
    const mesolens::MembraneWarp warp =
      mesolens::membrane_warp(std::move(result), data.patch, request);
    if (!mapped_atoms && !data.molecule_ids.empty() && drawable(warp))
    {
      build_molecule_centres(atoms, data, warp, this->Internal->CentreArrays, output);
    }
    vtkMesoMembraneWarp::Write(warp, output->GetFieldData());
    if (atoms->GetInformation()->Has(vtkDataObject::DATA_TIME_STEP()))
    {
      output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(),
                                    atoms->GetInformation()->Get(vtkDataObject::DATA_TIME_STEP()));
    }
    if (request.piece == 0)
    {
      build_chart_outputs(*chart, this->LatticeEdge, disk_output, lattice_output);
    }
  }
  catch (const mesolens::Error& e)
  {
    vtkErrorMacro("Cannot map the membrane: " << e.what());
    output->Initialize();
    disk_output->Initialize();
    lattice_output->Initialize();
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
  os << indent << "MaximumPolynomialResidual: " << this->MaximumPolynomialResidual << "\n";
  os << indent << "MinimumDiskTriangles: " << this->MinimumDiskTriangles << "\n";
  os << indent << "MaximumDiskTriangles: " << this->MaximumDiskTriangles << "\n";
  os << indent << "MaximumStretch: " << this->MaximumStretch << "\n";
  os << indent << "MapWhatFits: " << (this->MapWhatFits ? "on" : "off") << "\n";
  os << indent << "LatticeEdge: " << this->LatticeEdge << "\n";
  os << indent << "OutputAtoms: " << (this->OutputAtoms ? "on" : "off") << "\n";
}
