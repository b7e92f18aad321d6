// SPDX-License-Identifier: GPL-3.0-or-later
// Reader benchmarks. Prints, for each input, the figure and its ratio to a baseline measured in
// the same run (these machines are noisy; absolute times only mean something relative to it):
//  - PDB and mmCIF parse time per atom of vtkMesoStructureReader (everything it does: parse,
//    alternate locations, secondary structure, molecules, bonds) against VTK's vtkPDBReader on
//    the same PDB file (which drops hydrogens and alternate atoms), and its time against gemmi's
//    bare read_structure of the same file, with how far reads stray from run to run;
//  - XTC decoding: frames and atoms per second of mesolens::TrajectoryFile (random access, frame
//    validation) and of vtkMesoTrajectoryReader (plus whole, continuous molecules) against a
//    plain sequential GROMACS read_next_frame loop.
// The largest protein of the shared data (3l5q.gro, 79452 atoms) has no PDB/mmCIF form: it is
// written as PDB by GROMACS, and its atoms as an mmCIF atom_site loop, first. Inputs that are
// absent are skipped.
#include "vtkMesoStructureReader.h"
#include "vtkMesoTrajectoryReader.h"

#include "mesolens/molecules/elements.h"
#include "mesolens/io/structure_file.h"
#include "mesolens/io/trajectory_file.h"
#include "mesolens_benchmark_timing.h"
#include "mesolens_test_data.h"

#include <gemmi/gz.hpp>
#include <gemmi/mmread.hpp>
#include <gromacs/fileio/confio.h>
#include <gromacs/fileio/oenv.h>
#include <gromacs/fileio/trxio.h>
#include <gromacs/pbcutil/pbc.h>
#include <gromacs/topology/atoms.h>
#include <gromacs/topology/symtab.h>
#include <gromacs/trajectory/trajectoryframe.h>
#include <gromacs/utility/smalloc.h>

#include <vtkExecutive.h>
#include <vtkInformation.h>
#include <vtkNew.h>
#include <vtkPDBReader.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <utility>
#include <string>
#include <vector>

namespace {
using mesolens_test::median;
using mesolens_test::median_seconds;
using mesolens_test::seconds_of;

/// Times of `repeats` runs of each of `work`, interleaved so all see the same machine load.
std::vector<std::vector<double>> interleaved_times(int repeats,
                                                   const std::vector<std::function<void()>>& work)
{
  std::vector<std::vector<double>> times(work.size());
  for (int r = 0; r < repeats; ++r)
  {
    for (std::size_t w = 0; w < work.size(); ++w)
    {
      times[w].push_back(seconds_of(work[w]));
    }
  }
  return times;
}

/// How far reads of one file in one process stray from their median: the second slowest and
/// the second fastest of the runs (one outlier each way is the machine, not the reader), as
/// the larger relative distance from the median.
double run_to_run_spread(std::vector<double> times)
{
  std::sort(times.begin(), times.end());
  const double middle = times[times.size() / 2];
  const std::size_t skip = times.size() >= 5 ? 1 : 0;
  return std::max(times[times.size() - 1 - skip] / middle - 1.0, 1.0 - times[skip] / middle);
}

/// gemmi's own parse of a PDB or mmCIF file into its Structure (no bonds, no conversion): the
/// baseline the structure reader is held to.
void gemmi_bare_parse(const std::string& path)
{
  const gemmi::Structure structure = gemmi::read_structure(gemmi::MaybeGzipped(path));
  if (structure.models.empty())
  {
    std::printf("gemmi read no model from %s\n", path.c_str());
  }
}

/// Writes 3l5q.gro as PDB with GROMACS' own writer.
bool gro_to_pdb(const std::string& gro, const std::string& pdb)
{
  t_symtab symtab;
  open_symtab(&symtab);
  t_atoms atoms;
  init_t_atoms(&atoms, 0, FALSE);
  char* title = nullptr;
  rvec* x = nullptr;
  rvec* v = nullptr;
  matrix box;
  PbcType pbc = PbcType::Unset;
  readConfAndAtoms(gro.c_str(), &symtab, &title, &atoms, &pbc, &x, &v, box);
  write_sto_conf(pdb.c_str(), title, &atoms, x, nullptr, pbc, box);
  done_atom(&atoms);
  done_symtab(&symtab);
  sfree(x);
  sfree(v);
  sfree(title);
  return true;
}

/// Writes the atoms of a PDB file as a PDBx/mmCIF atom_site loop (the part readers parse).
void pdb_to_mmcif(const std::string& pdb, const std::string& cif)
{
  mesolens::StructureReadParams params;
  params.perceive_bonds = false;
  const mesolens::AtomTable t = mesolens::read_structure(pdb, params).models.front();
  std::FILE* out = std::fopen(cif.c_str(), "w");
  std::fprintf(out, "data_converted\nloop_\n");
  for (const char* item :
       { "group_PDB", "id", "type_symbol", "label_atom_id", "label_alt_id", "label_comp_id",
         "label_asym_id", "label_entity_id", "label_seq_id", "Cartn_x", "Cartn_y", "Cartn_z",
         "occupancy", "B_iso_or_equiv", "auth_seq_id", "auth_asym_id", "pdbx_PDB_model_num" })
  {
    std::fprintf(out, "_atom_site.%s\n", item);
  }
  for (std::size_t i = 0; i < t.size(); ++i)
  {
    const std::string chain = t.chain_ids[i].empty() ? "A" : t.chain_ids[i];
    std::fprintf(out, "%s %zu %s \"%s\" . %s %s 1 %d %.3f %.3f %.3f %.2f %.2f %d %s 1\n",
                 t.is_hetero[i] ? "HETATM" : "ATOM", i + 1,
                 mesolens::element_symbol(t.atomic_numbers[i]), t.atom_names[i].c_str(),
                 t.residue_names[i].c_str(), chain.c_str(), t.residue_numbers[i],
                 t.positions[3 * i], t.positions[3 * i + 1], t.positions[3 * i + 2],
                 t.occupancies[i], t.b_factors[i], t.residue_numbers[i], chain.c_str());
  }
  std::fclose(out);
}

void benchmark_structure(const std::string& label, const std::string& pdb, const std::string& cif,
                         int repeats)
{
  vtkNew<vtkMesoStructureReader> ours;
  ours->SetFileName(pdb.c_str());
  vtkNew<vtkPDBReader> vtk;
  vtk->SetFileName(pdb.c_str());
  const auto pdb_times = interleaved_times(repeats,
                                           { [&] {
                                              ours->Modified();
                                              ours->Update();
                                            },
                                             [&] {
                                               vtk->Modified();
                                               vtk->Update();
                                             },
                                             [&] { gemmi_bare_parse(pdb); } });
  const double ours_pdb = median(pdb_times[0]);
  const double vtk_pdb = median(pdb_times[1]);
  const double gemmi_pdb = median(pdb_times[2]);
  const vtkIdType ours_atoms = ours->GetOutput()->GetNumberOfPoints();
  const vtkIdType ours_bonds = ours->GetOutput()->GetNumberOfLines();
  const vtkIdType vtk_atoms = vtk->GetOutput()->GetNumberOfPoints();
  std::printf("BENCH structure-pdb input=%s atoms=%lld | vtkMesoStructureReader %.3f us/atom "
              "(%.1f ms, %lld atoms, %lld bonds) | vtkPDBReader %.3f us/atom (%.1f ms, %lld atoms) "
              "| speedup %.1fx\n",
              label.c_str(), static_cast<long long>(ours_atoms),
              1e6 * ours_pdb / double(ours_atoms), 1e3 * ours_pdb,
              static_cast<long long>(ours_atoms), static_cast<long long>(ours_bonds),
              1e6 * vtk_pdb / double(std::max<vtkIdType>(vtk_atoms, 1)), 1e3 * vtk_pdb,
              static_cast<long long>(vtk_atoms), vtk_pdb / ours_pdb);
  std::printf("BENCH structure-pdb-vs-gemmi input=%s | vtkMesoStructureReader (bonds included) "
              "%.1f ms | gemmi read_structure (bare parse) %.1f ms | ratio ours/gemmi %.2f (goal "
              "<= 1.5) | run-to-run spread ours %.0f%% gemmi %.0f%% (goal ours <= 20%%)\n",
              label.c_str(), 1e3 * ours_pdb, 1e3 * gemmi_pdb, ours_pdb / gemmi_pdb,
              100 * run_to_run_spread(pdb_times[0]), 100 * run_to_run_spread(pdb_times[2]));
  if (cif.empty())
  {
    return;
  }
  ours->SetFileName(cif.c_str());
  const auto cif_times = interleaved_times(repeats,
                                           { [&] {
                                              ours->Modified();
                                              ours->Update();
                                            },
                                             [&] { gemmi_bare_parse(cif); } });
  const double ours_cif = median(cif_times[0]);
  const double gemmi_cif = median(cif_times[1]);
  std::printf("BENCH structure-mmcif input=%s atoms=%lld | vtkMesoStructureReader %.3f us/atom "
              "(%.1f ms) | vtkPDBReader on the PDB form %.3f us/atom | speedup %.1fx | mmCIF/PDB "
              "time %.2f\n",
              label.c_str(), static_cast<long long>(ours->GetOutput()->GetNumberOfPoints()),
              1e6 * ours_cif / double(ours->GetOutput()->GetNumberOfPoints()), 1e3 * ours_cif,
              1e6 * vtk_pdb / double(std::max<vtkIdType>(vtk_atoms, 1)), vtk_pdb / ours_cif,
              ours_cif / ours_pdb);
  std::printf("BENCH structure-mmcif-vs-gemmi input=%s | vtkMesoStructureReader (bonds included) "
              "%.1f ms | gemmi read_structure %.1f ms | ratio ours/gemmi %.2f (goal <= 1.5) | "
              "run-to-run spread ours %.0f%%\n",
              label.c_str(), 1e3 * ours_cif, 1e3 * gemmi_cif, ours_cif / gemmi_cif,
              100 * run_to_run_spread(cif_times[0]));
}

/// Sequential decoding of every frame with GROMACS alone: the baseline.
double gromacs_sequential(const std::string& xtc, int& frames)
{
  return median_seconds(3, [&] {
    gmx_output_env_t* oenv = nullptr;
    output_env_init_default(&oenv);
    t_trxstatus* status = nullptr;
    t_trxframe frame;
    clear_trxframe(&frame, TRUE);
    frames = 0;
    bool more = read_first_frame(oenv, &status, xtc.c_str(), &frame, TRX_NEED_X);
    while (more)
    {
      ++frames;
      more = read_next_frame(oenv, status, &frame);
    }
    close_trx(status);
    done_frame(&frame);
    output_env_done(oenv);
  });
}

void benchmark_trajectory(const std::string& label, const std::string& gro, const std::string& xtc)
{
  int frames = 0;
  const double baseline = gromacs_sequential(xtc, frames);
  std::size_t atoms = 0;
  const double core = median_seconds(3, [&] {
    mesolens::TrajectoryFile file(xtc);
    atoms = file.atom_count();
    for (std::size_t f = 0; f < file.frame_count(); ++f)
    {
      file.read_frame(f);
    }
  });
  vtkNew<vtkMesoTrajectoryReader> reader;
  reader->SetTopologyFileName(gro.c_str());
  reader->SetTrajectoryFileName(xtc.c_str());
  reader->UpdateInformation();
  const std::vector<double> times(
    reader->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS()),
    reader->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS()) + frames);
  const double pipeline = median_seconds(3, [&] {
    for (auto it = times.rbegin(); it != times.rend(); ++it) // backwards: random access
    {
      reader->UpdateTimeStep(*it);
    }
  });
  const double forward = median_seconds(5, [&] {
    for (const double time : times)
    {
      reader->UpdateTimeStep(time);
    }
  });
  const double n = double(frames);
  std::printf(
    "BENCH xtc input=%s frames=%d atoms=%zu | TrajectoryFile %.1f frames/s %.2f Matoms/s "
    "| vtkMesoTrajectoryReader (whole, continuous, backwards) %.1f frames/s %.2f Matoms/s "
    "| GROMACS sequential %.1f frames/s %.2f Matoms/s | ratio TrajectoryFile/GROMACS %.2f\n",
    label.c_str(), frames, atoms, n / core, n * double(atoms) / core / 1e6, n / pipeline,
    n * double(atoms) / pipeline / 1e6, n / baseline, n * double(atoms) / baseline / 1e6,
    baseline / core);
  // MDAnalysis reading the same files in order (its coordinates as stored), where installed.
  const std::string script =
    std::string(MESOLENS_SOURCE_DIR) + "/Testing/Benchmarks/mdanalysis_trajectory.py";
  std::FILE* pipe =
    popen(("/usr/bin/python3 " + script + " " + gro + " " + xtc + " 5 2>/dev/null").c_str(), "r");
  int mda_frames = 0;
  double mda_rate = 0;
  const bool have_mda = pipe && std::fscanf(pipe, "%d %lf", &mda_frames, &mda_rate) == 2;
  if (pipe)
  {
    pclose(pipe);
  }
  if (have_mda && mda_rate > 0)
  {
    std::printf("BENCH xtc input=%s in order | vtkMesoTrajectoryReader (whole, continuous) %.1f "
                "frames/s | MDAnalysis (as stored) %.1f frames/s | ratio ours/MDAnalysis %.2f "
                "(goal >= 0.8)\n",
                label.c_str(), n / forward, mda_rate, n / forward / mda_rate);
  }
  else
  {
    std::printf("BENCH xtc input=%s in order | vtkMesoTrajectoryReader (whole, continuous) %.1f "
                "frames/s | MDAnalysis not installed (python3-mdanalysis): no ratio\n",
                label.c_str(), n / forward);
  }
}
} // namespace

int main(int argc, char* argv[])
{
  // --repeats N: reads of each structure file per reader (default 15); --structures: skip the
  // trajectories.
  const int repeats = mesolens_test::count_argument(argc, argv, "--repeats", 15);
  const bool structures_only = std::find_if(argv + 1, argv + argc, [](const char* a) {
                                 return std::string(a) == "--structures";
                               }) != argv + argc;
  using mesolens_test::data_file;
  using mesolens_test::exists;
  using mesolens_test::shared_file;
  const std::string big_gro = shared_file("proteins/3l5q.gro");
  if (exists(big_gro))
  {
    const std::string pdb = mesolens_test::output_file("3l5q_from_gro.pdb");
    const std::string cif = mesolens_test::output_file("3l5q_from_gro.cif");
    gro_to_pdb(big_gro, pdb);
    pdb_to_mmcif(pdb, cif);
    benchmark_structure("3l5q (proteasome, written from 3l5q.gro)", pdb, cif, repeats);
  }
  else
  {
    std::printf("BENCH skipped 3l5q: %s not found\n", big_gro.c_str());
  }
  const std::string mtor = shared_file("proteins/4jsv.pdb");
  if (exists(mtor))
  {
    benchmark_structure("4jsv.pdb (real PDB entry)", mtor, "", repeats);
  }
  const std::string achbp = shared_file("proteins/3wip.pdb");
  if (exists(achbp))
  {
    benchmark_structure("3wip (real PDB and mmCIF entries)", achbp,
                        shared_file("proteins/3wip.cif"), repeats);
  }
  const std::string capsid = shared_file("proteins/1m4x.pdb");
  if (exists(capsid))
  {
    benchmark_structure("1m4x (real PDB and mmCIF entries)", capsid,
                        shared_file("proteins/1m4x.cif"), repeats);
  }
  benchmark_structure("1tii.pdb (Data/)", data_file("proteins/1tii.pdb"), "", repeats);
  if (structures_only)
  {
    return 0;
  }
  benchmark_trajectory("yiip_popepopg.xtc (all-atom)", data_file("membranes/yiip_popepopg.gro"),
                       data_file("membranes/yiip_popepopg.xtc"));
  benchmark_trajectory("martini_dppc_vesicle.xtc (coarse-grained, triclinic)",
                       data_file("membranes/martini_dppc_vesicle.gro"),
                       data_file("membranes/martini_dppc_vesicle.xtc"));
  return 0;
}
