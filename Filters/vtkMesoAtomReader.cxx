// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoAtomReader.h"

#include "vtkMesoAtomReaderParameters.h"
#include "vtkMesoParallelFor.h"

#include <charconv>

namespace {
/// The double that a float's shortest decimal writes (0.45f gives 0.45, not 0.449999988): a
/// Core default held in a float reads back as written.
double as_written(float value)
{
  char text[32];
  const char* end = std::to_chars(text, text + sizeof(text), value).ptr;
  double written = value;
  std::from_chars(text, end, written);
  return written;
}
} // namespace

vtkMesoAtomReader::vtkMesoAtomReader()
{
  this->SetNumberOfInputPorts(0);
  const mesolens::StructureReadParams defaults;
  this->RemoveWaters = defaults.remove_waters;
  this->PerceiveBonds = defaults.perceive_bonds;
  this->BondTolerance = as_written(defaults.bonds.tolerance);
  this->CoarseGrainedBeadCutoff = as_written(defaults.bonds.bead_cutoff);
  this->ForceCoarseGrained = defaults.force_coarse_grained;
}

void vtkMesoAtomReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RemoveWaters: " << this->RemoveWaters << "\n";
  os << indent << "PerceiveBonds: " << this->PerceiveBonds << "\n";
  os << indent << "BondTolerance: " << this->BondTolerance << "\n";
  os << indent << "CoarseGrainedBeadCutoff: " << this->CoarseGrainedBeadCutoff << "\n";
  os << indent << "ForceCoarseGrained: " << this->ForceCoarseGrained << "\n";
}

mesolens::StructureReadParams vtkMesoAtomReaderParameters(vtkMesoAtomReader* reader)
{
  mesolens::StructureReadParams params;
  params.remove_waters = reader->GetRemoveWaters();
  params.perceive_bonds = reader->GetPerceiveBonds();
  params.bonds.tolerance = static_cast<float>(reader->GetBondTolerance());
  params.bonds.bead_cutoff = static_cast<float>(reader->GetCoarseGrainedBeadCutoff());
  params.force_coarse_grained = reader->GetForceCoarseGrained();
  params.parallel_for = vtkMesoParallelFor::Get();
  return params;
}
