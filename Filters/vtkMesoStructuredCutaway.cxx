// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoStructuredCutaway.h"

#include "vtkMesoSurfaceConversion.h"

#include "mesolens/errors.h"
#include "mesolens/molecule_pbc.h"
#include "mesolens/structure_mesh.h"
#include "mesolens/structured_cutaway.h"

#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkIdTypeArray.h>
#include <vtkImplicitFunction.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>

#include <cmath>
#include <unordered_map>
#include <vector>

vtkStandardNewMacro(vtkMesoStructuredCutaway);
vtkCxxSetObjectMacro(vtkMesoStructuredCutaway, CutFunction, vtkImplicitFunction);

namespace {
/// Atoms grouped into molecules: the molecule of each atom (dense, in order of first appearance)
/// and each molecule's centre (mean of its atoms).
struct Molecules
{
  std::vector<std::uint32_t> OfAtom;
  std::vector<double> Centres;
  std::vector<std::array<double, 3>> Shifts; ///< per molecule, to make the assembly whole

  /// Moves each molecule by the box vectors that gather the assembly in `box`.
  void MakeWhole(const mesolens::PeriodicBox& box)
  {
    this->Shifts = mesolens::assembly_shifts(this->Centres, box);
    for (std::size_t m = 0; m < this->Shifts.size(); ++m)
    {
      for (int d = 0; d < 3; ++d)
      {
        this->Centres[3 * m + d] += this->Shifts[m][d];
      }
    }
  }

  Molecules(vtkPolyData* atoms, vtkDataArray* ids)
  {
    const vtkIdType n = atoms->GetNumberOfPoints();
    this->OfAtom.resize(static_cast<std::size_t>(n));
    std::unordered_map<long long, std::uint32_t> index;
    std::vector<double> counts;
    for (vtkIdType a = 0; a < n; ++a)
    {
      const long long id = ids ? static_cast<long long>(ids->GetComponent(a, 0)) : a;
      const auto found = index.emplace(id, static_cast<std::uint32_t>(counts.size()));
      if (found.second)
      {
        counts.push_back(0);
        this->Centres.insert(this->Centres.end(), { 0, 0, 0 });
      }
      const std::uint32_t m = found.first->second;
      this->OfAtom[static_cast<std::size_t>(a)] = m;
      double p[3];
      atoms->GetPoint(a, p);
      for (int d = 0; d < 3; ++d)
      {
        if (!std::isfinite(p[d]))
        {
          throw mesolens::InvalidInput("atom " + std::to_string(a) + " has a non-finite position");
        }
        this->Centres[3 * m + d] += p[d];
      }
      counts[m] += 1;
    }
    for (std::size_t m = 0; m < counts.size(); ++m)
    {
      for (int d = 0; d < 3; ++d)
      {
        this->Centres[3 * m + d] /= counts[m];
      }
    }
  }
};
} // namespace

struct vtkMesoStructuredCutaway::Internals
{
  std::unique_ptr<mesolens::StructuredCutaway> Solver;
  vtkNew<vtkPolyData> Structure; // made from the molecules when none is connected
  int StructureVertices = 0;
  // What the solver was built from.
  vtkMTimeType StructureTime = 0;
  const void* StructureData = nullptr;
  const void* IdArray = nullptr;
  vtkMTimeType IdTime = 0;
  vtkIdType AtomCount = -1;
  int Assignments = 0;
};

vtkMesoStructuredCutaway::vtkMesoStructuredCutaway()
  : Internal(std::make_unique<Internals>())
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(2);
}

vtkMesoStructuredCutaway::~vtkMesoStructuredCutaway()
{
  this->SetCutFunction(nullptr);
}

int vtkMesoStructuredCutaway::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  if (port == 1)
  {
    // Optional for the pipeline, so that a missing structure gets its own clear error.
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  }
  return 1;
}

vtkMTimeType vtkMesoStructuredCutaway::GetMTime()
{
  vtkMTimeType time = this->Superclass::GetMTime();
  if (this->CutFunction)
  {
    time = std::max(time, this->CutFunction->GetMTime());
  }
  return time;
}

int vtkMesoStructuredCutaway::GetNumberOfAssignments() const
{
  return this->Internal->Assignments;
}

int vtkMesoStructuredCutaway::RequestData(vtkInformation*, vtkInformationVector** inputVector,
                                          vtkInformationVector* outputVector)
{
  vtkPolyData* atoms = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* structure = vtkPolyData::GetData(inputVector[1]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkPolyData* structure_output = vtkPolyData::GetData(outputVector, 1);
  output->Initialize();
  structure_output->Initialize();
  if (!atoms || atoms->GetNumberOfPoints() == 0)
  {
    vtkErrorMacro("No atoms to cut away.");
    return 0;
  }
  Internals& in = *this->Internal;
  try
  {
    vtkDataArray* ids = atoms->GetPointData()->GetArray("MoleculeId");
    Molecules molecules(atoms, ids);
    vtkDataArray* box_vectors = atoms->GetFieldData()->GetArray("PeriodicBoxVectors");
    if (this->MakeAssemblyWhole && box_vectors && box_vectors->GetNumberOfComponents() == 9 &&
        box_vectors->GetNumberOfTuples() > 0)
    {
      mesolens::PeriodicBox box;
      for (int k = 0; k < 9; ++k)
      {
        box.vectors[k / 3][k % 3] = box_vectors->GetComponent(0, k);
      }
      molecules.MakeWhole(box);
    }
    if (!structure)
    {
      // The structure from the molecules' centres, kept with the assignment.
      const bool same_molecules = in.Solver && in.IdArray == ids &&
        in.IdTime == (ids ? ids->GetMTime() : 0) && in.AtomCount == atoms->GetNumberOfPoints();
      if (!same_molecules || in.StructureVertices != this->StructureVertices)
      {
        mesolens::MeshQuality quality;
        const mesolens::TriangleMesh mesh = mesolens::structure_mesh(
          molecules.Centres, { static_cast<std::size_t>(this->StructureVertices), 0.0 }, &quality);
        vtkNew<vtkPolyData> made;
        vtkMesoSurfaceConversion::FromTriangleMesh(mesh, made);
        for (const auto& [name, value] :
             { std::pair<const char*, double>{ "MinAngle", quality.min_angle },
               std::pair<const char*, double>{ "MaxAngle", quality.max_angle },
               std::pair<const char*, double>{ "MeanEdge", quality.mean_edge },
               std::pair<const char*, double>{ "EdgeSpread", quality.edge_spread } })
        {
          vtkNew<vtkDoubleArray> field;
          field->SetName(name);
          field->InsertNextValue(value);
          made->GetFieldData()->AddArray(field);
        }
        in.Structure->ShallowCopy(made);
        in.StructureVertices = this->StructureVertices;
      }
      structure = in.Structure;
    }
    // A new assignment only for a new structure or a new set of molecules.
    if (!in.Solver || in.StructureData != structure || in.StructureTime != structure->GetMTime() ||
        in.IdArray != ids || in.IdTime != (ids ? ids->GetMTime() : 0) ||
        in.AtomCount != atoms->GetNumberOfPoints())
    {
      in.Solver.reset();
      const mesolens::TriangleMesh mesh = vtkMesoSurfaceConversion::ToTriangleMesh(structure);
      in.Solver = std::make_unique<mesolens::StructuredCutaway>(mesh, molecules.Centres);
      in.StructureData = structure;
      in.StructureTime = structure->GetMTime();
      in.IdArray = ids;
      in.IdTime = ids ? ids->GetMTime() : 0;
      in.AtomCount = atoms->GetNumberOfPoints();
      ++in.Assignments;
    }
    if (in.Solver->molecule_count() * 3 != molecules.Centres.size())
    {
      throw mesolens::InvalidInput("the molecules changed; the structure must be assigned again");
    }
    mesolens::CutawaySettings settings;
    settings.k = this->K;
    settings.fraction_hidden = this->FractionHidden;
    settings.inverted = this->Inverted;
    settings.random = this->RandomOrder;
    settings.seed = static_cast<std::uint64_t>(this->Seed);
    std::size_t in_cut = 0;
    vtkImplicitFunction* cut = this->CutFunction;
    const auto visible = in.Solver->visibility(
      [cut, &in_cut](const std::array<double, 3>& p) {
        double x[3] = { p[0], p[1], p[2] };
        const bool inside = cut && cut->FunctionValue(x) <= 0;
        in_cut += inside ? 1 : 0;
        return inside;
      },
      settings, molecules.Centres.data());
    const std::vector<double> priority = in.Solver->priorities(this->K);

    output->ShallowCopy(atoms);
    const vtkIdType n = atoms->GetNumberOfPoints();
    if (!molecules.Shifts.empty())
    {
      vtkNew<vtkPoints> moved;
      moved->SetDataTypeToFloat();
      moved->SetNumberOfPoints(n);
      for (vtkIdType a = 0; a < n; ++a)
      {
        double p[3];
        atoms->GetPoint(a, p);
        const auto& shift = molecules.Shifts[molecules.OfAtom[static_cast<std::size_t>(a)]];
        moved->SetPoint(a, p[0] + shift[0], p[1] + shift[1], p[2] + shift[2]);
      }
      output->SetPoints(moved);
    }
    vtkNew<vtkUnsignedCharArray> visible_atoms;
    visible_atoms->SetName("Visible");
    visible_atoms->SetNumberOfValues(n);
    vtkNew<vtkFloatArray> priority_atoms;
    priority_atoms->SetName("RemovalPriority");
    priority_atoms->SetNumberOfValues(n);
    for (vtkIdType a = 0; a < n; ++a)
    {
      const std::uint32_t m = molecules.OfAtom[static_cast<std::size_t>(a)];
      visible_atoms->SetValue(a, visible[m]);
      priority_atoms->SetValue(a, static_cast<float>(priority[m]));
    }
    output->GetPointData()->AddArray(visible_atoms);
    structure_output->ShallowCopy(structure);
    output->GetPointData()->AddArray(priority_atoms);
    std::size_t hidden = 0;
    for (std::uint8_t v : visible)
    {
      hidden += v ? 0 : 1;
    }
    for (const auto& [name, value] :
         { std::pair<const char*, std::size_t>{ "MoleculesInCut", in_cut },
           std::pair<const char*, std::size_t>{ "MoleculesHidden", hidden } })
    {
      vtkNew<vtkIdTypeArray> field;
      field->SetName(name);
      field->InsertNextValue(static_cast<vtkIdType>(value));
      output->GetFieldData()->AddArray(field);
    }
  }
  catch (const mesolens::Error& error)
  {
    output->Initialize();
    structure_output->Initialize();
    vtkErrorMacro("Cannot cut the molecules away: " << error.what());
    return 0;
  }
  return 1;
}

void vtkMesoStructuredCutaway::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "CutFunction: " << this->CutFunction << "\n";
  os << indent << "K: " << this->K << "\n";
  os << indent << "FractionHidden: " << this->FractionHidden << "\n";
  os << indent << "Inverted: " << this->Inverted << "\n";
  os << indent << "RandomOrder: " << this->RandomOrder << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "StructureVertices: " << this->StructureVertices << "\n";
  os << indent << "MakeAssemblyWhole: " << this->MakeAssemblyWhole << "\n";
  os << indent << "Assignments: " << this->Internal->Assignments << "\n";
}
