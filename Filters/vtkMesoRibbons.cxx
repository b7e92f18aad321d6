// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoRibbons.h"

#include "vtkMesoArrayNames.h"

#include "vtkMesoAtomInput.h"
#include "vtkMesoAtomTableConversion.h"
#include "vtkMesoSurfaceConversion.h"
#include "vtkMesoParallelFor.h"
#include "vtkMesoStamp.h"

#include "mesolens/protein/dssp.h"
#include "mesolens/common/errors.h"
#include "mesolens/molecules/molecule_assignment.h"
#include "mesolens/protein/protein_backbone.h"
#include "mesolens/protein/ribbon_geometry.h"
#include "mesolens/protein/ribbon_trace.h"

#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkIdList.h>
#include <vtkIdTypeArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMesoRibbons);
vtkCxxSetObjectMacro(vtkMesoRibbons, SegmentSubdivisions, vtkIntArray);

/// Which atoms the ribbon is traced through, kept while the atoms' names and residues stay: a
/// new frame (or a new level of detail) then only reads positions and classes.
struct vtkMesoRibbons::Internals
{
  vtkMesoAtomInput Atoms;
  mesolens::RibbonTrace Trace;
  mesolens::RibbonMesh Mesh; ///< the last update's, its memory reused by the next
};

vtkMesoRibbons::vtkMesoRibbons()
  : Internal(std::make_unique<Internals>())
{
  const mesolens::RibbonParams defaults;
  this->Subdivisions = defaults.subdivisions;
  this->TubeSides = defaults.tube_sides;
  this->HelixAsCylinder = defaults.helix_as_cylinder;
  this->HelixWidth = defaults.helix_width;
  this->StrandWidth = defaults.strand_width;
  this->RibbonThickness = defaults.ribbon_thickness;
  this->CoilRadius = defaults.coil_radius;
  this->NucleicRadius = defaults.nucleic_radius;
  this->CylinderRadius = defaults.cylinder_radius;
  this->ArrowWidthFactor = defaults.arrow_width_factor;
}

vtkMesoRibbons::~vtkMesoRibbons()
{
  this->SetSegmentSubdivisions(nullptr);
}

vtkMTimeType vtkMesoRibbons::GetMTime()
{
  vtkMTimeType time = this->Superclass::GetMTime();
  if (this->SegmentSubdivisions)
  {
    time = std::max(time, this->SegmentSubdivisions->GetMTime());
  }
  return time;
}

namespace {
/// The filter's shape settings; the per-piece subdivisions apply while they match the pieces
/// (counted only when some are given: ribbon_mesh finds the pieces itself).
mesolens::RibbonParams ribbon_params(vtkMesoRibbons* filter,
                                     const std::vector<mesolens::RibbonResidue>& residues)
{
  mesolens::RibbonParams params;
  params.subdivisions = filter->GetSubdivisions();
  params.tube_sides = filter->GetTubeSides();
  params.helix_as_cylinder = filter->GetHelixAsCylinder();
  params.helix_width = filter->GetHelixWidth();
  params.strand_width = filter->GetStrandWidth();
  params.ribbon_thickness = filter->GetRibbonThickness();
  params.coil_radius = filter->GetCoilRadius();
  params.nucleic_radius = filter->GetNucleicRadius();
  params.cylinder_radius = filter->GetCylinderRadius();
  params.arrow_width_factor = filter->GetArrowWidthFactor();
  vtkIntArray* per_segment = filter->GetSegmentSubdivisions();
  if (per_segment &&
      per_segment->GetNumberOfTuples() ==
        vtkIdType(mesolens::ribbon_segments(residues, params).size()))
  {
    for (vtkIdType s = 0; s < per_segment->GetNumberOfTuples(); ++s)
    {
      params.segment_subdivisions.push_back(std::clamp(per_segment->GetValue(s), 1, 32));
    }
  }
  return params;
}

/// The mesh as the output's points, triangles and normals, each vertex with its trace atom
/// (AtomId), residue, chain and class, and every numeric array of that atom.
void write_mesh(const mesolens::RibbonMesh& mesh, const mesolens::RibbonTrace& trace,
                vtkPolyData* atoms, vtkPolyData* output)
{
  const vtkIdType vertices = vtkIdType(mesh.vertex_count());
  vtkSmartPointer<vtkFloatArray> normals =
    vtkMesoSurfaceConversion::SetFloatPoints(mesh.points, mesh.normals, output);
  vtkNew<vtkIdList> from;
  from->SetNumberOfIds(vertices);
  vtkNew<vtkIdTypeArray> atom_ids;
  atom_ids->SetName(vtkMesoArrayNames::AtomId);
  atom_ids->SetNumberOfValues(vertices);
  vtkNew<vtkIntArray> residue_ids;
  residue_ids->SetName(vtkMesoArrayNames::ResidueIndex);
  residue_ids->SetNumberOfValues(vertices);
  vtkNew<vtkIntArray> chain_ids;
  chain_ids->SetName(vtkMesoArrayNames::ChainIndex);
  chain_ids->SetNumberOfValues(vertices);
  vtkNew<vtkUnsignedCharArray> classes;
  classes->SetName(vtkMesoArrayNames::SecondaryStructure);
  classes->SetNumberOfValues(vertices);
  // Straight into the arrays' memory, in parallel: the mesh can have millions of vertices.
  vtkIdType* atom_of = atom_ids->GetPointer(0);
  vtkIdType* source = from->GetPointer(0);
  int* residue_of = residue_ids->GetPointer(0);
  int* chain_of = chain_ids->GetPointer(0);
  unsigned char* class_of = classes->GetPointer(0);
  vtkMesoParallelFor::For(0, vertices, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType v = begin; v < end; ++v)
    {
      const auto traced = std::size_t(mesh.vertex_residue_id[std::size_t(v)]);
      atom_of[v] = trace.trace_atom[traced];
      source[v] = trace.trace_atom[traced];
      residue_of[v] = trace.residue_index[traced];
      chain_of[v] = int(trace.residues[traced].chain);
      class_of[v] = static_cast<unsigned char>(
        mesolens::from_dssp_letter(mesh.vertex_secondary_structure[std::size_t(v)]));
    }
  });
  vtkMesoSurfaceConversion::SetTriangles(mesh.triangles, output);

  vtkPointData* out = output->GetPointData();
  // Each numeric array of the input, gathered from the trace atoms.
  vtkMesoAtomTableConversion::GatherAtomArrays(
    atoms->GetPointData(), from, out,
    { vtkMesoArrayNames::ResidueIndex, vtkMesoArrayNames::SecondaryStructure });
  out->AddArray(atom_ids);
  out->AddArray(residue_ids);
  out->AddArray(chain_ids);
  out->AddArray(classes);
  out->SetNormals(normals);
}

/// Per piece of chain, its bounds and residues (field data SegmentBounds and
/// SegmentResidueCounts), for a view-dependent level of detail.
void add_segment_fields(const mesolens::RibbonMesh& mesh,
                        const std::vector<mesolens::RibbonResidue>& residues, vtkPolyData* output)
{
  vtkNew<vtkDoubleArray> bounds;
  bounds->SetName(vtkMesoArrayNames::SegmentBounds);
  bounds->SetNumberOfComponents(6);
  vtkNew<vtkIntArray> lengths;
  lengths->SetName(vtkMesoArrayNames::SegmentResidueCounts);
  for (const mesolens::RibbonSegment& segment : mesh.segments)
  {
    double box[6] = { VTK_DOUBLE_MAX, VTK_DOUBLE_MIN, VTK_DOUBLE_MAX,
                      VTK_DOUBLE_MIN, VTK_DOUBLE_MAX, VTK_DOUBLE_MIN };
    for (std::size_t r = segment.first_residue; r < segment.first_residue + segment.residue_count;
         ++r)
    {
      for (int d = 0; d < 3; ++d)
      {
        box[2 * d] = std::min(box[2 * d], residues[r].trace[std::size_t(d)]);
        box[2 * d + 1] = std::max(box[2 * d + 1], residues[r].trace[std::size_t(d)]);
      }
    }
    bounds->InsertNextTuple(box);
    lengths->InsertNextValue(int(segment.residue_count));
  }
  output->GetFieldData()->AddArray(bounds);
  output->GetFieldData()->AddArray(lengths);
}
} // namespace

void vtkMesoRibbons::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Subdivisions: " << this->Subdivisions << "\n";
  os << indent << "TubeSides: " << this->TubeSides << "\n";
  os << indent << "HelixAsCylinder: " << this->HelixAsCylinder << "\n";
  os << indent << "HelixWidth: " << this->HelixWidth << "\n";
  os << indent << "StrandWidth: " << this->StrandWidth << "\n";
  os << indent << "RibbonThickness: " << this->RibbonThickness << "\n";
  os << indent << "CoilRadius: " << this->CoilRadius << "\n";
  os << indent << "NucleicRadius: " << this->NucleicRadius << "\n";
  os << indent << "CylinderRadius: " << this->CylinderRadius << "\n";
  os << indent << "ArrowWidthFactor: " << this->ArrowWidthFactor << "\n";
  os << indent << "SegmentSubdivisions: " << this->SegmentSubdivisions << "\n";
}

int vtkMesoRibbons::RequestData(vtkInformation*, vtkInformationVector** inputVector,
                                vtkInformationVector* outputVector)
{
  vtkPolyData* atoms = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  output->Initialize();
  if (!atoms || atoms->GetNumberOfPoints() == 0)
  {
    vtkErrorMacro("No atoms to draw ribbons through.");
    return 0;
  }
  Internals& in = *this->Internal;
  try
  {
    if (in.Atoms.ReadLayout(atoms))
    {
      in.Trace = mesolens::ribbon_trace(in.Atoms.Layout());
    }
    in.Trace.update(in.Atoms.Positions(atoms),
                    in.Atoms.Bytes(atoms, vtkMesoArrayNames::SecondaryStructure));
    // Into the last update's mesh: its memory is reused (see mesolens::ribbon_mesh).
    mesolens::RibbonMesh& mesh = in.Mesh;
    mesolens::ribbon_mesh(in.Trace.residues, ribbon_params(this, in.Trace.residues),
                          vtkMesoParallelFor::Get(), mesh);
    write_mesh(mesh, in.Trace, atoms, output);
    add_segment_fields(mesh, in.Trace.residues, output);
  }
  catch (const mesolens::Error& error)
  {
    output->Initialize();
    vtkErrorMacro("Cannot draw the ribbons: " << error.what());
    return 0;
  }
  return 1;
}
