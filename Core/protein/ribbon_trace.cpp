// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/protein/ribbon_trace.h"

#include "mesolens/molecules/molecule_assignment.h"
#include "mesolens/protein/dssp.h"
#include "mesolens/protein/protein_backbone.h"

#include <limits>
#include <map>
#include <string>

namespace mesolens {

namespace {
/// The first atom named P among the rows [begin, end), or -1.
std::int64_t phosphorus(const AtomTable& table, std::size_t begin, std::size_t end)
{
  for (std::size_t a = begin; a < end; ++a)
  {
    if (table.atom_names[a] == "P")
    {
      return std::int64_t(a);
    }
  }
  return -1;
}
} // namespace

RibbonTrace ribbon_trace(const AtomTable& table)
{
  const ProteinBackbone backbone = protein_backbone(table);
  std::map<int, std::size_t> amino_acid_of_residue;
  for (std::size_t r = 0; r < backbone.residue_index.size(); ++r)
  {
    amino_acid_of_residue[backbone.residue_index[r]] = r;
  }
  RibbonTrace trace;
  // Chains as the backbone tells them apart (chain id or molecule changes), nucleotides too.
  std::int64_t chain = -1;
  std::string previous_chain;
  int previous_molecule = std::numeric_limits<int>::min();
  const std::size_t count = table.atom_names.size();
  std::size_t begin = 0;
  while (begin < count)
  {
    std::size_t end = begin + 1;
    while (end < count && table.residue_indices[end] == table.residue_indices[begin])
    {
      ++end;
    }
    const int index = table.residue_indices[begin];
    const auto amino_acid = amino_acid_of_residue.find(index);
    std::int64_t trace_row = -1;
    std::int64_t oxygen_row = -1;
    RibbonResidue residue;
    if (amino_acid != amino_acid_of_residue.end() && backbone.atom_rows[amino_acid->second][1] >= 0)
    {
      const BackboneResidue& b = backbone.residues[amino_acid->second];
      trace_row = backbone.atom_rows[amino_acid->second][1]; // CA
      if (b.has_o)
      {
        residue.carbonyl_oxygen = b.o;
        oxygen_row = backbone.atom_rows[amino_acid->second][3];
      }
    }
    else if (is_nucleotide_residue(table.residue_names[begin]))
    {
      trace_row = phosphorus(table, begin, end);
      residue.nucleotide = true;
    }
    if (trace_row >= 0)
    {
      const auto t = std::size_t(trace_row);
      const std::string& chain_id = table.chain_ids[t];
      const int molecule = table.molecule_ids[t];
      if (chain < 0 || chain_id != previous_chain || molecule != previous_molecule)
      {
        ++chain;
      }
      previous_chain = chain_id;
      previous_molecule = molecule;
      residue.trace = { table.positions[3 * t], table.positions[3 * t + 1],
                        table.positions[3 * t + 2] };
      residue.secondary_structure =
        dssp_letter(static_cast<SecondaryStructure>(table.secondary_structure[t]));
      residue.chain = chain;
      residue.id = std::int64_t(trace.residues.size());
      trace.residues.push_back(residue);
      trace.trace_atom.push_back(trace_row);
      trace.oxygen_atom.push_back(oxygen_row);
      trace.residue_index.push_back(index);
    }
    begin = end;
  }
  return trace;
}

void RibbonTrace::update(PointSpan<const float> positions, const std::uint8_t* classes)
{
  for (std::size_t r = 0; r < this->residues.size(); ++r)
  {
    const auto t = std::size_t(this->trace_atom[r]);
    if (t >= positions.size() || this->oxygen_atom[r] >= std::int64_t(positions.size()))
    {
      throw InvalidInput("the ribbon trace needs " + std::to_string(t + 1) +
                         " or more atom positions; got " + std::to_string(positions.size()));
    }
    RibbonResidue& residue = this->residues[r];
    residue.trace = positions.point(t);
    if (this->oxygen_atom[r] >= 0)
    {
      residue.carbonyl_oxygen = positions.point(std::size_t(this->oxygen_atom[r]));
    }
    residue.secondary_structure =
      classes ? dssp_letter(static_cast<SecondaryStructure>(classes[t])) : ' ';
  }
}

} // namespace mesolens
