// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoStructureReader.h"

#include "vtkMesoArrayNames.h"
#include "vtkMesoAssemblyInstances.h"
#include "vtkMesoAtomPieces.h"

#include "vtkMesoAtomReaderParameters.h"
#include "vtkMesoAtomTableConversion.h"
#include "vtkMesoParallelFor.h"

#include "mesolens/common/errors.h"
#include "mesolens/io/file_names.h"
#include "mesolens/io/structure_file.h"
#include "mesolens/protein/assembly.h"

#include <vtkIntArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <vector>

vtkStandardNewMacro(vtkMesoStructureReader);

struct vtkMesoStructureReader::Cache
{
  mesolens::StructureFile File;
  vtkMTimeType ReadTime = 0;
  bool Valid = false;
  std::string Warnings;
};

vtkMesoStructureReader::vtkMesoStructureReader()
  : Parsed(new Cache)
{
  this->SetNumberOfOutputPorts(2);
  const mesolens::StructureReadParams defaults;
  this->KeepAllAlternateLocations = defaults.alt_locs == mesolens::AltLocPolicy::KeepAll;
  this->RemoveHydrogens = defaults.remove_hydrogens;
}

vtkMesoStructureReader::~vtkMesoStructureReader() = default;

int vtkMesoStructureReader::CanReadFile(const char* fileName)
{
  if (!fileName)
  {
    return 0;
  }
  const std::string extension = mesolens::file_extension(fileName, true);
  if (extension == "pdb" || extension == "ent" || extension == "cif" || extension == "mmcif")
  {
    std::ifstream probe(fileName);
    return probe ? 1 : 0;
  }
  // No known extension: sniff the first line for PDB records or a CIF data block.
  std::ifstream probe(fileName);
  std::string line;
  if (!probe || !std::getline(probe, line))
  {
    return 0;
  }
  for (const char* record : { "HEADER", "ATOM  ", "HETATM", "CRYST1", "MODEL ", "REMARK", "data_" })
  {
    if (line.rfind(record, 0) == 0)
    {
      return 1;
    }
  }
  return 0;
}

bool vtkMesoStructureReader::ReadIfNeeded()
{
  Cache& cache = *this->Parsed;
  if (cache.Valid && cache.ReadTime >= this->GetMTime())
  {
    return true;
  }
  cache.Valid = false;
  cache.File = mesolens::StructureFile{};
  cache.Warnings.clear();
  if (this->FileName.empty())
  {
    vtkErrorMacro("No FileName was set.");
    return false;
  }
  mesolens::StructureReadParams params = vtkMesoAtomReaderParameters(this);
  params.alt_locs = this->KeepAllAlternateLocations ? mesolens::AltLocPolicy::KeepAll
                                                    : mesolens::AltLocPolicy::HighestOccupancy;
  params.remove_hydrogens = this->RemoveHydrogens;
  try
  {
    cache.File = mesolens::read_structure(this->FileName, params, [this](double fraction) {
      this->UpdateProgress(0.9 * fraction);
      return !this->GetAbortExecute();
    });
  }
  catch (const mesolens::Error& e)
  {
    vtkErrorMacro("Cannot read " << this->FileName << ": " << e.what());
    return false;
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("Cannot read " << this->FileName << ": unexpected error: " << e.what());
    return false;
  }
  for (const std::string& warning : cache.File.warnings)
  {
    vtkWarningMacro(<< this->FileName << ": " << warning);
    cache.Warnings += warning + "\n";
  }
  cache.ReadTime = this->GetMTime();
  cache.Valid = true;
  return true;
}

int vtkMesoStructureReader::RequestInformation(vtkInformation*, vtkInformationVector**,
                                               vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
  outInfo->Set(vtkAlgorithm::CAN_HANDLE_PIECE_REQUEST(), 1); // whole molecules per piece
  if (!this->ReadIfNeeded())
  {
    // The update fails here, before RequestData: do not leave an earlier result behind.
    if (vtkPolyData* output = vtkPolyData::GetData(outInfo))
    {
      output->Initialize();
    }
    return 0;
  }
  const std::size_t models = this->Parsed->File.models.size();
  if (models > 1)
  {
    std::vector<double> steps(models);
    for (std::size_t m = 0; m < models; ++m)
    {
      steps[m] = static_cast<double>(m);
    }
    outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_STEPS(), steps.data(),
                 static_cast<int>(models));
    const double range[2] = { 0.0, static_cast<double>(models - 1) };
    outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
  }
  return 1;
}

int vtkMesoStructureReader::RequestData(vtkInformation*, vtkInformationVector**,
                                        vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkPolyData* output = vtkPolyData::GetData(outInfo);
  output->Initialize();
  vtkPolyData* copies = vtkPolyData::GetData(outputVector, 1);
  copies->Initialize();
  if (!this->ReadIfNeeded())
  {
    return 0;
  }
  const std::vector<mesolens::AtomTable>& models = this->Parsed->File.models;
  std::size_t model = 0;
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()))
  {
    const double requested = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());
    if (std::isfinite(requested))
    {
      const double clamped = std::min(std::max(requested, 0.0), double(models.size() - 1));
      model = static_cast<std::size_t>(std::lround(clamped));
    }
  }
  const mesolens::Assembly* assembly = nullptr;
  if (!this->ChosenAssembly(assembly))
  {
    return 0;
  }
  if (assembly && !this->WriteAssembly(models[model], *assembly, output, copies))
  {
    output->Initialize();
    copies->Initialize();
    return 0;
  }
  if (!assembly || !this->ExpandAssembly)
  {
    vtkMesoAtomTableConversion::ToPolyData(models[model], 1.0, output);
  }
  vtkMesoAtomTableConversion::SetFieldValue(output, vtkMesoArrayNames::ModelIndex, double(model));
  vtkMesoAtomTableConversion::SetFieldValue(output, vtkMesoArrayNames::CoarseGrained,
                                            this->Parsed->File.coarse_grained ? 1.0 : 0.0);
  vtkMesoAtomTableConversion::SetFieldString(output, vtkMesoArrayNames::Title,
                                             this->Parsed->File.title);
  if (models.size() > 1)
  {
    output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), double(model));
  }
  const auto [piece, pieces] = vtkMesoAtomPieces::Requested(outInfo);
  vtkMesoAtomPieces::KeepPiece(output, piece, pieces);
  this->UpdateProgress(1.0);
  return 1;
}

int vtkMesoStructureReader::GetNumberOfModels()
{
  this->UpdateInformation();
  return this->Parsed->Valid ? static_cast<int>(this->Parsed->File.models.size()) : 0;
}

const char* vtkMesoStructureReader::GetTitle()
{
  this->UpdateInformation();
  return this->Parsed->File.title.c_str();
}

bool vtkMesoStructureReader::WriteAssembly(const mesolens::AtomTable& asymmetric_unit,
                                           const mesolens::Assembly& assembly, vtkPolyData* atoms,
                                           vtkPolyData* copies)
{
  try
  {
    if (!vtkMesoAssemblyInstances::Write(mesolens::assembly_instances(asymmetric_unit, assembly),
                                         copies))
    {
      vtkWarningMacro("Assembly '" << this->Assembly << "' of " << this->FileName
                                   << " has operators that are not rotations: its copies "
                                      "have no AssemblyOrientation (expand it to draw it)");
    }
    if (!this->ExpandAssembly)
    {
      return true;
    }
    mesolens::AssemblyExpansionParams params;
    params.max_atoms = std::size_t(this->MaximumAssemblyAtoms);
    params.parallel_for = vtkMesoParallelFor::Get();
    const mesolens::AssemblyExpansion expansion =
      mesolens::expand_assembly(asymmetric_unit, assembly, params);
    vtkMesoAtomTableConversion::ToPolyData(expansion.atoms, 1.0, atoms);
    vtkNew<vtkIntArray> copy_of_atom;
    copy_of_atom->SetName(vtkMesoArrayNames::AssemblyCopy);
    copy_of_atom->SetNumberOfValues(vtkIdType(expansion.copy_of_atom.size()));
    std::copy(expansion.copy_of_atom.begin(), expansion.copy_of_atom.end(),
              copy_of_atom->GetPointer(0));
    atoms->GetPointData()->AddArray(copy_of_atom);
    return true;
  }
  catch (const mesolens::Error& e)
  {
    vtkErrorMacro("Cannot build assembly '" << this->Assembly << "' of " << this->FileName << ": "
                                            << e.what());
    return false;
  }
}

bool vtkMesoStructureReader::ChosenAssembly(const mesolens::Assembly*& assembly)
{
  assembly = nullptr;
  if (this->Assembly.empty())
  {
    return true;
  }
  const std::vector<mesolens::Assembly>& assemblies = this->Parsed->File.assemblies;
  assembly = mesolens::find_assembly(assemblies, this->Assembly);
  if (assembly)
  {
    return true;
  }
  std::string names;
  for (const mesolens::Assembly& a : assemblies)
  {
    names += (names.empty() ? "'" : ", '") + a.name + "'";
  }
  vtkErrorMacro(<< this->FileName << " defines no assembly '" << this->Assembly << "' ("
                << (names.empty() ? std::string("it defines none") : "it defines " + names)
                << "); Assembly \"\" gives the asymmetric unit.");
  return false;
}

int vtkMesoStructureReader::GetNumberOfAssemblies()
{
  this->UpdateInformation();
  return this->Parsed->Valid ? static_cast<int>(this->Parsed->File.assemblies.size()) : 0;
}

namespace {
const mesolens::Assembly* AssemblyAt(const mesolens::StructureFile& file, int index)
{
  return index >= 0 && std::size_t(index) < file.assemblies.size()
    ? &file.assemblies[std::size_t(index)]
    : nullptr;
}
}

const char* vtkMesoStructureReader::GetAssemblyName(int index)
{
  this->UpdateInformation();
  const mesolens::Assembly* assembly = AssemblyAt(this->Parsed->File, index);
  return assembly ? assembly->name.c_str() : "";
}

const char* vtkMesoStructureReader::GetAssemblyDetails(int index)
{
  this->UpdateInformation();
  const mesolens::Assembly* assembly = AssemblyAt(this->Parsed->File, index);
  return assembly ? assembly->details.c_str() : "";
}

vtkIdType vtkMesoStructureReader::GetAssemblyCopyCount(int index)
{
  this->UpdateInformation();
  const mesolens::Assembly* assembly = AssemblyAt(this->Parsed->File, index);
  return assembly ? vtkIdType(assembly->copy_count()) : 0;
}

vtkIdType vtkMesoStructureReader::GetAssemblyAtomCount(int index)
{
  this->UpdateInformation();
  const mesolens::Assembly* assembly = AssemblyAt(this->Parsed->File, index);
  if (!assembly || this->Parsed->File.models.empty())
  {
    return 0;
  }
  try
  {
    return vtkIdType(mesolens::assembly_atom_count(this->Parsed->File.models.front(), *assembly));
  }
  catch (const mesolens::Error&)
  {
    return 0;
  }
}

const char* vtkMesoStructureReader::GetWarnings()
{
  return this->Parsed->Warnings.c_str();
}

void vtkMesoStructureReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName.empty() ? "(none)" : this->FileName) << "\n";
  os << indent << "KeepAllAlternateLocations: " << this->KeepAllAlternateLocations << "\n";
  os << indent << "RemoveHydrogens: " << this->RemoveHydrogens << "\n";
  os << indent << "Assembly: " << (this->Assembly.empty() ? "(asymmetric unit)" : this->Assembly)
     << "\n";
  os << indent << "MaximumAssemblyAtoms: " << this->MaximumAssemblyAtoms << "\n";
  os << indent << "ExpandAssembly: " << this->ExpandAssembly << "\n";
}
