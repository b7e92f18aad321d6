// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/protein/protein_backbone.h"

#include "mesolens/common/errors.h"
#include "mesolens/molecules/molecule_assignment.h"

#include <cstdint>
#include <limits>
#include <string>

namespace mesolens {

ProteinBackbone protein_backbone(const AtomTable& atoms)
{
  ProteinBackbone backbone;
  const std::size_t count = atoms.atom_names.size();
  if (atoms.residue_indices.size() != count || atoms.positions.size() != 3 * count ||
      atoms.residue_names.size() != count)
  {
    throw InvalidInput("the backbone needs atom names, residue names, residue indices and "
                       "positions for every atom");
  }
  auto position = [&](std::size_t atom) {
    return std::array<double, 3>{ atoms.positions[3 * atom], atoms.positions[3 * atom + 1],
                                  atoms.positions[3 * atom + 2] };
  };
  auto occupancy = [&](std::size_t atom) {
    return atom < atoms.occupancies.size() ? atoms.occupancies[atom] : 1.0f;
  };
  int chain = -1;
  std::string previous_chain;
  int previous_molecule = std::numeric_limits<int>::min();
  std::size_t begin = 0;
  while (begin < count)
  {
    std::size_t end = begin + 1;
    while (end < count && atoms.residue_indices[end] == atoms.residue_indices[begin])
    {
      ++end;
    }
    // The residue's backbone atoms, highest occupancy first among alternates.
    std::array<std::int64_t, 5> found{ -1, -1, -1, -1, -1 }; // N CA C O H
    std::array<std::int64_t, 2> spare{ -1, -1 };             // terminal O, HN
    auto take = [&](std::int64_t& slot, std::size_t atom) {
      if (slot < 0 || occupancy(atom) > occupancy(std::size_t(slot)))
      {
        slot = std::int64_t(atom);
      }
    };
    for (std::size_t a = begin; a < end; ++a)
    {
      const std::string& name = atoms.atom_names[a];
      if (name == "N")
        take(found[0], a);
      else if (name == "CA")
        take(found[1], a);
      else if (name == "C")
        take(found[2], a);
      else if (name == "O")
        take(found[3], a);
      else if (name == "H")
        take(found[4], a);
      else if (name == "OT1" || name == "O1" || name == "OC1")
        take(spare[0], a);
      else if (name == "HN")
        take(spare[1], a);
    }
    found[3] = found[3] >= 0 ? found[3] : spare[0];
    found[4] = found[4] >= 0 ? found[4] : spare[1];
    const std::string& residue_name = atoms.residue_names[begin];
    const bool amino_acid =
      is_amino_acid_residue(residue_name) || (found[0] >= 0 && found[1] >= 0 && found[2] >= 0);
    if (amino_acid && found[1] >= 0)
    {
      const std::string chain_id = begin < atoms.chain_ids.size() ? atoms.chain_ids[begin] : "";
      const int molecule =
        begin < atoms.molecule_ids.size() ? atoms.molecule_ids[begin] : previous_molecule;
      if (chain < 0 || chain_id != previous_chain || molecule != previous_molecule)
      {
        ++chain;
      }
      previous_chain = chain_id;
      previous_molecule = molecule;
      BackboneResidue residue;
      residue.chain = chain;
      residue.proline = residue_name == "PRO";
      std::array<std::array<double, 3>*, 5> targets{ &residue.n, &residue.ca, &residue.c,
                                                     &residue.o, &residue.h };
      std::array<bool*, 5> flags{ &residue.has_n, &residue.has_ca, &residue.has_c, &residue.has_o,
                                  &residue.has_h };
      for (int k = 0; k < 5; ++k)
      {
        if (found[k] >= 0)
        {
          *targets[k] = position(std::size_t(found[k]));
          *flags[k] = true;
        }
      }
      backbone.residues.push_back(residue);
      backbone.residue_index.push_back(atoms.residue_indices[begin]);
      backbone.atom_rows.push_back(found);
    }
    begin = end;
  }
  return backbone;
}

void ProteinBackbone::update_positions(PointSpan<const float> positions)
{
  for (std::size_t r = 0; r < this->residues.size(); ++r)
  {
    BackboneResidue& residue = this->residues[r];
    std::array<std::array<double, 3>*, 5> targets{ &residue.n, &residue.ca, &residue.c, &residue.o,
                                                   &residue.h };
    for (int k = 0; k < 5; ++k)
    {
      const std::int64_t row = this->atom_rows[r][std::size_t(k)];
      if (row >= std::int64_t(positions.size()))
      {
        throw InvalidInput("the backbone needs " + std::to_string(row + 1) +
                           " or more atom positions; got " + std::to_string(positions.size()));
      }
      if (row >= 0)
      {
        *targets[std::size_t(k)] = positions.point(std::size_t(row));
      }
    }
  }
}

} // namespace mesolens
