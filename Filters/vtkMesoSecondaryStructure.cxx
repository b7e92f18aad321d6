// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoSecondaryStructure.h"

#include "vtkMesoArrayNames.h"
#include "vtkMesoAtomPieces.h"

#include "vtkMesoAtomInput.h"
#include "vtkMesoAtomTableConversion.h"
#include "vtkMesoParallelFor.h"
#include "vtkMesoStamp.h"

#include "mesolens/protein/dssp.h"
#include "mesolens/common/errors.h"

#include <vtkDataArray.h>
#include <vtkDataObject.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkUnsignedCharArray.h>

#include <array>
#include <cmath>
#include <optional>
#include <vector>

vtkStandardNewMacro(vtkMesoSecondaryStructure);

struct vtkMesoSecondaryStructure::Internals
{
  std::optional<mesolens::SecondaryStructureHysteresis> Hysteresis;
  vtkMTimeType SettingsTime = 0;
  double LastTime = -HUGE_VAL;
  std::vector<mesolens::SecondaryStructure> LastShown;
  // The backbone's layout (which atom is which), kept while the atoms' names and residues stay:
  // a new frame then only reads positions.
  vtkMesoAtomInput Atoms;
  mesolens::ProteinBackbone Backbone;
  std::vector<int> BackboneResidueOfAtom; ///< per atom, -1: not an amino acid's

  /// Stage 1: the backbone of this frame; its layout read again only for new atoms.
  void ReadBackbone(vtkPolyData* atoms)
  {
    if (!this->Atoms.ReadLayout(atoms))
    {
      this->Backbone.update_positions(this->Atoms.Positions(atoms));
      return;
    }
    const mesolens::AtomTable& table = this->Atoms.Layout();
    this->Backbone = mesolens::protein_backbone(table);
    // Per atom, its residue's place among the backbone residues (-1: none).
    std::vector<int> slot_of_residue;
    for (std::size_t r = 0; r < this->Backbone.residue_index.size(); ++r)
    {
      const auto index = static_cast<std::size_t>(std::max(0, this->Backbone.residue_index[r]));
      if (index >= slot_of_residue.size())
      {
        slot_of_residue.resize(index + 1, -1);
      }
      slot_of_residue[index] = static_cast<int>(r);
    }
    this->BackboneResidueOfAtom.assign(table.residue_indices.size(), -1);
    for (std::size_t a = 0; a < table.residue_indices.size(); ++a)
    {
      const int residue = table.residue_indices[a];
      if (residue >= 0 && std::size_t(residue) < slot_of_residue.size())
      {
        this->BackboneResidueOfAtom[a] = slot_of_residue[std::size_t(residue)];
      }
    }
  }

  /// Stage 3, a played trajectory: the classes shown after the hysteresis over `frames`
  /// successive time steps (1: none). New settings (`settings_time`) or a jump back in time
  /// start over; the same frame again shows what it showed.
  std::vector<mesolens::SecondaryStructure> Shown(
    const std::vector<mesolens::SecondaryStructure>& assigned, int frames, double time,
    vtkMTimeType settings_time)
  {
    std::vector<mesolens::SecondaryStructure> classes = assigned;
    if (frames > 1)
    {
      if (!this->Hysteresis || this->SettingsTime != settings_time || time < this->LastTime)
      {
        this->LastShown.clear();
        this->Hysteresis.emplace(frames);
        this->SettingsTime = settings_time;
      }
      if (time != this->LastTime || this->LastShown.size() != assigned.size())
      {
        this->LastShown = this->Hysteresis->update(assigned);
      }
      classes = this->LastShown;
    }
    else
    {
      this->Hysteresis.reset();
    }
    this->LastTime = time;
    return classes;
  }
};

namespace {
/// The atoms' positions as floats (a pointer into the points when they are floats already).
/// Stage 4a: per atom, its residue's class (SecondaryStructure) and run (SecondaryStructureId).
void add_atom_classes(const std::vector<mesolens::SecondaryStructure>& classes,
                      const std::vector<int>& runs, const std::vector<int>& residue_of_atom,
                      vtkPolyData* output)
{
  const auto n = static_cast<vtkIdType>(residue_of_atom.size());
  vtkNew<vtkUnsignedCharArray> per_atom;
  per_atom->SetName(vtkMesoArrayNames::SecondaryStructure);
  per_atom->SetNumberOfValues(n);
  vtkNew<vtkIntArray> per_atom_run;
  per_atom_run->SetName(vtkMesoArrayNames::SecondaryStructureId);
  per_atom_run->SetNumberOfValues(n);
  for (vtkIdType a = 0; a < n; ++a)
  {
    const int slot = residue_of_atom[std::size_t(a)];
    per_atom->SetValue(a, slot >= 0 ? static_cast<unsigned char>(classes[std::size_t(slot)]) : 0);
    per_atom_run->SetValue(a, slot >= 0 ? runs[std::size_t(slot)] : -1);
  }
  output->GetPointData()->AddArray(per_atom);
  output->GetPointData()->AddArray(per_atom_run);
}

/// Stage 4b: per residue its class and residue index, and per chain its DSSP string, in field
/// data.
void add_residue_classes(const std::vector<mesolens::SecondaryStructure>& classes,
                         const mesolens::ProteinBackbone& backbone, vtkPolyData* output)
{
  vtkNew<vtkUnsignedCharArray> per_residue;
  per_residue->SetName(vtkMesoArrayNames::ResidueSecondaryStructure);
  vtkNew<vtkIntArray> residue_indices;
  residue_indices->SetName(vtkMesoArrayNames::ResidueIndexOfAssignment);
  vtkNew<vtkStringArray> chains;
  chains->SetName(vtkMesoArrayNames::DSSP);
  std::string letters;
  for (std::size_t r = 0; r < classes.size(); ++r)
  {
    per_residue->InsertNextValue(static_cast<unsigned char>(classes[r]));
    residue_indices->InsertNextValue(backbone.residue_index[r]);
    if (r > 0 && backbone.residues[r].chain != backbone.residues[r - 1].chain)
    {
      chains->InsertNextValue(letters);
      letters.clear();
    }
    letters += mesolens::dssp_string({ classes[r] });
  }
  if (!letters.empty())
  {
    chains->InsertNextValue(letters);
  }
  output->GetFieldData()->AddArray(per_residue);
  output->GetFieldData()->AddArray(residue_indices);
  output->GetFieldData()->AddArray(chains);
}
} // namespace

vtkMesoSecondaryStructure::vtkMesoSecondaryStructure()
  : Internal(std::make_unique<Internals>())
{
  const mesolens::DsspParams defaults;
  this->PiHelixPriority = defaults.pi_helix_priority;
  this->PolyprolineStretch = defaults.polyproline_stretch;
  this->Bulges = defaults.bulges;
  this->UseFileHydrogens = defaults.file_hydrogens;
}

vtkMesoSecondaryStructure::~vtkMesoSecondaryStructure() = default;

namespace {
/// Whether any atom has a class other than coil in the input's `SecondaryStructure`.
bool has_records(vtkPolyData* atoms)
{
  vtkDataArray* classes = atoms->GetPointData()->GetArray(vtkMesoArrayNames::SecondaryStructure);
  for (vtkIdType a = 0; classes && a < classes->GetNumberOfTuples(); ++a)
  {
    if (classes->GetComponent(a, 0) != 0)
    {
      return true;
    }
  }
  return false;
}

/// Per residue, the index of its run of one class (helix, strand, bridge, polyproline) along
/// its chain, -1 for coil, turn and bend.
std::vector<int> run_ids(const std::vector<mesolens::SecondaryStructure>& classes,
                         const std::vector<mesolens::BackboneResidue>& residues)
{
  using mesolens::SecondaryStructure;
  std::vector<int> ids(classes.size(), -1);
  int next = 0;
  for (std::size_t r = 0; r < classes.size(); ++r)
  {
    const SecondaryStructure s = classes[r];
    if (s == SecondaryStructure::Coil || s == SecondaryStructure::Turn ||
        s == SecondaryStructure::Bend)
    {
      continue;
    }
    const bool continues =
      r > 0 && classes[r - 1] == s && residues[r - 1].chain == residues[r].chain;
    ids[r] = continues ? ids[r - 1] : next++;
  }
  return ids;
}
} // namespace

int vtkMesoSecondaryStructure::RequestUpdateExtent(vtkInformation*,
                                                   vtkInformationVector** inputVector,
                                                   vtkInformationVector* outputVector)
{
  vtkMesoAtomPieces::RequestWholeInputsWhenStreaming(inputVector, 1, outputVector);
  return 1;
}

int vtkMesoSecondaryStructure::RequestData(vtkInformation*, vtkInformationVector** inputVector,
                                           vtkInformationVector* outputVector)
{
  // On many processes: computed on every process's atoms, this process's kept.
  const vtkMesoAtomPieces::GatheredInput gathered(inputVector[0], outputVector,
                                                  vtkMesoAtomPieces::GatheredInput::KeepOwn);
  vtkPolyData* atoms = gathered.Whole();
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  output->Initialize();
  if (!atoms || atoms->GetNumberOfPoints() == 0)
  {
    vtkErrorMacro("No atoms to assign a secondary structure to.");
    return 0;
  }
  Internals& in = *this->Internal;
  try
  {
    in.ReadBackbone(atoms);
    output->ShallowCopy(atoms);
    if (this->KeepFileRecords && has_records(atoms))
    {
      return 1; // the file's classes as they are
    }
    mesolens::DsspParams params;
    params.pi_helix_priority = this->PiHelixPriority;
    params.polyproline_stretch = this->PolyprolineStretch;
    params.bulges = this->Bulges;
    params.file_hydrogens = this->UseFileHydrogens;
    const mesolens::DsspResult result =
      mesolens::assign_secondary_structure(in.Backbone.residues, params, vtkMesoParallelFor::Get());
    const double time = atoms->GetInformation()->Has(vtkDataObject::DATA_TIME_STEP())
      ? atoms->GetInformation()->Get(vtkDataObject::DATA_TIME_STEP())
      : 0.0;
    const std::vector<mesolens::SecondaryStructure> classes =
      in.Shown(result.structure, this->HysteresisFrames, time, this->GetMTime());
    add_atom_classes(classes, run_ids(classes, in.Backbone.residues), in.BackboneResidueOfAtom,
                     output);
    add_residue_classes(classes, in.Backbone, output);
    vtkMesoAtomTableConversion::SetFieldValue(output, vtkMesoArrayNames::HydrogenBonds,
                                              double(result.hydrogen_bonds));
  }
  catch (const mesolens::Error& error)
  {
    output->Initialize();
    vtkErrorMacro("Cannot assign the secondary structure: " << error.what());
    return 0;
  }
  return 1;
}

void vtkMesoSecondaryStructure::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "KeepFileRecords: " << this->KeepFileRecords << "\n";
  os << indent << "PiHelixPriority: " << this->PiHelixPriority << "\n";
  os << indent << "PolyprolineStretch: " << this->PolyprolineStretch << "\n";
  os << indent << "Bulges: " << this->Bulges << "\n";
  os << indent << "UseFileHydrogens: " << this->UseFileHydrogens << "\n";
  os << indent << "HysteresisFrames: " << this->HysteresisFrames << "\n";
}
