// SPDX-License-Identifier: GPL-3.0-or-later
// Writes Data/proteins/awkward/gromacs_wrapped_numbers.pdb with GROMACS' own PDB writer, so the
// structure reader is tested on what GROMACS really writes past residue 9999 and atom 99999.
//
// It takes one DPPC lipid and 50 TIP3P waters from an all-atom bilayer (read with GROMACS' .gro
// reader), numbers their residues 9990..10040 and places them at atoms 99811..100090 of a larger
// system, then writes only those atoms, as `gmx trjconv -n` writes a selection (serial = index
// in the system + 1). GROMACS 2022 writes residue numbers modulo 10000 and serials modulo
// 100000, in fixed columns.
//
// Built on request only (target write_gromacs_pdb_fixture, not part of `all`, not a test):
//   write_gromacs_pdb_fixture Data/membranes/dppc128_slipids_323K.gro \
//     Data/proteins/awkward/gromacs_wrapped_numbers.pdb
#include <gromacs/fileio/confio.h>
#include <gromacs/math/vec.h>
#include <gromacs/pbcutil/pbc.h>
#include <gromacs/topology/atoms.h>
#include <gromacs/topology/symtab.h>
#include <gromacs/utility/smalloc.h>

#include <cctype>
#include <cstdio>
#include <cstring>
#include <vector>

namespace {
// Where the selection sits in the pretended system: the first residue's number and the first
// atom's index, chosen so both numbering limits fall inside the waters.
constexpr int first_residue_number = 9990;
constexpr int first_atom_index = 99810;
constexpr int water_count = 50;
} // namespace

int main(int argc, char** argv)
{
  if (argc != 3)
  {
    std::fprintf(stderr, "usage: %s dppc128_slipids_323K.gro output.pdb\n", argv[0]);
    return 2;
  }
  t_symtab symtab;
  open_symtab(&symtab);
  char* title = nullptr;
  t_atoms source;
  PbcType pbc_type = PbcType::Unset;
  rvec* source_x = nullptr;
  matrix box;
  readConfAndAtoms(argv[1], &symtab, &title, &source, &pbc_type, &source_x, nullptr, box);

  // The first lipid and the first waters of the bilayer, in file order.
  std::vector<int> picked;
  int waters = 0;
  for (int i = 0; i < source.nr; ++i)
  {
    const t_resinfo& residue = source.resinfo[source.atom[i].resind];
    const bool lipid = residue.nr == source.resinfo[0].nr;
    const bool water = std::strcmp(*residue.name, "SOL") == 0;
    if (water && (picked.empty() || source.atom[picked.back()].resind != source.atom[i].resind))
    {
      ++waters;
    }
    if (lipid || (water && waters <= water_count))
    {
      picked.push_back(i);
    }
  }

  const int atom_count = first_atom_index + int(picked.size());
  t_atoms system;
  init_t_atoms(&system, atom_count, FALSE);
  rvec* x = nullptr;
  snew(x, atom_count);
  // Atoms before the selection are never written; they only give it its place.
  char** placeholder = put_symtab(&symtab, "X");
  for (int i = 0; i < first_atom_index; ++i)
  {
    system.atomname[i] = placeholder;
    system.atom[i].resind = 0;
  }
  t_atoms_set_resinfo(&system, 0, &symtab, "X", 1, ' ', 0, ' ');
  system.nres = 1;
  std::vector<int> written;
  int last_source_residue = -1;
  for (const int i : picked)
  {
    const int target = first_atom_index + int(written.size());
    if (source.atom[i].resind != last_source_residue)
    {
      last_source_residue = source.atom[i].resind;
      system.atom[target].resind = system.nres++;
      t_atoms_set_resinfo(&system, target, &symtab, *source.resinfo[last_source_residue].name,
                          first_residue_number + system.atom[target].resind - 1, ' ', 0, 'A');
    }
    else
    {
      system.atom[target].resind = system.atom[target - 1].resind;
    }
    system.atomname[target] = source.atomname[i];
    // The .gro file names no elements; these all-atom names start with theirs.
    system.atom[target].elem[0] =
      char(std::toupper(static_cast<unsigned char>((*source.atomname[i])[0])));
    system.atom[target].elem[1] = '\0';
    copy_rvec(source_x[i], x[target]);
    written.push_back(target);
  }
  write_sto_conf_indexed(argv[2], "DPPC and TIP3P across residue 9999 and atom 99999", &system, x,
                         nullptr, pbc_type, box, int(written.size()), written.data());
  std::printf("wrote %zu atoms, serials %d..%d, residues %d..%d\n", written.size(),
              written.front() + 1, written.back() + 1, first_residue_number,
              first_residue_number + system.nres - 2);
  return 0;
}
