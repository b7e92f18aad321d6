// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/molecules/molecule_assignment.h"

#include <gemmi/resinfo.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <string>
#include <unordered_map>

namespace mesolens {

namespace {
// Protonation-state and force-field variants that the PDB chemical component table lacks.
bool is_force_field_amino_acid(const std::string& name)
{
  static const std::array<const char*, 22> variants = {
    "HSD", "HSE", "HSP",  "HID", "HIE",  "HIP", "HISD", "HISE", "HISH", "HISA", "HISB",
    "CYX", "CYM", "CYS2", "LYN", "LYSH", "ASH", "ASPH", "GLH",  "GLUH", "ARGN", "NME"
  };
  for (const char* variant : variants)
  {
    if (name == variant)
    {
      return true;
    }
  }
  // AMBER terminal residues: NALA, CLYS, ...
  return name.size() == 4 && (name[0] == 'N' || name[0] == 'C') &&
    gemmi::find_tabulated_residue(name.substr(1)).is_amino_acid();
}

enum class PolymerKind
{
  None,
  Protein,
  NucleicAcid,
};

PolymerKind polymer_kind(const std::string& residue_name)
{
  if (is_amino_acid_residue(residue_name))
  {
    return PolymerKind::Protein;
  }
  if (is_nucleotide_residue(residue_name))
  {
    return PolymerKind::NucleicAcid;
  }
  return PolymerKind::None;
}

/// Atom range [begin, end) of each residue.
struct ResidueSpan
{
  std::size_t begin;
  std::size_t end;
};

std::vector<ResidueSpan> residue_spans(const AtomTable& table)
{
  std::vector<ResidueSpan> spans;
  for (std::size_t i = 0; i < table.size(); ++i)
  {
    if (i == 0 || table.residue_indices[i] != table.residue_indices[i - 1])
    {
      spans.push_back({ i, i + 1 });
    }
    else
    {
      spans.back().end = i + 1;
    }
  }
  return spans;
}

long find_atom(const AtomTable& table, const ResidueSpan& span, const char* name)
{
  for (std::size_t i = span.begin; i < span.end; ++i)
  {
    if (table.atom_names[i] == name)
    {
      return long(i);
    }
  }
  return -1;
}

double periodic_distance(const AtomTable& table, long a, long b)
{
  std::array<double, 3> d{};
  for (int k = 0; k < 3; ++k)
  {
    d[std::size_t(k)] = double(table.positions[std::size_t(3 * a + k)]) -
      double(table.positions[std::size_t(3 * b + k)]);
  }
  d = table.box.minimum_image(d);
  return std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

/// True when the residues are chemically linked along the backbone.
bool backbone_linked(const AtomTable& table, const ResidueSpan& previous, const ResidueSpan& next,
                     PolymerKind kind)
{
  struct LinkRule
  {
    const char* from;
    const char* to;
    double max_distance; // Å
  };
  static const std::array<LinkRule, 3> protein_links = {
    { { "C", "N", 2.0 }, { "CA", "CA", 4.3 }, { "BB", "BB", 5.0 } }
  };
  static const std::array<LinkRule, 4> nucleic_links = {
    { { "O3'", "P", 2.0 }, { "O3*", "P", 2.0 }, { "P", "P", 8.0 }, { "BB1", "BB1", 8.0 } }
  };
  const LinkRule* rules =
    kind == PolymerKind::Protein ? protein_links.data() : nucleic_links.data();
  const std::size_t rule_count =
    kind == PolymerKind::Protein ? protein_links.size() : nucleic_links.size();
  for (std::size_t r = 0; r < rule_count; ++r)
  {
    const long a = find_atom(table, previous, rules[r].from);
    const long b = find_atom(table, next, rules[r].to);
    if (a >= 0 && b >= 0)
    {
      return periodic_distance(table, a, b) <= rules[r].max_distance;
    }
  }
  return false;
}
} // namespace

bool is_amino_acid_residue(const std::string& residue_name)
{
  return gemmi::find_tabulated_residue(residue_name).is_amino_acid() ||
    is_force_field_amino_acid(residue_name);
}

bool is_nucleotide_residue(const std::string& residue_name)
{
  return gemmi::find_tabulated_residue(residue_name).is_nucleic_acid();
}

bool is_lipid_residue(const std::string& residue_name)
{
  std::string name = residue_name;
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  // AMBER's lauroyl (LA) and arachidonoyl (AR) tails are left out: ion residues use those names.
  static const std::array<const char*, 19> named = { "CHOL", "CHL1", "CLR",  "ERG",  "CDL0",
                                                     "CDL1", "CDL2", "TOCL", "POCL", "PSM",
                                                     "PC",   "PE",   "PS",   "PGR",  "PA",
                                                     "OL",   "ST",   "MY",   "DHA" };
  if (std::any_of(named.begin(), named.end(), [&name](const char* n) { return name == n; }))
  {
    return true;
  }
  static const std::array<const char*, 7> heads = { "PC", "PE", "PS", "PG", "PA", "PI", "SM" };
  return name.size() == 4 && std::isalpha(static_cast<unsigned char>(name[0])) &&
    std::isalpha(static_cast<unsigned char>(name[1])) &&
    std::any_of(heads.begin(), heads.end(),
                [&name](const char* head) { return name.compare(2, 2, head) == 0; });
}

void assign_residues(AtomTable& table)
{
  table.residue_indices.resize(table.size());
  int residue = -1;
  for (std::size_t i = 0; i < table.size(); ++i)
  {
    const bool same = i > 0 && table.chain_ids[i] == table.chain_ids[i - 1] &&
      table.residue_numbers[i] == table.residue_numbers[i - 1] &&
      table.insertion_codes[i] == table.insertion_codes[i - 1] &&
      table.residue_names[i] == table.residue_names[i - 1];
    if (!same)
    {
      ++residue;
    }
    table.residue_indices[i] = residue;
  }
}

void assign_molecules(AtomTable& table)
{
  table.molecule_ids.assign(table.size(), 0);
  const std::vector<ResidueSpan> spans = residue_spans(table);
  int molecule = -1;
  PolymerKind previous_kind = PolymerKind::None;
  for (std::size_t r = 0; r < spans.size(); ++r)
  {
    const ResidueSpan& span = spans[r];
    const PolymerKind kind = polymer_kind(table.residue_names[span.begin]);
    bool continues = false;
    if (r > 0 && kind != PolymerKind::None && kind == previous_kind)
    {
      const std::string& chain = table.chain_ids[span.begin];
      const std::string& previous_chain = table.chain_ids[spans[r - 1].begin];
      if (chain != previous_chain)
      {
        continues = false;
      }
      else if (!chain.empty())
      {
        continues = true;
      }
      else
      {
        continues = backbone_linked(table, spans[r - 1], span, kind);
      }
    }
    if (!continues)
    {
      ++molecule;
    }
    for (std::size_t i = span.begin; i < span.end; ++i)
    {
      table.molecule_ids[i] = molecule;
    }
    previous_kind = kind;
  }
}

} // namespace mesolens
