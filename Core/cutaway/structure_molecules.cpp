// SPDX-License-Identifier: GPL-3.0-or-later
// Which molecules of a membrane system its structure mesh is made from.
#include "mesolens/molecules/molecule_assignment.h"
#include "mesolens/cutaway/structure_mesh.h"

#include "mesolens/common/errors.h"

#include <algorithm>
#include <cctype>
#include <iterator>
#include <string>

namespace mesolens {

namespace {
/// Water models and monatomic ions, upper case, without charge signs (see normalised()).
const char* const solvent_names[] = {
  // water, all-atom
  "SOL", "WAT", "HOH", "H2O", "DOD", "TIP", "TIP3", "TIP4", "TIP5", "T3P", "T4P", "T4E", "T5P",
  "SPC", "SPCE", "OPC", "OPC3",
  // water, coarse-grained (Martini: W, antifreeze WF, polarizable PW, big multipole BMW;
  // Martini 3 tiny and small: TW, SW)
  "W", "WF", "PW", "BMW", "TW", "SW",
  // ions: GROMACS, AMBER, OPLS and PDB codes, Martini's ION
  "NA", "CL", "K", "CA", "MG", "ZN", "LI", "RB", "CS", "BA", "SR", "F", "BR", "I", "MN", "FE", "CU",
  "CO", "NI", "CD", "HG", "IOD", "ION",
  // ions: CHARMM
  "SOD", "POT", "CLA", "CAL", "CES", "LIT", "RUB", "BAR", "ZN2", "CD2"
};

/// The name in upper case, without surrounding blanks, and without an ion's trailing charge
/// (NA+, CL-, CA2+, Mg2+; FE2 and CU1 keep their digit: they are PDB codes).
std::string normalised(const std::string& name)
{
  std::string upper;
  for (const char c : name)
  {
    if (!std::isspace(static_cast<unsigned char>(c)))
    {
      upper.push_back(static_cast<char>(std::toupper(static_cast<unsigned char>(c))));
    }
  }
  if (!upper.empty() && (upper.back() == '+' || upper.back() == '-'))
  {
    upper.pop_back();
    while (!upper.empty() && std::isdigit(static_cast<unsigned char>(upper.back())))
    {
      upper.pop_back();
    }
  }
  return upper;
}
} // namespace

bool is_solvent_residue(const std::string& residue_name)
{
  const std::string name = normalised(residue_name);
  return std::any_of(std::begin(solvent_names), std::end(solvent_names),
                     [&](const char* known) { return name == known; });
}

std::vector<std::uint8_t> structure_molecules(const std::vector<int>& types,
                                              const std::vector<std::string>& type_names,
                                              const std::vector<std::size_t>& atom_counts)
{
  const std::size_t count = !types.empty() ? types.size() : atom_counts.size();
  if (!types.empty() && !atom_counts.empty() && types.size() != atom_counts.size())
  {
    throw InvalidInput("the molecules' types and atom counts differ in number");
  }
  std::vector<std::uint8_t> solvent_type(type_names.size(), 0);
  std::vector<std::uint8_t> polymer_type(type_names.size(), 0);
  for (std::size_t t = 0; t < type_names.size(); ++t)
  {
    solvent_type[t] = is_solvent_residue(type_names[t]);
    polymer_type[t] =
      is_amino_acid_residue(normalised(type_names[t])) || is_nucleotide_residue(type_names[t]);
  }
  const std::size_t largest =
    atom_counts.empty() ? 0 : *std::max_element(atom_counts.begin(), atom_counts.end());
  std::vector<std::uint8_t> kept(count, 1);
  std::vector<std::uint8_t> polymer(count, 0);
  std::size_t kept_count = 0;
  std::size_t polymers = 0;
  for (std::size_t m = 0; m < count; ++m)
  {
    if (!types.empty())
    {
      const int t = types[m];
      if (t < 0 || std::size_t(t) >= type_names.size())
      {
        throw InvalidInput("molecule " + std::to_string(m) + " has no type name");
      }
      kept[m] = !solvent_type[std::size_t(t)];
      polymer[m] = polymer_type[std::size_t(t)];
    }
    if (!atom_counts.empty() && largest >= 4 && atom_counts[m] < 4)
    {
      kept[m] = 0;
    }
    kept_count += kept[m];
    polymers += kept[m] && polymer[m];
  }
  // Proteins and nucleic acids cross the membrane but are not its sheet; without lipids they
  // are all there is.
  if (kept_count - polymers >= 4)
  {
    for (std::size_t m = 0; m < count; ++m)
    {
      kept[m] = kept[m] && !polymer[m];
    }
  }
  return kept;
}

} // namespace mesolens
