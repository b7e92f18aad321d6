// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoStructuredCutaway.h"

#include "vtkMesoArrayNames.h"
#include "vtkMesoAtomPieces.h"

#include "vtkMesoIntValues.h"
#include "vtkMesoParallelFor.h"
#include "vtkMesoSelectAtoms.h"
#include "vtkMesoStamp.h"
#include "vtkMesoSurfaceConversion.h"

#include "mesolens/common/errors.h"
#include "mesolens/molecules/molecule_groups.h"
#include "mesolens/molecules/molecule_pbc.h"
#include "mesolens/cutaway/structure_mesh.h"
#include "mesolens/cutaway/structured_cutaway.h"

#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkExecutive.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkIdList.h>
#include <vtkIdTypeArray.h>
#include <vtkImplicitFunction.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <string>
#include <tuple>
#include <unordered_map>
#include <vector>

vtkStandardNewMacro(vtkMesoStructuredCutaway);
vtkCxxSetObjectMacro(vtkMesoStructuredCutaway, CutFunction, vtkImplicitFunction);

namespace {
/// Atoms grouped into molecules (mesolens::group_molecules), their types (residue names) and
/// centres, and the shifts that make the assembly whole.
struct Molecules
{
  mesolens::MoleculeGroups Groups;
  std::vector<int> Types;                    ///< per molecule, an index into TypeNames
  std::vector<std::string> TypeNames;        ///< residue names, in order of first appearance
  std::vector<double> Centres;               ///< 3 per molecule, after the shifts
  std::vector<std::array<double, 3>> Shifts; ///< per molecule; empty: none

  std::size_t Count() const
  {
    return this->Groups.count();
  }

  /// Groups the atoms by `ids` (nullptr: one molecule per atom); types from `names`, the
  /// residue name of each molecule's first atom.
  void Group(vtkIdType atoms, vtkDataArray* ids, vtkStringArray* names)
  {
    std::vector<int> id_copy;
    const int* id_values = vtkMesoIntValues(ids, id_copy);
    this->Groups = mesolens::group_molecules(id_values, static_cast<std::size_t>(atoms));
    this->Types.clear();
    this->TypeNames.clear();
    std::unordered_map<std::string, int> type_index;
    for (std::size_t m = 0; m < this->Groups.count(); ++m)
    {
      const std::uint32_t first_atom = this->Groups.atoms[this->Groups.first[m]];
      const std::string name = names ? names->GetValue(first_atom) : std::string();
      const auto type = type_index.emplace(name, static_cast<int>(this->TypeNames.size()));
      if (type.second)
      {
        this->TypeNames.push_back(name);
      }
      this->Types.push_back(type.first->second);
    }
  }

  /// The centres of the molecules a structure mesh is made from (no water, ions or proteins:
  /// mesolens::structure_molecules()).
  std::vector<double> StructureCentres() const
  {
    std::vector<std::size_t> atom_counts(this->Count());
    for (std::size_t m = 0; m < this->Count(); ++m)
    {
      atom_counts[m] = this->Groups.size_of(m);
    }
    const std::vector<std::uint8_t> kept =
      mesolens::structure_molecules(this->Types, this->TypeNames, atom_counts);
    std::vector<double> centres;
    for (std::size_t m = 0; m < this->Count(); ++m)
    {
      if (kept[m])
      {
        centres.insert(centres.end(), this->Centres.begin() + std::ptrdiff_t(3 * m),
                       this->Centres.begin() + std::ptrdiff_t(3 * m + 3));
      }
    }
    if (centres.size() < 3 * 4)
    {
      throw mesolens::InvalidInput(
        "only " + std::to_string(centres.size() / 3) + " of the " + std::to_string(this->Count()) +
        " molecules are neither water nor ions: too few to make a structure mesh from; give one");
    }
    return centres;
  }

  /// The molecules' centres (mean of their atoms), moved by the box vectors that gather the
  /// assembly in `box` when it is given.
  void Centre(vtkPoints* points, const mesolens::PeriodicBox* box)
  {
    if (auto* floats = vtkFloatArray::SafeDownCast(points->GetData()))
    {
      this->Centres = mesolens::molecule_centres(
        this->Groups, { floats->GetPointer(0), std::size_t(points->GetNumberOfPoints()) });
    }
    else
    {
      std::vector<double> coordinates(3 * static_cast<std::size_t>(points->GetNumberOfPoints()));
      for (vtkIdType a = 0; a < points->GetNumberOfPoints(); ++a)
      {
        points->GetPoint(a, coordinates.data() + 3 * a);
      }
      this->Centres = mesolens::molecule_centres(this->Groups, coordinates);
    }
    this->Shifts.clear();
    if (box)
    {
      this->Shifts = mesolens::assembly_shifts(this->Centres, *box);
      for (std::size_t m = 0; m < this->Shifts.size(); ++m)
      {
        for (int d = 0; d < 3; ++d)
        {
          this->Centres[3 * m + d] += this->Shifts[m][d];
        }
      }
    }
  }

  /// The atoms moved with their molecules' shifts (nullptr when there are none).
  vtkSmartPointer<vtkPoints> MovedAtoms(vtkPoints* atoms) const
  {
    if (this->Shifts.empty())
    {
      return nullptr;
    }
    auto moved = vtkSmartPointer<vtkPoints>::New();
    moved->SetDataTypeToFloat();
    moved->SetNumberOfPoints(atoms->GetNumberOfPoints());
    vtkMesoParallelFor::For(0, atoms->GetNumberOfPoints(), [&](vtkIdType begin, vtkIdType end) {
      for (vtkIdType a = begin; a < end; ++a)
      {
        double p[3];
        atoms->GetPoint(a, p);
        const auto& shift = this->Shifts[this->Groups.of_atom[static_cast<std::size_t>(a)]];
        moved->SetPoint(a, p[0] + shift[0], p[1] + shift[1], p[2] + shift[2]);
      }
    });
    return moved;
  }
};

/// The box of `vectors` (9 components: a, b, c), or a box that is not set.
mesolens::PeriodicBox BoxOf(vtkDataArray* vectors)
{
  mesolens::PeriodicBox box;
  if (vectors)
  {
    for (int k = 0; k < 9; ++k)
    {
      box.vectors[k / 3][k % 3] = vectors->GetComponent(0, k);
    }
  }
  return box;
}

void AddFieldValue(vtkFieldData* field, const char* name, double value)
{
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->InsertNextValue(value);
  field->AddArray(array);
}
} // namespace

/// Values [first, first + count) of an array, as a new array of the same type and name.
template<typename Array>
vtkSmartPointer<Array> Slice(Array* values, vtkIdType first, vtkIdType count)
{
  vtkSmartPointer<Array> slice;
  slice.TakeReference(Array::SafeDownCast(values->NewInstance()));
  slice->SetName(values->GetName());
  slice->SetNumberOfComponents(values->GetNumberOfComponents());
  slice->SetNumberOfTuples(count);
  for (vtkIdType i = 0; i < count; ++i)
  {
    slice->SetTuple(i, first + i, values);
  }
  return slice;
}

/// The atom input as the stages see it.
struct AtomInput
{
  vtkPolyData* Atoms = nullptr;
  vtkDataArray* Ids = nullptr;
  vtkStringArray* Names = nullptr;
  vtkDataArray* BoxVectors = nullptr; ///< 9 components, or nullptr
  std::array<vtkMesoStamp, 4> Stamps; ///< ids, names, points, box

  explicit AtomInput(vtkPolyData* atoms)
    : Atoms(atoms)
    , Ids(atoms->GetPointData()->GetArray(vtkMesoArrayNames::MoleculeId))
    , Names(vtkStringArray::SafeDownCast(
        atoms->GetPointData()->GetAbstractArray(vtkMesoArrayNames::ResidueName)))
    , BoxVectors(atoms->GetFieldData()->GetArray(vtkMesoArrayNames::PeriodicBoxVectors))
  {
    if (this->BoxVectors &&
        (this->BoxVectors->GetNumberOfComponents() != 9 ||
         this->BoxVectors->GetNumberOfTuples() == 0))
    {
      this->BoxVectors = nullptr;
    }
    this->Stamps = { vtkMesoStamp::Of(this->Ids), vtkMesoStamp::Of(this->Names),
                     vtkMesoStamp::Of(atoms->GetPoints()->GetData()),
                     vtkMesoStamp::Of(this->BoxVectors) };
  }
  vtkIdType Count() const
  {
    return this->Atoms->GetNumberOfPoints();
  }
};

struct vtkMesoStructuredCutaway::Internals
{
  // The molecules, kept while the input's points, ids, names and box stay.
  Molecules Groups;
  std::array<vtkMesoStamp, 4> GroupsFrom; // ids, names, points, box
  bool GroupsWhole = false;
  vtkSmartPointer<vtkPoints> MovedAtoms;
  int CentresVersion = 0;

  // The structure made from the molecules when none is connected (the mesh and its VTK form).
  mesolens::TriangleMesh StructureMesh;
  vtkNew<vtkPolyData> Structure;
  int StructureVertices = 0;
  double StructureRadius = -1;

  // The assignment: kept while the structure and the molecules' grouping stay.
  std::unique_ptr<mesolens::StructuredCutaway> Solver;
  vtkMesoStamp SolverStructure;
  std::array<vtkMesoStamp, 2> SolverGroups; // ids, names
  vtkIdType SolverAtoms = -1;
  int Assignments = 0;

  // The removal order: kept while the cut, the order settings and the centres stay.
  mesolens::RemovalOrder Order;
  std::tuple<double, bool, bool, bool, int, vtkMesoStamp, int, int> OrderFrom{};
  bool HasOrder = false;
  int Orderings = 0;

  // The atoms' priorities for one K and assignment.
  vtkSmartPointer<vtkFloatArray> AtomPriority;
  std::vector<double> MoleculePriority;
  std::pair<double, int> PriorityFrom{ 2.0, -1 };

  std::map<std::string, double> ResidueFractions;
  vtkNew<vtkMesoSelectAtoms> Select; // the hideable selection

  /// The fractions set per residue name, for the molecule types that have them.
  void AddResidueFractions(mesolens::CutawayParams& settings) const
  {
    for (std::size_t t = 0; t < this->Groups.TypeNames.size(); ++t)
    {
      const auto found = this->ResidueFractions.find(this->Groups.TypeNames[t]);
      if (found != this->ResidueFractions.end())
      {
        settings.fraction_by_type[static_cast<int>(t)] = found->second;
      }
    }
  }

  /// Stage 1: the molecules and their centres (made whole in the box when `whole`), kept while
  /// the atoms' ids, names, points and box stay.
  void GroupMolecules(const AtomInput& input, bool whole)
  {
    const bool same_grouping = this->GroupsFrom[0] == input.Stamps[0] &&
      this->GroupsFrom[1] == input.Stamps[1] &&
      this->Groups.Groups.of_atom.size() == std::size_t(input.Count());
    if (!same_grouping)
    {
      this->Groups.Group(input.Count(), input.Ids, input.Names);
    }
    if (!same_grouping || !(this->GroupsFrom[2] == input.Stamps[2]) ||
        !(this->GroupsFrom[3] == input.Stamps[3]) || this->GroupsWhole != whole)
    {
      this->GroupsFrom = {}; // stays invalid if Centre throws
      const mesolens::PeriodicBox box = BoxOf(input.BoxVectors);
      this->Groups.Centre(input.Atoms->GetPoints(), whole && input.BoxVectors ? &box : nullptr);
      this->MovedAtoms = this->Groups.MovedAtoms(input.Atoms->GetPoints());
      this->GroupsFrom = input.Stamps;
      this->GroupsWhole = whole;
      ++this->CentresVersion;
    }
  }

  /// Stage 2 without a connected structure: the structure mesh of the molecules' centres, made
  /// once and kept with the assignment over later frames.
  vtkPolyData* MadeStructure(const AtomInput& input, int vertices, double mid_surface_radius)
  {
    const bool same_molecules = this->Solver && this->SolverGroups[0] == input.Stamps[0] &&
      this->SolverGroups[1] == input.Stamps[1] && this->SolverAtoms == input.Count();
    if (same_molecules && this->StructureVertices == vertices &&
        this->StructureRadius == mid_surface_radius)
    {
      return this->Structure;
    }
    mesolens::StructureMeshParams params;
    params.vertices = static_cast<std::size_t>(vertices);
    params.mid_surface_radius = mid_surface_radius;
    params.box = BoxOf(input.BoxVectors); // a flat periodic patch is meshed over its cell
    mesolens::MeshQuality quality;
    this->StructureMesh = mesolens::structure_mesh(this->Groups.StructureCentres(), params,
                                                   &quality, vtkMesoParallelFor::Get());
    vtkNew<vtkPolyData> made;
    vtkMesoSurfaceConversion::FromTriangleMesh(this->StructureMesh, made);
    vtkFieldData* fields = made->GetFieldData();
    AddFieldValue(fields, vtkMesoArrayNames::MinAngle, quality.min_angle);
    AddFieldValue(fields, vtkMesoArrayNames::MaxAngle, quality.max_angle);
    AddFieldValue(fields, vtkMesoArrayNames::MeanEdge, quality.mean_edge);
    AddFieldValue(fields, vtkMesoArrayNames::EdgeSpread, quality.edge_spread);
    AddFieldValue(fields, vtkMesoArrayNames::BoundaryEdges, double(quality.boundary_edges));
    AddFieldValue(fields, vtkMesoArrayNames::BoundaryLoops, double(quality.boundary_loops));
    AddFieldValue(fields, vtkMesoArrayNames::Components, double(quality.components));
    this->Structure->ShallowCopy(made);
    this->Structure->Modified();
    this->StructureVertices = vertices;
    this->StructureRadius = mid_surface_radius;
    return this->Structure;
  }

  /// Stage 3: the molecules assigned to the structure's triangles, only for a new structure or
  /// a new set of molecules.
  void Assign(vtkPolyData* structure, const AtomInput& input)
  {
    if (this->Solver && this->SolverStructure == vtkMesoStamp::Of(structure) &&
        this->SolverGroups[0] == input.Stamps[0] && this->SolverGroups[1] == input.Stamps[1] &&
        this->SolverAtoms == input.Count())
    {
      return;
    }
    this->Solver.reset();
    this->HasOrder = false;
    // The structure made here is at hand as a mesh; a connected one is converted.
    const mesolens::TriangleMesh mesh = structure == this->Structure.GetPointer()
      ? this->StructureMesh
      : vtkMesoSurfaceConversion::ToTriangleMesh(structure);
    this->Solver = std::make_unique<mesolens::StructuredCutaway>(
      mesh, this->Groups.Centres, this->Groups.Types, vtkMesoParallelFor::Get());
    this->SolverStructure = vtkMesoStamp::Of(structure);
    this->SolverGroups = { input.Stamps[0], input.Stamps[1] };
    this->SolverAtoms = input.Count();
    ++this->Assignments;
  }

  /// Stage 4: the removal order for the cut (kept while only the fractions change) and the
  /// molecules it leaves visible, of those that may be hidden (`hideable`; empty: all).
  template<typename OrderKey>
  std::vector<std::uint8_t> Visibility(vtkImplicitFunction* cut,
                                       const mesolens::CutawayParams& settings,
                                       const OrderKey& order_from,
                                       const std::vector<std::uint8_t>& hideable)
  {
    if (!this->HasOrder || this->OrderFrom != order_from)
    {
      this->Order = this->Solver->removal_order(
        [cut](const std::array<double, 3>& p) {
          double x[3] = { p[0], p[1], p[2] };
          return cut && cut->FunctionValue(x) <= 0;
        },
        settings, this->Groups.Centres);
      this->OrderFrom = order_from;
      this->HasOrder = true;
      ++this->Orderings;
    }
    if (hideable.empty())
    {
      return this->Solver->visibility(this->Order, settings);
    }
    // The fractions apply to the molecules that may be hidden: the others leave the order.
    mesolens::RemovalOrder order = this->Order;
    for (auto& entry : order.by_type)
    {
      std::vector<std::uint32_t>& molecules = entry.second;
      molecules.erase(std::remove_if(molecules.begin(), molecules.end(),
                                     [&hideable](std::uint32_t m) { return !hideable[m]; }),
                      molecules.end());
    }
    return this->Solver->visibility(order, settings);
  }

  /// Per molecule, 1 when the selection matches every one of its atoms; empty for no selection.
  std::vector<std::uint8_t> Hideable(vtkPolyData* atoms, const std::string& selection)
  {
    if (selection.empty())
    {
      return {};
    }
    this->Select->SetInputData(atoms);
    this->Select->SetSelection(selection.c_str());
    this->Select->SetMaskArrayName("Hideable");
    if (!this->Select->GetExecutive()->Update())
    {
      throw mesolens::InvalidInput("the hideable selection failed (see the error above)");
    }
    vtkDataArray* mask = this->Select->GetOutput()->GetPointData()->GetArray("Hideable");
    const mesolens::MoleculeGroups& groups = this->Groups.Groups;
    std::vector<std::uint8_t> hideable(groups.count(), 1);
    for (std::size_t a = 0; a < groups.of_atom.size(); ++a)
    {
      if (mask->GetComponent(vtkIdType(a), 0) == 0.0)
      {
        hideable[groups.of_atom[a]] = 0;
      }
    }
    return hideable;
  }

  /// Stage 5, the per-atom arrays: each atom's removal priority (kept per K and assignment)
  /// and visibility.
  vtkSmartPointer<vtkUnsignedCharArray> AtomArrays(double k,
                                                   const std::vector<std::uint8_t>& visible,
                                                   vtkIdType n)
  {
    const std::vector<std::uint32_t>& of_atom = this->Groups.Groups.of_atom;
    if (this->PriorityFrom != std::make_pair(k, this->Assignments) || !this->AtomPriority ||
        this->AtomPriority->GetNumberOfValues() != n)
    {
      this->MoleculePriority = this->Solver->priorities(k);
      this->AtomPriority = vtkSmartPointer<vtkFloatArray>::New();
      this->AtomPriority->SetName(vtkMesoArrayNames::RemovalPriority);
      this->AtomPriority->SetNumberOfValues(n);
      float* out = this->AtomPriority->GetPointer(0);
      const std::vector<double>& priority = this->MoleculePriority;
      vtkMesoParallelFor::For(0, n, [&](vtkIdType begin, vtkIdType end) {
        for (vtkIdType a = begin; a < end; ++a)
        {
          out[a] = static_cast<float>(priority[of_atom[static_cast<std::size_t>(a)]]);
        }
      });
      this->PriorityFrom = { k, this->Assignments };
    }
    auto visible_atoms = vtkSmartPointer<vtkUnsignedCharArray>::New();
    visible_atoms->SetName(vtkMesoArrayNames::Visible);
    visible_atoms->SetNumberOfValues(n);
    unsigned char* mask = visible_atoms->GetPointer(0);
    vtkMesoParallelFor::For(0, n, [&](vtkIdType begin, vtkIdType end) {
      for (vtkIdType a = begin; a < end; ++a)
      {
        mask[a] = visible[of_atom[static_cast<std::size_t>(a)]];
      }
    });
    return visible_atoms;
  }

  /// The molecules' visibility and priority, and the counts in the cut and hidden, as field
  /// data of `output`.
  void AddMoleculeFields(const std::vector<std::uint8_t>& visible, vtkPolyData* output) const
  {
    std::size_t hidden = 0;
    vtkNew<vtkUnsignedCharArray> molecule_visible;
    molecule_visible->SetName(vtkMesoArrayNames::MoleculeVisible);
    molecule_visible->SetNumberOfValues(static_cast<vtkIdType>(visible.size()));
    vtkNew<vtkFloatArray> molecule_priority;
    molecule_priority->SetName(vtkMesoArrayNames::MoleculeRemovalPriority);
    molecule_priority->SetNumberOfValues(static_cast<vtkIdType>(visible.size()));
    for (std::size_t m = 0; m < visible.size(); ++m)
    {
      hidden += visible[m] ? 0 : 1;
      molecule_visible->SetValue(static_cast<vtkIdType>(m), visible[m]);
      molecule_priority->SetValue(static_cast<vtkIdType>(m),
                                  static_cast<float>(this->MoleculePriority[m]));
    }
    output->GetFieldData()->AddArray(molecule_visible);
    output->GetFieldData()->AddArray(molecule_priority);
    for (const auto& [name, value] :
         { std::pair<const char*, std::size_t>{ vtkMesoArrayNames::MoleculesInCut,
                                                this->Order.in_cut() },
           std::pair<const char*, std::size_t>{ vtkMesoArrayNames::MoleculesHidden, hidden } })
    {
      vtkNew<vtkIdTypeArray> field;
      field->SetName(name);
      field->InsertNextValue(static_cast<vtkIdType>(value));
      output->GetFieldData()->AddArray(field);
    }
  }
};

vtkMesoStructuredCutaway::vtkMesoStructuredCutaway()
  : Internal(std::make_unique<Internals>())
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(2);
  const mesolens::CutawayParams cut;
  this->K = cut.k;
  this->FractionHidden = cut.fraction_hidden;
  this->Inverted = cut.inverted;
  this->RandomOrder = cut.random;
  this->ProbabilisticOrder = cut.probabilistic;
  this->Seed = static_cast<int>(cut.seed);
  const mesolens::StructureMeshParams structure;
  this->StructureVertices = static_cast<int>(structure.vertices);
  this->StructureMidSurfaceRadius = structure.mid_surface_radius;
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

void vtkMesoStructuredCutaway::SetFractionHiddenOfResidue(const char* residue, double fraction)
{
  if (!residue)
  {
    return;
  }
  this->Internal->ResidueFractions[residue] = std::clamp(fraction, 0.0, 1.0);
  this->Modified();
}

void vtkMesoStructuredCutaway::RemoveAllResidueFractions()
{
  if (!this->Internal->ResidueFractions.empty())
  {
    this->Internal->ResidueFractions.clear();
    this->Modified();
  }
}

int vtkMesoStructuredCutaway::GetNumberOfAssignments() const
{
  return this->Internal->Assignments;
}

int vtkMesoStructuredCutaway::GetNumberOfOrderings() const
{
  return this->Internal->Orderings;
}

int vtkMesoStructuredCutaway::RequestUpdateExtent(vtkInformation*,
                                                  vtkInformationVector** inputVector,
                                                  vtkInformationVector* outputVector)
{
  vtkMesoAtomPieces::RequestWholeInputsWhenStreaming(inputVector, 2, outputVector);
  return 1;
}

int vtkMesoStructuredCutaway::RequestData(vtkInformation*, vtkInformationVector** inputVector,
                                          vtkInformationVector* outputVector)
{
  vtkPolyData* local_atoms = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkPolyData* structure_output = vtkPolyData::GetData(outputVector, 1);
  output->Initialize();
  structure_output->Initialize();
  // On many processes every one cuts every process's atoms, so that all hide the molecules one
  // process would, and keeps its own.
  // What AtomInput reads; every array for a selection.
  static const std::initializer_list<const char*> grouping = { vtkMesoArrayNames::MoleculeId,
                                                               vtkMesoArrayNames::ResidueName };
  const vtkMesoAtomPieces::GatheredInput gathered(
    inputVector[0], outputVector, vtkMesoAtomPieces::GatheredInput::KeepWhole,
    this->HideableSelection.empty() ? grouping : std::initializer_list<const char*>{});
  vtkPolyData* atoms = gathered.Whole();
  const vtkIdType first = gathered.FirstOwn();
  const vtkMesoAtomPieces::GatheredInput whole_structure(
    inputVector[1], outputVector, vtkMesoAtomPieces::GatheredInput::KeepWhole);
  vtkPolyData* structure =
    inputVector[1]->GetInformationObject(0) ? whole_structure.Whole() : nullptr;
  if (atoms->GetNumberOfPoints() == 0)
  {
    vtkErrorMacro("No atoms to cut away.");
    return 0;
  }
  const vtkIdType local_count = local_atoms ? local_atoms->GetNumberOfPoints() : 0;
  if (local_count == 0)
  {
    return 1; // another process holds the atoms
  }
  Internals& in = *this->Internal;
  try
  {
    const AtomInput input(atoms);
    in.GroupMolecules(input, this->MakeAssemblyWhole);
    if (!structure)
    {
      structure = in.MadeStructure(input, this->StructureVertices, this->StructureMidSurfaceRadius);
    }
    in.Assign(structure, input);
    mesolens::CutawayParams settings;
    settings.k = this->K;
    settings.fraction_hidden = this->FractionHidden;
    settings.inverted = this->Inverted;
    settings.random = this->RandomOrder;
    settings.probabilistic = this->ProbabilisticOrder;
    settings.seed = static_cast<std::uint64_t>(this->Seed);
    in.AddResidueFractions(settings);
    const auto order_from = std::make_tuple(
      this->K, this->Inverted, this->RandomOrder, this->ProbabilisticOrder, this->Seed,
      vtkMesoStamp::Of(this->CutFunction), in.CentresVersion, in.Assignments);
    const std::vector<std::uint8_t> visible = in.Visibility(
      this->CutFunction, settings, order_from, in.Hideable(atoms, this->HideableSelection));

    vtkNew<vtkPolyData> all;
    all->ShallowCopy(local_atoms);
    vtkSmartPointer<vtkUnsignedCharArray> visible_atoms =
      in.AtomArrays(this->K, visible, atoms->GetNumberOfPoints());
    vtkSmartPointer<vtkFloatArray> priority = in.AtomPriority;
    if (gathered.Gathered())
    {
      // This process's atoms of all.
      visible_atoms = Slice(visible_atoms.GetPointer(), first, local_count);
      priority = Slice(priority.GetPointer(), first, local_count);
      if (in.MovedAtoms)
      {
        vtkNew<vtkPoints> moved;
        moved->SetData(Slice(in.MovedAtoms->GetData(), first, local_count));
        all->SetPoints(moved);
      }
    }
    else if (in.MovedAtoms)
    {
      all->SetPoints(in.MovedAtoms); // the same object while the input stays: no new upload
    }
    all->GetPointData()->AddArray(visible_atoms);
    all->GetPointData()->AddArray(priority);
    if (!gathered.Gathered() && gathered.PieceCount() > 1)
    {
      // Streaming: cut with every atom, keep the piece asked for.
      vtkMesoAtomPieces::KeepPiece(all, gathered.Piece(), gathered.PieceCount());
      visible_atoms = vtkUnsignedCharArray::SafeDownCast(
        all->GetPointData()->GetArray(vtkMesoArrayNames::Visible));
    }
    if (this->ExtractVisibleAtoms)
    {
      vtkMesoAtomPieces::ExtractAtoms(all, visible_atoms, output);
    }
    else
    {
      output->ShallowCopy(all);
    }
    structure_output->ShallowCopy(structure);
    in.AddMoleculeFields(visible, output);
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
  os << indent << "ProbabilisticOrder: " << this->ProbabilisticOrder << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "StructureVertices: " << this->StructureVertices << "\n";
  os << indent << "StructureMidSurfaceRadius: " << this->StructureMidSurfaceRadius << "\n";
  os << indent << "ExtractVisibleAtoms: " << this->ExtractVisibleAtoms << "\n";
  os << indent << "HideableSelection: "
     << (this->HideableSelection.empty() ? "(every molecule)" : this->HideableSelection) << "\n";
  os << indent << "Orderings: " << this->Internal->Orderings << "\n";
  os << indent << "MakeAssemblyWhole: " << this->MakeAssemblyWhole << "\n";
  os << indent << "Assignments: " << this->Internal->Assignments << "\n";
}
