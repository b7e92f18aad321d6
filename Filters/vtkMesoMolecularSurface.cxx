// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoMolecularSurface.h"

#include "vtkMesoArrayNames.h"
#include "vtkMesoAtomPieces.h"

#include "vtkMesoAtomInput.h"
#include "vtkMesoAtomTableConversion.h"
#include "vtkMesoSurfaceConversion.h"
#include "vtkMesoParallelFor.h"

#include "mesolens/common/errors.h"
#include "mesolens/molecules/elements.h"
#include "mesolens/surface/molecular_surface.h"

#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkIdList.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkUnsignedCharArray.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMesoMolecularSurface);

vtkMesoMolecularSurface::vtkMesoMolecularSurface()
{
  const mesolens::MolecularSurfaceParams defaults;
  this->SurfaceType = static_cast<int>(defaults.kind);
  this->ProbeRadius = defaults.probe_radius;
  this->Tolerance = defaults.tolerance;
  this->ComputeExactFigures = defaults.exact_figures;
  this->KeepCavities = defaults.keep_cavities;
  this->BeadRadius = mesolens::bead_radius;
}

vtkMesoMolecularSurface::~vtkMesoMolecularSurface()
{
  this->SetRadiusArrayName(nullptr);
}

namespace {
/// The surface as the output's points, triangles and normals, each vertex with its atom
/// (AtomId), its patch type, every numeric array of its atom, and ChainIndex (chains numbered
/// in order of first appearance) when the atoms have chain ids.
void write_surface(const mesolens::MolecularSurface& surface, vtkPolyData* atoms,
                   vtkPolyData* output)
{
  const vtkIdType vertices = static_cast<vtkIdType>(surface.atom.size());
  vtkSmartPointer<vtkFloatArray> normals =
    vtkMesoSurfaceConversion::SetFloatPoints(surface.points, surface.normals, output);
  vtkNew<vtkIdTypeArray> atom_ids;
  atom_ids->SetName(vtkMesoArrayNames::AtomId);
  atom_ids->SetNumberOfValues(vertices);
  vtkNew<vtkUnsignedCharArray> patches;
  patches->SetName(vtkMesoArrayNames::PatchType);
  patches->SetNumberOfValues(vertices);
  vtkNew<vtkIdList> from;
  from->SetNumberOfIds(vertices);
  for (vtkIdType v = 0; v < vertices; ++v)
  {
    atom_ids->SetValue(v, surface.atom[std::size_t(v)]);
    patches->SetValue(v, static_cast<unsigned char>(surface.patch[std::size_t(v)]));
    from->SetId(v, surface.atom[std::size_t(v)]);
  }
  vtkMesoSurfaceConversion::SetTriangles(surface.triangles, output);

  // Each numeric array of the atoms, carried to the vertices through their atoms.
  vtkPointData* in = atoms->GetPointData();
  vtkPointData* out = output->GetPointData();
  vtkMesoAtomTableConversion::GatherAtomArrays(
    in, from, out,
    { vtkMesoArrayNames::Normals, vtkMesoArrayNames::AtomId, vtkMesoArrayNames::PatchType });
  // Chains as numbers (in order of first appearance), to colour by chain.
  vtkStringArray* chains =
    vtkStringArray::SafeDownCast(in->GetAbstractArray(vtkMesoArrayNames::ChainId));
  if (chains && !in->GetArray(vtkMesoArrayNames::ChainIndex))
  {
    std::map<std::string, int> index_of;
    std::vector<int> chain_of_atom(static_cast<std::size_t>(chains->GetNumberOfValues()));
    for (vtkIdType a = 0; a < chains->GetNumberOfValues(); ++a)
    {
      chain_of_atom[std::size_t(a)] =
        index_of.emplace(chains->GetValue(a), int(index_of.size())).first->second;
    }
    vtkNew<vtkIntArray> chain_index;
    chain_index->SetName(vtkMesoArrayNames::ChainIndex);
    chain_index->SetNumberOfValues(vertices);
    for (vtkIdType v = 0; v < vertices; ++v)
    {
      chain_index->SetValue(v, chain_of_atom[std::size_t(surface.atom[std::size_t(v)])]);
    }
    out->AddArray(chain_index);
  }
  out->AddArray(atom_ids);
  out->AddArray(patches);
  out->SetNormals(normals);
}

/// The surface's figures as field data (areas and volume only when they were computed).
void add_surface_fields(const mesolens::MolecularSurface& surface, vtkPolyData* output)
{
  using vtkMesoAtomTableConversion::SetFieldValue;
  if (std::isfinite(surface.area)) // else not asked for
  {
    SetFieldValue(output, vtkMesoArrayNames::Area, surface.area);
    SetFieldValue(output, vtkMesoArrayNames::Volume, surface.volume);
    SetFieldValue(output, vtkMesoArrayNames::ConvexArea, surface.patch_area[0]);
    SetFieldValue(output, vtkMesoArrayNames::ToroidalArea, surface.patch_area[1]);
    SetFieldValue(output, vtkMesoArrayNames::ConcaveArea, surface.patch_area[2]);
    SetFieldValue(output, vtkMesoArrayNames::SingularPatchCount,
                  double(surface.singular_patch_count));
  }
  SetFieldValue(output, vtkMesoArrayNames::ComponentCount, double(surface.component_count));
  SetFieldValue(output, vtkMesoArrayNames::CavityCount, double(surface.cavity_count));
  SetFieldValue(output, vtkMesoArrayNames::GridSpacing, surface.grid_spacing);
  SetFieldValue(output, vtkMesoArrayNames::DegenerateVertexCount,
                double(surface.degenerate_vertex_count));
}
} // namespace

int vtkMesoMolecularSurface::RequestUpdateExtent(vtkInformation*,
                                                 vtkInformationVector** inputVector,
                                                 vtkInformationVector* outputVector)
{
  vtkMesoAtomPieces::RequestWholeInputsWhenStreaming(inputVector, 1, outputVector);
  return 1;
}

int vtkMesoMolecularSurface::RequestData(vtkInformation*, vtkInformationVector** inputVector,
                                         vtkInformationVector* outputVector)
{
  // On many processes: the surface of every process's atoms, made once, by rank 0.
  const vtkMesoAtomPieces::GatheredInput gathered(inputVector[0], outputVector,
                                                  vtkMesoAtomPieces::GatheredInput::KeepWhole);
  if (gathered.Piece() > 0)
  {
    vtkPolyData::GetData(outputVector)->Initialize();
    return 1;
  }
  vtkPolyData* atoms = gathered.Whole();
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  output->Initialize();
  if (!atoms || atoms->GetNumberOfPoints() == 0)
  {
    vtkErrorMacro("No atoms to wrap in a surface.");
    return 0;
  }
  mesolens::MolecularSurfaceParams params;
  params.kind = static_cast<mesolens::SurfaceKind>(this->SurfaceType);
  params.probe_radius = this->ProbeRadius;
  params.tolerance = this->Tolerance;
  params.keep_cavities = this->KeepCavities;
  params.exact_figures = this->ComputeExactFigures;
  mesolens::MolecularSurface surface;
  try
  {
    std::vector<std::array<double, 3>> centres;
    std::vector<double> radii;
    vtkMesoAtomInput::Spheres(atoms, this->RadiusArrayName, this->BeadRadius, centres, radii);
    surface =
      mesolens::molecular_surface(centres, radii, params, vtkMesoParallelFor::Get(),
                                  [this](double fraction) { this->UpdateProgress(fraction); });
  }
  catch (const mesolens::Error& failure)
  {
    vtkErrorMacro("Cannot build the surface: " << failure.what());
    return 0;
  }
  write_surface(surface, atoms, output);
  add_surface_fields(surface, output);
  if (surface.degenerate_vertex_count > 0)
  {
    vtkWarningMacro("Four or more atoms touch one probe position at "
                    << surface.degenerate_vertex_count
                    << " points (a perfect lattice?): Area and Volume are unreliable there; the "
                       "mesh is not affected.");
  }
  return 1;
}

void vtkMesoMolecularSurface::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  static const char* const types[] = { "solvent-excluded", "solvent-accessible", "van der Waals" };
  os << indent << "SurfaceType: " << types[this->SurfaceType] << "\n";
  os << indent << "ProbeRadius: " << this->ProbeRadius << "\n";
  os << indent << "Tolerance: " << this->Tolerance << "\n";
  os << indent << "ComputeExactFigures: " << (this->ComputeExactFigures ? "on" : "off") << "\n";
  os << indent << "KeepCavities: " << (this->KeepCavities ? "on" : "off") << "\n";
  os << indent
     << "RadiusArrayName: " << (this->RadiusArrayName ? this->RadiusArrayName : "(elements)")
     << "\n";
  os << indent << "BeadRadius: " << this->BeadRadius << "\n";
}
