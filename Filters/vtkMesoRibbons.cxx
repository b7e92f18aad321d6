// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoRibbons.h"

#include "vtkMesoArrayNames.h"

#include "vtkMesoAtomTableConversion.h"
#include "vtkMesoSurfaceConversion.h"
#include "vtkMesoParallelFor.h"
#include "vtkMesoStamp.h"

#include "mesolens/protein/dssp.h"
#include "mesolens/common/errors.h"
#include "mesolens/molecules/molecule_assignment.h"
#include "mesolens/protein/protein_backbone.h"
#include "mesolens/protein/ribbon_geometry.h"

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
#include <vtkSMPTools.h>
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
  std::vector<vtkMesoStamp> LayoutFrom;
  std::vector<mesolens::RibbonResidue> Residues;
  std::vector<std::int64_t> TraceAtom;
  std::vector<std::int64_t> OxygenAtom; ///< -1: none
  std::vector<int> ResidueIndex;
};

vtkMesoRibbons::vtkMesoRibbons()
  : Internal(std::make_unique<Internals>())
{
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
/// The traced residues of a table in table order: amino acids through CA (oriented by O),
/// nucleotides through P. `atom` gets each one's trace atom row, `residue` its residue index.
std::vector<mesolens::RibbonResidue> traced_residues(const mesolens::AtomTable& table,
                                                     std::vector<std::int64_t>& atom,
                                                     std::vector<std::int64_t>& oxygen,
                                                     std::vector<int>& residue)
{
  const mesolens::ProteinBackbone backbone = mesolens::protein_backbone(table);
  std::map<int, std::size_t> amino_acid_of_residue;
  for (std::size_t r = 0; r < backbone.residue_index.size(); ++r)
  {
    amino_acid_of_residue[backbone.residue_index[r]] = r;
  }
  std::vector<mesolens::RibbonResidue> traced;
  // Chains as the backbone tells them apart (chain id or molecule changes), nucleotides too.
  std::int64_t chain = -1;
  std::string previous_chain;
  int previous_molecule = std::numeric_limits<int>::min();
  const std::size_t count = table.atom_names.size();
  std::size_t begin = 0;
  while (begin < count)
  {
    std::size_t end = begin + 1;
    while (end < count && table.residue_indices[end] == table.residue_indices[begin])
    {
      ++end;
    }
    const int index = table.residue_indices[begin];
    const auto amino_acid = amino_acid_of_residue.find(index);
    std::int64_t trace = -1;
    std::int64_t oxygen_row = -1;
    mesolens::RibbonResidue residue_out;
    if (amino_acid != amino_acid_of_residue.end() && backbone.atom_rows[amino_acid->second][1] >= 0)
    {
      const mesolens::BackboneResidue& b = backbone.residues[amino_acid->second];
      trace = backbone.atom_rows[amino_acid->second][1]; // CA
      if (b.has_o)
      {
        residue_out.carbonyl_oxygen = b.o;
        oxygen_row = backbone.atom_rows[amino_acid->second][3];
      }
    }
    else if (mesolens::is_nucleotide_residue(table.residue_names[begin]))
    {
      for (std::size_t a = begin; a < end && trace < 0; ++a)
      {
        if (table.atom_names[a] == "P")
        {
          trace = std::int64_t(a);
        }
      }
      residue_out.nucleotide = true;
    }
    if (trace >= 0)
    {
      const std::size_t t = std::size_t(trace);
      const std::string& chain_id = table.chain_ids[t];
      const int molecule = table.molecule_ids[t];
      if (chain < 0 || chain_id != previous_chain || molecule != previous_molecule)
      {
        ++chain;
      }
      previous_chain = chain_id;
      previous_molecule = molecule;
      residue_out.trace = { table.positions[3 * t], table.positions[3 * t + 1],
                            table.positions[3 * t + 2] };
      residue_out.secondary_structure = mesolens::dssp_letter(
        static_cast<mesolens::SecondaryStructure>(table.secondary_structure[t]));
      residue_out.chain = chain;
      residue_out.id = std::int64_t(traced.size());
      traced.push_back(residue_out);
      atom.push_back(trace);
      oxygen.push_back(oxygen_row);
      residue.push_back(index);
    }
    begin = end;
  }
  return traced;
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
    vtkPointData* data = atoms->GetPointData();
    const auto stamps = vtkMesoAtomLayoutStamps(atoms);
    if (stamps != in.LayoutFrom)
    {
      in.LayoutFrom.clear();
      mesolens::AtomTable table;
      std::string missing;
      if (!vtkMesoAtomTableConversion::FromPolyData(atoms, 1.0, table, &missing))
      {
        vtkErrorMacro(<< vtkMesoAtomTableConversion::MissingArrayMessage(missing));
        return 0;
      }
      in.TraceAtom.clear();
      in.OxygenAtom.clear();
      in.ResidueIndex.clear();
      in.Residues = traced_residues(table, in.TraceAtom, in.OxygenAtom, in.ResidueIndex);
      in.LayoutFrom = stamps;
    }
    // This frame's positions and classes.
    vtkDataArray* codes = data->GetArray(vtkMesoArrayNames::SecondaryStructure);
    vtkPoints* positions = atoms->GetPoints();
    for (std::size_t r = 0; r < in.Residues.size(); ++r)
    {
      mesolens::RibbonResidue& residue = in.Residues[r];
      double p[3];
      positions->GetPoint(in.TraceAtom[r], p);
      residue.trace = { p[0], p[1], p[2] };
      if (in.OxygenAtom[r] >= 0)
      {
        positions->GetPoint(in.OxygenAtom[r], p);
        residue.carbonyl_oxygen = std::array<double, 3>{ p[0], p[1], p[2] };
      }
      residue.secondary_structure = codes
        ? mesolens::dssp_letter(
            static_cast<mesolens::SecondaryStructure>(codes->GetComponent(in.TraceAtom[r], 0)))
        : ' ';
    }
    const std::vector<mesolens::RibbonResidue>& residues = in.Residues;
    const std::vector<std::int64_t>& trace_atom = in.TraceAtom;
    const std::vector<int>& residue_index = in.ResidueIndex;
    mesolens::RibbonParams settings;
    settings.subdivisions = this->Subdivisions;
    settings.tube_sides = this->TubeSides;
    settings.helix_as_cylinder = this->HelixAsCylinder;
    settings.helix_width = this->HelixWidth;
    settings.strand_width = this->StrandWidth;
    settings.ribbon_thickness = this->RibbonThickness;
    settings.coil_radius = this->CoilRadius;
    settings.nucleic_radius = this->NucleicRadius;
    settings.cylinder_radius = this->CylinderRadius;
    settings.arrow_width_factor = this->ArrowWidthFactor;
    // Per-piece counts apply while they match the pieces (counted only when some are given:
    // ribbon_mesh finds the pieces itself).
    if (this->SegmentSubdivisions &&
        this->SegmentSubdivisions->GetNumberOfTuples() ==
          vtkIdType(mesolens::ribbon_segments(residues, settings).size()))
    {
      for (vtkIdType s = 0; s < this->SegmentSubdivisions->GetNumberOfTuples(); ++s)
      {
        settings.segment_subdivisions.push_back(
          std::clamp(this->SegmentSubdivisions->GetValue(s), 1, 32));
      }
    }
    const mesolens::RibbonMesh mesh =
      mesolens::ribbon_mesh(residues, settings, vtkMesoParallelFor::Get());

    const vtkIdType vertices = vtkIdType(mesh.vertex_count());
    vtkNew<vtkFloatArray> coordinates;
    coordinates->SetNumberOfComponents(3);
    coordinates->SetNumberOfTuples(vertices);
    vtkNew<vtkFloatArray> normals;
    normals->SetName(vtkMesoArrayNames::Normals);
    normals->SetNumberOfComponents(3);
    normals->SetNumberOfTuples(vertices);
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
    float* xyz = coordinates->GetPointer(0);
    float* nxyz = normals->GetPointer(0);
    vtkIdType* atom_of = atom_ids->GetPointer(0);
    vtkIdType* source = from->GetPointer(0);
    int* residue_of = residue_ids->GetPointer(0);
    int* chain_of = chain_ids->GetPointer(0);
    unsigned char* class_of = classes->GetPointer(0);
    vtkSMPTools::For(0, vertices, [&](vtkIdType begin, vtkIdType end) {
      for (vtkIdType v = begin; v < end; ++v)
      {
        const std::size_t i = 3 * std::size_t(v);
        for (int d = 0; d < 3; ++d)
        {
          xyz[i + std::size_t(d)] = static_cast<float>(mesh.points[i + std::size_t(d)]);
          nxyz[i + std::size_t(d)] = static_cast<float>(mesh.normals[i + std::size_t(d)]);
        }
        const auto traced = std::size_t(mesh.vertex_residue_id[std::size_t(v)]);
        atom_of[v] = trace_atom[traced];
        source[v] = trace_atom[traced];
        residue_of[v] = residue_index[traced];
        chain_of[v] = int(residues[traced].chain);
        class_of[v] = static_cast<unsigned char>(
          mesolens::from_dssp_letter(mesh.vertex_secondary_structure[std::size_t(v)]));
      }
    });
    vtkNew<vtkPoints> points;
    points->SetData(coordinates);
    output->SetPoints(points);
    vtkMesoSurfaceConversion::SetTriangles(mesh.triangles, output);

    vtkPointData* in = atoms->GetPointData();
    vtkPointData* out = output->GetPointData();
    // Each numeric array of the input, gathered from the trace atoms.
    vtkMesoAtomTableConversion::GatherAtomArrays(
      in, from, out, { vtkMesoArrayNames::ResidueIndex, vtkMesoArrayNames::SecondaryStructure });
    out->AddArray(atom_ids);
    out->AddArray(residue_ids);
    out->AddArray(chain_ids);
    out->AddArray(classes);
    out->SetNormals(normals);

    // Per piece of chain: its bounds and residues, for a view-dependent level of detail.
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
  catch (const mesolens::Error& error)
  {
    output->Initialize();
    vtkErrorMacro("Cannot draw the ribbons: " << error.what());
    return 0;
  }
  return 1;
}
