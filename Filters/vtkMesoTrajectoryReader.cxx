// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoTrajectoryReader.h"

#include "vtkMesoArrayNames.h"
#include "vtkMesoAtomPieces.h"

#include "vtkMesoAtomTableConversion.h"
#include "vtkMesoAtomReaderParameters.h"

#include "mesolens/common/errors.h"
#include "mesolens/io/file_names.h"
#include "mesolens/io/gro_topology.h"
#include "mesolens/molecules/molecule_assignment.h"
#include "mesolens/molecules/molecule_pbc.h"
#include "mesolens/io/structure_file.h"
#include "mesolens/io/trajectory_file.h"

#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <algorithm>
#include <functional>
#include <cmath>

vtkStandardNewMacro(vtkMesoTrajectoryReader);

struct vtkMesoTrajectoryReader::State
{
  bool Valid = false;
  vtkMTimeType OpenTime = 0;
  mesolens::AtomTable Topology;          // every atom, with molecules and bonds
  std::vector<std::size_t> KeptAtoms;    // output atoms (empty: all)
  vtkSmartPointer<vtkPolyData> Template; // output arrays, built once
  // One piece of many (MPI ranks): its template and the file atoms it keeps, built once.
  std::pair<int, int> PieceOf{ 0, 1 };
  vtkSmartPointer<vtkPolyData> PieceTemplate;
  std::vector<std::size_t> PieceAtoms;

  /// The template and kept atoms of one piece (the whole template for one).
  vtkPolyData* TemplateOf(int piece, int pieces)
  {
    if (pieces <= 1)
    {
      return this->Template;
    }
    if (!this->PieceTemplate || this->PieceOf != std::pair{ piece, pieces })
    {
      const std::vector<vtkIdType> atoms =
        vtkMesoAtomPieces::AtomsOfPiece(this->Template, piece, pieces);
      this->PieceTemplate = vtkSmartPointer<vtkPolyData>::New();
      vtkMesoAtomPieces::ExtractAtomIds(this->Template, atoms, this->PieceTemplate);
      this->PieceAtoms.clear();
      for (const vtkIdType a : atoms)
      {
        this->PieceAtoms.push_back(this->KeptAtoms.empty() ? std::size_t(a)
                                                           : this->KeptAtoms[std::size_t(a)]);
      }
      this->PieceOf = { piece, pieces };
    }
    return this->PieceTemplate;
  }
  std::unique_ptr<mesolens::TrajectoryFile> File; // null: the topology is the only frame
  bool TrajectoryIsTopology = false;              // the frames are those of the topology file
  std::vector<double> Times;                      // ps
  std::unique_ptr<mesolens::MoleculeContinuity> Continuity;
  mesolens::MoleculeGroups Molecules; // the topology's, grouped once for every frame

  /// Frame `index` of the file (the topology's own when there is no trajectory, or when the
  /// trajectory is the topology file and index is 0), its molecules made whole when asked.
  mesolens::TrajectoryFrame WholeFrame(std::size_t index, bool make_whole) const
  {
    mesolens::TrajectoryFrame frame;
    if (!this->File || (index == 0 && this->TrajectoryIsTopology))
    {
      frame.positions = this->Topology.positions;
      frame.box = this->Topology.box;
      if (this->File)
      {
        frame.time_ps = this->Times.front();
      }
    }
    else
    {
      frame = this->File->read_frame(index);
    }
    if (make_whole)
    {
      mesolens::make_molecules_whole(frame.positions, this->Molecules, frame.box);
    }
    return frame;
  }

  /// Frame `index`, whole and, with Continuity, continuous with the frames before it: those not
  /// seen yet are visited once, in order, each reported to `visited`, which returns false to
  /// stop (then false).
  bool ContinuousFrame(std::size_t index, bool make_whole,
                       const std::function<bool(std::size_t)>& visited,
                       mesolens::TrajectoryFrame& frame)
  {
    if (this->Continuity)
    {
      for (std::size_t k = this->Continuity->known_frames(); k < index; ++k)
      {
        mesolens::TrajectoryFrame earlier = this->WholeFrame(k, make_whole);
        this->Continuity->add_frame(k, earlier.positions, earlier.box);
        if (!visited(k))
        {
          return false;
        }
      }
    }
    frame = this->WholeFrame(index, make_whole);
    if (this->Continuity)
    {
      if (this->Continuity->known_frames() == index)
      {
        this->Continuity->add_frame(index, frame.positions, frame.box);
      }
      else
      {
        this->Continuity->apply(index, frame.positions, frame.box);
      }
    }
    return true;
  }
};

vtkMesoTrajectoryReader::vtkMesoTrajectoryReader()
  : Internal(new State)
{
}

vtkMesoTrajectoryReader::~vtkMesoTrajectoryReader() = default;

namespace {

/// Names, residues and connectivity of the topology; bonds are perceived on whole molecules.
mesolens::AtomTable load_topology(const std::string& path,
                                  const mesolens::StructureReadParams& params)
{
  mesolens::AtomTable table;
  std::vector<mesolens::Bond> explicit_bonds;
  if (mesolens::file_extension(path) == "gro")
  {
    table = mesolens::read_gro_topology(path);
  }
  else
  {
    mesolens::StructureReadParams structure_params;
    structure_params.alt_locs = mesolens::AltLocPolicy::KeepAll;
    structure_params.perceive_bonds = false; // perceived below, after making molecules whole
    mesolens::StructureFile file = mesolens::read_structure(path, structure_params);
    table = std::move(file.models.front());
    explicit_bonds = table.bonds;
  }
  mesolens::assign_residues(table);
  mesolens::assign_molecules(table);
  mesolens::AtomTable whole = table;
  mesolens::make_molecules_whole(whole.positions, whole.molecule_ids.data(), whole.box);
  const bool elements_given = mesolens::file_extension(path) != "gro";
  mesolens::build_connectivity(whole, explicit_bonds, params, elements_given);
  table.bonds = whole.bonds;
  table.atomic_numbers = whole.atomic_numbers; // zeroed for coarse-grained beads
  table.molecule_ids = whole.molecule_ids;
  return table;
}
} // namespace

int vtkMesoTrajectoryReader::CanReadFile(const char* fileName)
{
  return fileName && mesolens::TrajectoryFile::has_trajectory_extension(fileName) ? 1 : 0;
}

bool vtkMesoTrajectoryReader::OpenIfNeeded()
{
  State& state = *this->Internal;
  if (state.Valid && state.OpenTime >= this->GetMTime())
  {
    return true;
  }
  state = State{};
  std::string topology = this->TopologyFileName;
  if (topology.empty() && !this->TrajectoryFileName.empty())
  {
    topology = mesolens::topology_beside(this->TrajectoryFileName);
  }
  if (topology.empty())
  {
    vtkErrorMacro(
      "No TopologyFileName was set"
      << (this->TrajectoryFileName.empty()
            ? std::string(".")
            : ", and no topology lies beside " + this->TrajectoryFileName +
              " (a .gro, .pdb or .cif of the same name, or the only one in its folder)."));
    return false;
  }
  const mesolens::StructureReadParams params = vtkMesoAtomReaderParameters(this);
  const auto incomplete = this->SkipIncompleteFrames
    ? mesolens::TrajectoryFile::IncompleteFrames::Skip
    : mesolens::TrajectoryFile::IncompleteFrames::Reject;
  try
  {
    state.Topology = load_topology(topology, params);
    state.Molecules =
      mesolens::group_molecules(state.Topology.molecule_ids.data(), state.Topology.size());
    this->UpdateProgress(0.5);
    std::string trajectory = this->TrajectoryFileName;
    if (trajectory.empty() && mesolens::file_extension(topology) == "gro")
    {
      trajectory = topology;
      state.TrajectoryIsTopology = true;
    }
    if (!trajectory.empty())
    {
      state.File = std::make_unique<mesolens::TrajectoryFile>(trajectory, incomplete);
      if (state.File->atom_count() != state.Topology.size())
      {
        vtkErrorMacro("Atom count mismatch: trajectory "
                      << trajectory << " has " << state.File->atom_count()
                      << " atoms per frame but topology " << topology << " has "
                      << state.Topology.size() << " atoms.");
        state = State{};
        return false;
      }
      state.Times = state.File->frame_times();
    }
    else
    {
      state.Times = { 0.0 };
    }
  }
  catch (const mesolens::Error& e)
  {
    vtkErrorMacro("Cannot read " << topology << (this->TrajectoryFileName.empty() ? "" : " + ")
                                 << this->TrajectoryFileName << ": " << e.what());
    state = State{};
    return false;
  }

  mesolens::AtomTable output_atoms = state.Topology;
  if (this->RemoveWaters)
  {
    std::vector<bool> keep(output_atoms.size());
    for (std::size_t i = 0; i < keep.size(); ++i)
    {
      keep[i] = !mesolens::is_water_residue(output_atoms.residue_names[i]);
      if (keep[i])
      {
        state.KeptAtoms.push_back(i);
      }
    }
    output_atoms.filter(keep);
  }
  state.Template = vtkSmartPointer<vtkPolyData>::New();
  state.PieceTemplate = nullptr;
  vtkMesoAtomTableConversion::ToPolyData(output_atoms, 1.0, state.Template);
  if (this->MakeMoleculesWhole && this->KeepMoleculesContinuous && state.File)
  {
    state.Continuity = std::make_unique<mesolens::MoleculeContinuity>(state.Topology.molecule_ids);
  }
  state.OpenTime = this->GetMTime();
  state.Valid = true;
  return true;
}

std::size_t vtkMesoTrajectoryReader::FrameForTime(double time) const
{
  const std::vector<double>& times = this->Internal->Times;
  if (!std::isfinite(time) || times.empty())
  {
    return 0;
  }
  const double slack = 1e-6 * std::max(1.0, std::abs(time));
  const auto after = std::upper_bound(times.begin(), times.end(), time + slack);
  return after == times.begin() ? 0 : static_cast<std::size_t>(after - times.begin() - 1);
}

int vtkMesoTrajectoryReader::RequestInformation(vtkInformation*, vtkInformationVector**,
                                                vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
  outInfo->Set(vtkAlgorithm::CAN_HANDLE_PIECE_REQUEST(), 1); // whole molecules per piece
  if (!this->OpenIfNeeded())
  {
    if (vtkPolyData* output = vtkPolyData::GetData(outInfo))
    {
      output->Initialize();
    }
    return 0;
  }
  const std::vector<double>& times = this->Internal->Times;
  outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_STEPS(), times.data(),
               static_cast<int>(times.size()));
  const double range[2] = { times.front(), times.back() };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
  return 1;
}

int vtkMesoTrajectoryReader::RequestData(vtkInformation*, vtkInformationVector**,
                                         vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkPolyData* output = vtkPolyData::GetData(outInfo);
  output->Initialize();
  if (!this->OpenIfNeeded())
  {
    return 0;
  }
  State& state = *this->Internal;
  double requested = state.Times.front();
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()))
  {
    requested = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());
  }
  const std::size_t frame_index = this->FrameForTime(requested);

  mesolens::TrajectoryFrame frame;
  try
  {
    auto visited = [this, frame_index](std::size_t k) {
      this->UpdateProgress(0.9 * double(k) / double(frame_index));
      return !this->GetAbortExecute();
    };
    if (!state.ContinuousFrame(frame_index, this->MakeMoleculesWhole, visited, frame))
    {
      return 0;
    }
  }
  catch (const mesolens::Error& e)
  {
    vtkErrorMacro("Cannot read frame " << frame_index << ": " << e.what());
    output->Initialize();
    return 0;
  }

  const double scale = this->LengthUnit == NANOMETER ? 0.1 : 1.0;
  const auto [piece, pieces] = vtkMesoAtomPieces::Requested(outInfo);
  vtkPolyData* atoms = state.TemplateOf(piece, pieces);
  if (pieces > 1 && state.PieceAtoms.empty())
  {
    return 1; // a piece without molecules (more pieces than molecules)
  }
  output->CopyStructure(atoms);
  output->GetPointData()->PassData(atoms->GetPointData());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  output->SetPoints(points);
  vtkMesoAtomTableConversion::SetPositions(
    frame.positions, pieces > 1 ? state.PieceAtoms : state.KeptAtoms, scale, output);
  vtkMesoAtomTableConversion::SetPeriodicBox(frame.box, scale, output);
  vtkMesoAtomTableConversion::SetFieldValue(output, vtkMesoArrayNames::TimePs, frame.time_ps);
  vtkMesoAtomTableConversion::SetFieldValue(output, vtkMesoArrayNames::FrameIndex,
                                            double(frame_index));
  vtkMesoAtomTableConversion::SetFieldValue(output, vtkMesoArrayNames::Step, double(frame.step));
  output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), state.Times[frame_index]);
  this->UpdateProgress(1.0);
  return 1;
}

int vtkMesoTrajectoryReader::GetNumberOfFrames()
{
  this->UpdateInformation();
  return this->Internal->Valid ? static_cast<int>(this->Internal->Times.size()) : 0;
}

vtkIdType vtkMesoTrajectoryReader::GetNumberOfTopologyAtoms()
{
  this->UpdateInformation();
  return this->Internal->Valid ? static_cast<vtkIdType>(this->Internal->Topology.size()) : 0;
}

void vtkMesoTrajectoryReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent
     << "TopologyFileName: " << (this->TopologyFileName.empty() ? "(none)" : this->TopologyFileName)
     << "\n";
  os << indent << "TrajectoryFileName: "
     << (this->TrajectoryFileName.empty() ? "(none)" : this->TrajectoryFileName) << "\n";
  os << indent << "LengthUnit: " << (this->LengthUnit == NANOMETER ? "nm" : "Angstrom") << "\n";
  os << indent << "MakeMoleculesWhole: " << this->MakeMoleculesWhole << "\n";
  os << indent << "KeepMoleculesContinuous: " << this->KeepMoleculesContinuous << "\n";
  os << indent << "SkipIncompleteFrames: " << this->SkipIncompleteFrames << "\n";
}
