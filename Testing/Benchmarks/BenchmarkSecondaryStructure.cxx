// SPDX-License-Identifier: GPL-3.0-or-later
// Secondary-structure benchmark: MesoLens' DSSP against Debian's mkdssp (4.2.2) on the same file
// in the same run (4jsv.pdb, 22 k atoms, the largest file here that mkdssp accepts; whole
// programs, reading included, and the assignment alone), and on the 79 k-atom proteasome
// 3l5q.gro, which mkdssp cannot read (GRO), against the goal of DSSP + ribbons in 100 ms.
//
//   BenchmarkSecondaryStructure [--repeats N]
#include "mesolens_benchmark_timing.h"
#include "vtkMesoParallelFor.h"
#include "mesolens_test_data.h"
#include "vtkMesoSecondaryStructure.h"
#include "vtkMesoStructureReader.h"
#include "vtkMesoTrajectoryReader.h"

#include "mesolens/protein/dssp.h"
#include "mesolens/io/gro_topology.h"
#include "mesolens/molecules/molecule_assignment.h"
#include "mesolens/io/structure_file.h"

#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSMPTools.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace {
using mesolens_test::median_seconds;
using mesolens_test::seconds_of;

/// The protein of `table` as a PDB file mkdssp accepts: HEADER, COMPND and SOURCE with a
/// MOL_ID, CRYST1, and a chain letter per polymer molecule (62 letters, reused).
void write_pdb_for_mkdssp(const mesolens::AtomTable& table, const std::string& path)
{
  std::FILE* file = std::fopen(path.c_str(), "w");
  if (!file)
    return;
  std::fprintf(file, "HEADER    HYDROLASE                               01-JAN-00   XXXX\n");
  std::fprintf(file, "COMPND    MOL_ID: 1;\nSOURCE    MOL_ID: 1;\n");
  std::fprintf(file, "CRYST1  300.000  300.000  300.000  90.00  90.00  90.00 P 1           1\n");
  const char* letters = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";
  int chain = 0;
  for (std::size_t a = 0; a < table.size(); ++a)
  {
    if (!mesolens::is_amino_acid_residue(table.residue_names[a]))
      continue;
    if (a > 0 && table.molecule_ids[a] != table.molecule_ids[a - 1])
      ++chain;
    const std::string& name = table.atom_names[a];
    const std::string padded = name.size() < 4 ? " " + name : name;
    std::fprintf(file, "ATOM  %5d %-4s %3s %c%4d    %8.3f%8.3f%8.3f  1.00  0.00          %2c\n",
                 int((a + 1) % 100000), padded.substr(0, 4).c_str(),
                 table.residue_names[a].substr(0, 3).c_str(), letters[chain % 62],
                 table.residue_numbers[a] % 10000, table.positions[3 * a],
                 table.positions[3 * a + 1], table.positions[3 * a + 2], name[0]);
  }
  std::fprintf(file, "END\n");
  std::fclose(file);
}
} // namespace

int main(int argc, char* argv[])
{
  const int repeats = mesolens_test::count_argument(argc, argv, "--repeats", 5);
  std::printf("BENCH dssp threads: %d\n", vtkMesoParallelFor::ThreadCount());

  // 1. 4jsv.pdb against mkdssp.
  const std::string pdb = mesolens_test::shared_file("proteins/4jsv.pdb");
  if (mesolens_test::exists(pdb))
  {
    const auto file = mesolens::read_structure(pdb);
    const auto backbone = mesolens::protein_backbone(file.models.at(0));
    const double assign = median_seconds(
      repeats, [&] { (void)mesolens::assign_secondary_structure(backbone.residues); });
    const double whole = median_seconds(repeats, [&] {
      vtkNew<vtkMesoStructureReader> reader;
      reader->SetFileName(pdb.c_str());
      vtkNew<vtkMesoSecondaryStructure> dssp;
      dssp->SetInputConnection(reader->GetOutputPort());
      dssp->Update();
    });
    std::printf("BENCH dssp 4jsv.pdb (%zu atoms, %zu residues): assignment %.1f ms; reader + "
                "vtkMesoSecondaryStructure %.1f ms\n",
                file.models[0].size(), backbone.residues.size(), 1e3 * assign, 1e3 * whole);
    if (mesolens_test::program_available("mkdssp --version"))
    {
      const std::string output =
        mesolens_test::output_file("BenchmarkSecondaryStructure_4jsv.dssp");
      const std::string command =
        "mkdssp --output-format dssp " + pdb + " " + output + " 2> /dev/null";
      const double mkdssp = median_seconds(repeats, [&] {
        if (std::system(command.c_str()) != 0)
          std::printf("mkdssp failed: %s\n", command.c_str());
      });
      std::printf("BENCH dssp 4jsv.pdb mkdssp 4.2.2 (whole program) %.1f ms; ratio ours/mkdssp: "
                  "whole %.3f, assignment alone %.4f\n",
                  1e3 * mkdssp, whole / mkdssp, assign / mkdssp);
    }
    else
    {
      std::printf("BENCH dssp mkdssp is not installed (Debian package dssp): no ratio\n");
    }
  }
  else
  {
    std::printf("BENCH dssp 4jsv.pdb needs ../shared/data: skipped\n");
  }

  // 2. The proteasome from a GRO file.
  const std::string gro = mesolens_test::shared_file("proteins/3l5q.gro");
  const std::string used =
    mesolens_test::exists(gro) ? gro : mesolens_test::data_file("proteins/1tii.pdb");
  vtkNew<vtkMesoTrajectoryReader> reader;
  reader->SetTopologyFileName(used.c_str());
  const double read = seconds_of([&] { reader->Update(); });
  vtkNew<vtkMesoSecondaryStructure> dssp;
  dssp->SetInputData(reader->GetOutput());
  const double filter = median_seconds(repeats, [&] {
    dssp->Modified();
    dssp->Update();
  });
  std::printf("BENCH dssp %s (%lld atoms): read %.0f ms; vtkMesoSecondaryStructure (conversion, "
              "backbone, assignment, arrays) %.1f ms; goal with ribbons <= 100 ms\n",
              used.substr(used.rfind('/') + 1).c_str(),
              static_cast<long long>(reader->GetOutput()->GetNumberOfPoints()), 1e3 * read,
              1e3 * filter);
  if (used == gro)
  {
    mesolens::AtomTable table = mesolens::read_gro_topology(gro);
    mesolens::assign_residues(table);
    mesolens::assign_molecules(table);
    mesolens::ProteinBackbone backbone;
    const double extract =
      median_seconds(repeats, [&] { backbone = mesolens::protein_backbone(table); });
    const double assign = median_seconds(
      repeats, [&] { (void)mesolens::assign_secondary_structure(backbone.residues); });
    std::printf("BENCH dssp 3l5q.gro in Core: backbone of %zu residues %.1f ms, assignment "
                "%.1f ms (one thread)\n",
                backbone.residues.size(), 1e3 * extract, 1e3 * assign);
    // mkdssp cannot read GRO: the same atoms as a PDB it accepts, timed once (about a minute).
    if (mesolens_test::program_available("mkdssp --version"))
    {
      const std::string pdb_copy =
        mesolens_test::output_file("BenchmarkSecondaryStructure_3l5q.pdb");
      write_pdb_for_mkdssp(table, pdb_copy);
      const std::string command = "mkdssp --output-format mmcif " + pdb_copy + " " +
        mesolens_test::output_file("BenchmarkSecondaryStructure_3l5q.cif") + " 2> /dev/null";
      const double mkdssp = seconds_of([&] {
        if (std::system(command.c_str()) != 0)
          std::printf("mkdssp failed: %s\n", command.c_str());
      });
      std::printf("BENCH dssp 3l5q (as PDB) mkdssp 4.2.2 %.1f s; ours: filter %.1f ms (ratio "
                  "%.5f), assignment alone %.1f ms (ratio %.5f)\n",
                  mkdssp, 1e3 * filter, filter / mkdssp, 1e3 * assign, assign / mkdssp);
    }
  }
  return 0;
}
