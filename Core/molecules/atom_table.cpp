// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/molecules/atom_table.h"

#include "mesolens/common/errors.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <string>
#include <unordered_map>

namespace mesolens {

void AtomTable::reserve(std::size_t count)
{
  this->positions.reserve(3 * count);
  this->atom_names.reserve(count);
  this->atomic_numbers.reserve(count);
  this->residue_names.reserve(count);
  this->residue_numbers.reserve(count);
  this->insertion_codes.reserve(count);
  this->chain_ids.reserve(count);
  this->label_asym_ids.reserve(count);
  this->alt_locs.reserve(count);
  this->occupancies.reserve(count);
  this->b_factors.reserve(count);
  this->is_hetero.reserve(count);
  this->serials.reserve(count);
  this->formal_charges.reserve(count);
  this->secondary_structure.reserve(count);
  this->secondary_structure_ids.reserve(count);
  this->residue_indices.reserve(count);
  this->molecule_ids.reserve(count);
}

void AtomTable::resize(std::size_t count)
{
  this->positions.resize(3 * count, 0.0f);
  this->atom_names.resize(count);
  this->atomic_numbers.resize(count, 0);
  this->residue_names.resize(count);
  this->residue_numbers.resize(count, 0);
  this->insertion_codes.resize(count, ' ');
  this->chain_ids.resize(count);
  this->label_asym_ids.resize(count);
  this->alt_locs.resize(count, ' ');
  this->occupancies.resize(count, 1.0f);
  this->b_factors.resize(count, 0.0f);
  this->is_hetero.resize(count, 0);
  this->serials.resize(count, 0);
  this->formal_charges.resize(count, 0);
  this->secondary_structure.resize(count, static_cast<std::uint8_t>(SecondaryStructure::Coil));
  this->secondary_structure_ids.resize(count, -1);
  this->residue_indices.resize(count, 0);
  this->molecule_ids.resize(count, 0);
}

void AtomTable::append_atom(const std::string& name, float x, float y, float z)
{
  this->positions.insert(this->positions.end(), { x, y, z });
  this->atom_names.push_back(name);
  this->atomic_numbers.push_back(0);
  this->residue_names.emplace_back();
  this->residue_numbers.push_back(0);
  this->insertion_codes.push_back(' ');
  this->chain_ids.emplace_back();
  this->label_asym_ids.emplace_back();
  this->alt_locs.push_back(' ');
  this->occupancies.push_back(1.0f);
  this->b_factors.push_back(0.0f);
  this->is_hetero.push_back(0);
  this->serials.push_back(0);
  this->formal_charges.push_back(0);
  this->secondary_structure.push_back(static_cast<std::uint8_t>(SecondaryStructure::Coil));
  this->secondary_structure_ids.push_back(-1);
  this->residue_indices.push_back(0);
  this->molecule_ids.push_back(0);
}

namespace {
template<typename T>
void keep_entries(std::vector<T>& values, const std::vector<bool>& keep, std::size_t stride = 1)
{
  std::size_t out = 0;
  for (std::size_t i = 0; i < keep.size(); ++i)
  {
    if (!keep[i])
    {
      continue;
    }
    for (std::size_t c = 0; c < stride; ++c)
    {
      values[out * stride + c] = values[i * stride + c];
    }
    ++out;
  }
  values.resize(out * stride);
}

// Renumbers ids densely in order of first appearance, so ids stay 0-based and increasing.
void renumber_dense(std::vector<int>& ids)
{
  int next = -1;
  int previous = 0;
  bool first = true;
  for (int& id : ids)
  {
    if (first || id != previous)
    {
      previous = id;
      ++next;
      first = false;
    }
    id = next;
  }
}
} // namespace

void AtomTable::filter(const std::vector<bool>& keep)
{
  if (keep.size() != this->size())
  {
    throw InvalidInput("AtomTable::filter: mask has " + std::to_string(keep.size()) +
                       " entries for " + std::to_string(this->size()) + " atoms");
  }
  std::vector<std::int64_t> new_index(keep.size(), -1);
  std::int64_t next = 0;
  for (std::size_t i = 0; i < keep.size(); ++i)
  {
    if (keep[i])
    {
      new_index[i] = next++;
    }
  }
  keep_entries(this->positions, keep, 3);
  keep_entries(this->atom_names, keep);
  keep_entries(this->atomic_numbers, keep);
  keep_entries(this->residue_names, keep);
  keep_entries(this->residue_numbers, keep);
  keep_entries(this->insertion_codes, keep);
  keep_entries(this->chain_ids, keep);
  keep_entries(this->label_asym_ids, keep);
  keep_entries(this->alt_locs, keep);
  keep_entries(this->occupancies, keep);
  keep_entries(this->b_factors, keep);
  keep_entries(this->is_hetero, keep);
  keep_entries(this->serials, keep);
  keep_entries(this->formal_charges, keep);
  keep_entries(this->secondary_structure, keep);
  keep_entries(this->secondary_structure_ids, keep);
  keep_entries(this->residue_indices, keep);
  keep_entries(this->molecule_ids, keep);
  renumber_dense(this->residue_indices);
  renumber_dense(this->molecule_ids);
  std::vector<Bond> kept;
  kept.reserve(this->bonds.size());
  for (const Bond& bond : this->bonds)
  {
    const std::int64_t a = new_index[bond.first];
    const std::int64_t b = new_index[bond.second];
    if (a >= 0 && b >= 0)
    {
      kept.push_back({ static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b) });
    }
  }
  this->bonds = std::move(kept);
}

void AtomTable::check_consistent() const
{
  const std::size_t n = this->size();
  const std::array<std::size_t, 17> sizes = { this->positions.size() / 3,
                                              this->atomic_numbers.size(),
                                              this->residue_names.size(),
                                              this->residue_numbers.size(),
                                              this->insertion_codes.size(),
                                              this->chain_ids.size(),
                                              this->label_asym_ids.size(),
                                              this->alt_locs.size(),
                                              this->occupancies.size(),
                                              this->b_factors.size(),
                                              this->is_hetero.size(),
                                              this->serials.size(),
                                              this->formal_charges.size(),
                                              this->secondary_structure.size(),
                                              this->secondary_structure_ids.size(),
                                              this->residue_indices.size(),
                                              this->molecule_ids.size() };
  if (this->positions.size() % 3 != 0 ||
      std::any_of(sizes.begin(), sizes.end(), [n](std::size_t s) { return s != n; }))
  {
    throw InvalidInput("AtomTable: per-atom arrays disagree on the number of atoms");
  }
  for (const Bond& bond : this->bonds)
  {
    if (bond.first >= n || bond.second >= n || bond.first >= bond.second)
    {
      throw InvalidInput("AtomTable: bond (" + std::to_string(bond.first) + ", " +
                         std::to_string(bond.second) + ") is out of range or not ordered");
    }
  }
}

bool is_water_residue(const std::string& residue_name)
{
  static const std::array<const char*, 14> names = { "HOH",  "WAT",  "SOL",  "H2O", "DOD",
                                                     "TIP3", "TIP4", "TIP5", "TP3", "SPC",
                                                     "SPCE", "T3P",  "W",    "PW" };
  std::string upper = residue_name;
  std::transform(upper.begin(), upper.end(), upper.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return std::any_of(names.begin(), names.end(),
                     [&upper](const char* name) { return upper == name; });
}

} // namespace mesolens
