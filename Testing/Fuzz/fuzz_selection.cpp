// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: atom selections (mesolens::AtomSelection) from arbitrary text, evaluated on
// a small system with every kind of atom (protein, nucleotide, water, lipid, ion, hydrogens,
// alternate locations, insertion codes, a NaN and a far-away atom) and one caller array. Every
// input must parse or throw mesolens::SelectionError with a position inside the text (or at
// its end); a parsed selection must give one 0/1 value per atom, the same on a second
// evaluation, and `not (...)` of it must give the complement.
//
// Input: the expression's bytes.
#include "fuzz_input.h"

#include "mesolens/molecules/atom_selection.h"
#include "mesolens/molecules/molecule_assignment.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace {

using mesolens_fuzz::require;

mesolens::AtomTable system_of_atoms()
{
  struct Atom
  {
    const char* name;
    const char* residue;
    int number;
    const char* chain;
    int element;
    float x;
  };
  const Atom atoms[] = {
    { "N", "ALA", 1, "A", 7, 0.0f },    { "CA", "ALA", 1, "A", 6, 1.4f },
    { "C", "ALA", 1, "A", 6, 2.9f },    { "O", "ALA", 1, "A", 8, 3.6f },
    { "H", "ALA", 1, "A", 1, -0.9f },   { "N", "GLY", 2, "A", 7, 4.2f },
    { "CA", "GLY", 2, "A", 6, 5.5f },   { "P", "DA", 3, "B", 15, 9.0f },
    { "O5'", "DA", 3, "B", 8, 10.1f },  { "OW", "HOH", 4, "", 8, 12.0f },
    { "P", "POPC", 5, "L", 15, 20.0f }, { "C21", "POPC", 5, "L", 6, 21.5f },
    { "NA", "NA", 6, "I", 11, NAN },    { "C1", "LIG", -7, "Z", 6, 3e38f },
  };
  mesolens::AtomTable table;
  for (const Atom& a : atoms)
  {
    table.append_atom(a.name, a.x, 0.5f * a.x, 1.0f);
    table.residue_names.back() = a.residue;
    table.residue_numbers.back() = a.number;
    table.chain_ids.back() = a.chain;
    table.atomic_numbers.back() = std::uint8_t(a.element);
    table.serials.back() = int(table.size());
  }
  table.alt_locs[1] = 'A';
  table.insertion_codes[6] = 'B';
  table.is_hetero[9] = table.is_hetero[13] = 1;
  mesolens::assign_residues(table);
  mesolens::assign_molecules(table);
  return table;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  static const mesolens::AtomTable atoms = system_of_atoms();
  static const mesolens::SelectionArrays arrays = { { "charge2",
                                                      std::vector<double>(atoms.size(), 0.5) } };
  const std::string expression(reinterpret_cast<const char*>(data), size);
  std::vector<std::uint8_t> mask;
  try
  {
    const mesolens::AtomSelection selection(expression);
    mask = selection.evaluate(atoms, arrays);
    require(mask == selection.evaluate(atoms, arrays));
  }
  catch (const mesolens::SelectionError& error)
  {
    require(error.position() <= size);
    return 0;
  }
  require(mask.size() == atoms.size());
  for (std::uint8_t m : mask)
  {
    require(m == 0 || m == 1);
  }
  try
  {
    const auto complement = mesolens::select_atoms(atoms, "not (" + expression + ")", arrays);
    for (std::size_t i = 0; i < mask.size(); ++i)
    {
      require(complement[i] == 1 - mask[i]);
    }
  }
  catch (const mesolens::SelectionError&)
  {
    // Wrapping can pass the nesting limit or join an unterminated quote with the ")".
  }
  return 0;
}
