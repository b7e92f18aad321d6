// SPDX-License-Identifier: GPL-3.0-or-later
// Selection benchmark: mesolens::AtomSelection against MDAnalysis' select_atoms (python3-
// mdanalysis, periodic=False) on the same atoms in the same run. The input is the YiiP membrane
// (yiip_popepopg.gro, 43 480 atoms: protein, POPE, POPG) tiled T x T in its box plane (T = 5:
// 1.09 M atoms), written as a .gro file that both read. Times are medians of the repeats after a
// warm-up; MesoLens runs on VTK's SMP threads (both cores here). The goal: `within` on 1 M atoms
// in under 100 ms.
//
//   BenchmarkAtomSelection [--tiles T] [--repeats N] [--smoke]   (smoke: T = 1, 1 repeat)
#include "mesolens_benchmark_timing.h"
#include "mesolens_test_data.h"
#include "vtkMesoParallelFor.h"

#include "mesolens/io/gro_topology.h"
#include "mesolens/molecules/atom_selection.h"
#include "mesolens/molecules/molecule_assignment.h"

#include <cstdio>
#include <cstring>
#include <fstream>
#include <numeric>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace {

/// The table repeated tiles x tiles times along the box vectors a and b.
mesolens::AtomTable tiled(const mesolens::AtomTable& patch, int tiles)
{
  mesolens::AtomTable out;
  out.reserve(patch.size() * std::size_t(tiles * tiles));
  for (int i = 0; i < tiles; ++i)
  {
    for (int j = 0; j < tiles; ++j)
    {
      for (std::size_t k = 0; k < patch.size(); ++k)
      {
        float p[3];
        for (int d = 0; d < 3; ++d)
        {
          p[d] = patch.positions[3 * k + d] + float(i * patch.box.vectors[0][d]) +
            float(j * patch.box.vectors[1][d]);
        }
        out.append_atom(patch.atom_names[k], p[0], p[1], p[2]);
        out.residue_names.back() = patch.residue_names[k];
        out.residue_numbers.back() = patch.residue_numbers[k];
        out.atomic_numbers.back() = patch.atomic_numbers[k];
      }
    }
  }
  return out;
}

/// Writes `table` as a .gro file (nm; numbers modulo 100000 as GROMACS writes them).
void write_gro(const mesolens::AtomTable& table, const std::string& path)
{
  std::FILE* file = std::fopen(path.c_str(), "w");
  if (!file)
  {
    return;
  }
  std::fprintf(file, "tiled membrane\n%zu\n", table.size());
  for (std::size_t i = 0; i < table.size(); ++i)
  {
    std::fprintf(file, "%5d%-5s%5s%5d%8.3f%8.3f%8.3f\n", table.residue_numbers[i] % 100000,
                 table.residue_names[i].substr(0, 5).c_str(),
                 table.atom_names[i].substr(0, 5).c_str(), int((i + 1) % 100000),
                 table.positions[3 * i] / 10.0, table.positions[3 * i + 1] / 10.0,
                 table.positions[3 * i + 2] / 10.0);
  }
  std::fprintf(file, "%10.5f%10.5f%10.5f\n", 100.0, 100.0, 100.0);
  std::fclose(file);
}

/// MDAnalysis' counts and median times (ms) per expression, or empty when it cannot run.
std::vector<std::pair<long, double>> mdanalysis_times(const std::string& gro,
                                                      const std::vector<std::string>& expressions,
                                                      int repeats)
{
  const std::string list = gro + ".expressions";
  std::ofstream(list) << [&] {
    std::string all;
    for (const std::string& e : expressions)
    {
      all += e + "\n";
    }
    return all;
  }();
  const std::string script =
    std::string(MESOLENS_SOURCE_DIR) + "/Testing/Benchmarks/mdanalysis_select.py";
  const std::string command = "/usr/bin/python3 " + script + " " + gro + " " +
    std::to_string(repeats) + " < " + list + " 2>/dev/null";
  std::vector<std::pair<long, double>> results;
  std::FILE* pipe = popen(command.c_str(), "r");
  if (!pipe)
  {
    return results;
  }
  long count = 0;
  double ms = 0.0;
  while (std::fscanf(pipe, "%ld %lf", &count, &ms) == 2)
  {
    results.emplace_back(count, ms);
  }
  pclose(pipe);
  return results;
}

} // namespace

int main(int argc, char* argv[])
{
  bool smoke = false;
  for (int i = 1; i < argc; ++i)
  {
    smoke = smoke || !std::strcmp(argv[i], "--smoke");
  }
  const int tiles = smoke ? 1 : mesolens_test::count_argument(argc, argv, "--tiles", 5);
  const int repeats = smoke ? 1 : mesolens_test::count_argument(argc, argv, "--repeats", 5);
  const std::string patch_path = mesolens_test::data_file("membranes/yiip_popepopg.gro");
  const mesolens::AtomTable patch = mesolens::read_gro_topology(patch_path);
  const std::string gro = std::string(MESOLENS_TEST_OUTPUT_DIR) + "/BenchmarkAtomSelection.gro";
  write_gro(tiled(patch, tiles), gro);
  // Both read the same file: the same atoms, rounded to the file's 0.01 Å.
  mesolens::AtomTable atoms = mesolens::read_gro_topology(gro);
  mesolens::assign_residues(atoms);
  mesolens::assign_molecules(atoms);
  vtkMesoParallelFor::UseThreads();

  const std::vector<std::pair<std::string, std::string>> expressions = {
    { "name P and z > 50", "name P and prop z > 50" },
    { "resname POPG and not name H*", "resname POPG and not name H*" },
    { "within 5 of protein", "(around 5 protein) or protein" },
    { "within 5 of resname POPG", "(around 5 resname POPG) or resname POPG" },
    { "exwithin 10 of (resid 50 and name CA)", "around 10 (resid 50 and name CA)" },
    { "same residue as within 3 of name P", "same residue as ((around 3 name P) or name P)" },
  };
  std::vector<std::string> theirs;
  for (const auto& e : expressions)
  {
    theirs.push_back(e.second);
  }
  const bool have_mdanalysis =
    !smoke && mesolens_test::program_available("/usr/bin/python3 -c 'import MDAnalysis'");
  const auto baseline = have_mdanalysis ? mdanalysis_times(gro, theirs, repeats)
                                        : std::vector<std::pair<long, double>>{};
  std::printf("BENCH select input %s tiled %dx%d: %zu atoms; baseline MDAnalysis %s\n",
              patch_path.c_str(), tiles, tiles, atoms.size(),
              baseline.size() == expressions.size() ? "2.4 select_atoms(periodic=False)"
                                                    : "not run");
  for (std::size_t e = 0; e < expressions.size(); ++e)
  {
    const mesolens::AtomSelection selection(expressions[e].first);
    std::vector<std::uint8_t> mask = selection.evaluate(atoms, {}, vtkMesoParallelFor::Get());
    const double seconds = mesolens_test::median_seconds(
      repeats, [&] { mask = selection.evaluate(atoms, {}, vtkMesoParallelFor::Get()); });
    const long count = std::accumulate(mask.begin(), mask.end(), 0L);
    std::printf("BENCH select \"%s\": %ld atoms, %.1f ms", expressions[e].first.c_str(), count,
                1000.0 * seconds);
    if (baseline.size() == expressions.size())
    {
      std::printf("; MDAnalysis %ld atoms, %.1f ms; ratio %.3f", baseline[e].first,
                  baseline[e].second, 1000.0 * seconds / baseline[e].second);
    }
    std::printf("\n");
  }
  std::remove(gro.c_str());
  std::remove((gro + ".expressions").c_str());
  return 0;
}
