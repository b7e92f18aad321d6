// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoAtomReader.h"

#include "vtkMesoAtomReaderParameters.h"
#include "vtkMesoParallelFor.h"

vtkMesoAtomReader::vtkMesoAtomReader()
{
  this->SetNumberOfInputPorts(0);
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
