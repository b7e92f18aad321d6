// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/molecules/atom_selection.h"

#include "mesolens/molecules/elements.h"
#include "mesolens/molecules/molecule_assignment.h"
#include "molecules/detail/atoms_within.h"
#include "molecules/detail/selection_syntax.h"

#include <fnmatch.h>

#include <algorithm>
#include <functional>
#include <type_traits>
#include <set>
#include <unordered_map>
#include <unordered_set>

namespace mesolens {

SelectionError::SelectionError(const std::string& message, std::size_t position)
  : InvalidInput(message)
  , Position(position)
{
}

namespace {

using detail::NumberField;
using detail::SelectionNode;
using Mask = std::vector<std::uint8_t>;

struct Context
{
  const AtomTable& atoms;
  const SelectionArrays& arrays;
  const ParallelFor& parallel_for;
  const std::string& expression;
};

/// Marks the atoms whose key (a residue name, an atom name...) passes `test`, testing each
/// distinct key once: tables have millions of atoms but few distinct names. `key(i)` may return
/// a reference into the table.
template<typename KeyOf, typename Test>
Mask by_key(std::size_t count, const KeyOf& key, const Test& test)
{
  using Key = std::decay_t<decltype(key(std::size_t(0)))>;
  Mask mask(count, 0);
  std::unordered_map<Key, bool> known;
  Key previous{};
  bool previous_result = false;
  for (std::size_t i = 0; i < count; ++i)
  {
    const auto& k = key(i);
    // Neighbours share names, residues and chains: most atoms need no hashing.
    if (i == 0 || !(k == previous))
    {
      auto found = known.find(k);
      if (found == known.end())
      {
        found = known.emplace(k, test(k)).first;
      }
      previous_result = found->second;
      previous = k;
    }
    mask[i] = previous_result ? 1 : 0;
  }
  return mask;
}

bool matches_any(const std::string& text, const std::vector<std::string>& patterns)
{
  return std::any_of(patterns.begin(), patterns.end(), [&text](const std::string& pattern) {
    return pattern.find_first_of("*?[") == std::string::npos
      ? text == pattern
      : fnmatch(pattern.c_str(), text.c_str(), 0) == 0;
  });
}

Mask text_mask(const SelectionNode& node, const AtomTable& atoms)
{
  const auto test = [&node](const std::string& text) { return matches_any(text, node.patterns); };
  switch (node.text_field)
  {
    case detail::TextField::Name:
      return by_key(
        atoms.size(), [&](std::size_t i) -> const std::string& { return atoms.atom_names[i]; },
        test);
    case detail::TextField::ResidueName:
      return by_key(
        atoms.size(), [&](std::size_t i) -> const std::string& { return atoms.residue_names[i]; },
        test);
    case detail::TextField::Chain:
      return by_key(
        atoms.size(), [&](std::size_t i) -> const std::string& { return atoms.chain_ids[i]; },
        test);
    case detail::TextField::AltLoc:
      break;
  }
  // An atom without an alternate location (' ') has the empty altloc "".
  return by_key(
    atoms.size(),
    [&](std::size_t i) {
      return atoms.alt_locs[i] == ' ' ? std::string() : std::string(1, atoms.alt_locs[i]);
    },
    test);
}

Mask residue_class_mask(const AtomTable& atoms, bool (*is_member)(const std::string&))
{
  return by_key(
    atoms.size(), [&](std::size_t i) -> const std::string& { return atoms.residue_names[i]; },
    [is_member](const std::string& name) { return is_member(name); });
}

Mask class_mask(detail::AtomClass atom_class, const AtomTable& atoms)
{
  const std::size_t n = atoms.size();
  switch (atom_class)
  {
    case detail::AtomClass::All:
      return Mask(n, 1);
    case detail::AtomClass::None:
      return Mask(n, 0);
    case detail::AtomClass::Protein:
      return residue_class_mask(atoms, is_amino_acid_residue);
    case detail::AtomClass::Nucleic:
      return residue_class_mask(atoms, is_nucleotide_residue);
    case detail::AtomClass::Water:
      return residue_class_mask(atoms, is_water_residue);
    case detail::AtomClass::Lipid:
      return residue_class_mask(atoms, is_lipid_residue);
    case detail::AtomClass::Backbone: {
      Mask mask = residue_class_mask(atoms, is_amino_acid_residue);
      const Mask names = by_key(
        n, [&](std::size_t i) -> const std::string& { return atoms.atom_names[i]; },
        [](const std::string& name) {
          return name == "N" || name == "CA" || name == "C" || name == "O";
        });
      for (std::size_t i = 0; i < n; ++i)
      {
        mask[i] &= names[i];
      }
      return mask;
    }
    case detail::AtomClass::Hydrogen:
    case detail::AtomClass::Hetero:
      break;
  }
  Mask mask(n, 0);
  for (std::size_t i = 0; i < n; ++i)
  {
    mask[i] = atom_class == detail::AtomClass::Hydrogen ? atoms.atomic_numbers[i] == 1
                                                        : atoms.is_hetero[i] != 0;
  }
  return mask;
}

/// The per-atom value of a numeric field, as a function of the atom index.
std::function<double(std::size_t)> field_values(const SelectionNode& node, const Context& context)
{
  const AtomTable& a = context.atoms;
  switch (node.number_field)
  {
    case NumberField::X:
    case NumberField::Y:
    case NumberField::Z: {
      const std::size_t axis = std::size_t(node.number_field) - std::size_t(NumberField::X);
      return [&a, axis](std::size_t i) { return double(a.positions[3 * i + axis]); };
    }
    case NumberField::Occupancy:
      return [&a](std::size_t i) { return double(a.occupancies[i]); };
    case NumberField::BFactor:
      return [&a](std::size_t i) { return double(a.b_factors[i]); };
    case NumberField::FormalCharge:
      return [&a](std::size_t i) { return double(a.formal_charges[i]); };
    case NumberField::Mass:
      return [&a](std::size_t i) { return double(atomic_mass(a.atomic_numbers[i])); };
    case NumberField::ResidueNumber:
      return [&a](std::size_t i) { return double(a.residue_numbers[i]); };
    case NumberField::Index:
      return [](std::size_t i) { return double(i); };
    case NumberField::PositionNumber:
      return [](std::size_t i) { return double(i) + 1.0; };
    case NumberField::Serial:
      return [&a](std::size_t i) { return double(a.serials[i]); };
    case NumberField::ResidueIndex:
      return [&a](std::size_t i) { return double(a.residue_indices[i]); };
    case NumberField::Molecule:
      return [&a](std::size_t i) { return double(a.molecule_ids[i]); };
    case NumberField::Array:
      break;
  }
  const auto array = context.arrays.find(node.array_name);
  if (array == context.arrays.end())
  {
    throw SelectionError(detail::selection_error_message(
                           context.expression,
                           "'" + node.array_name + "' is neither a keyword nor a per-atom array",
                           node.position),
                         node.position);
  }
  if (array->second.size() != a.size())
  {
    throw SelectionError(
      detail::selection_error_message(context.expression,
                                      "the array '" + node.array_name + "' has " +
                                        std::to_string(array->second.size()) + " values for " +
                                        std::to_string(a.size()) + " atoms",
                                      node.position),
      node.position);
  }
  const std::vector<double>& values = array->second;
  return [&values](std::size_t i) { return values[i]; };
}

bool compare(double value, detail::Comparison comparison, double reference)
{
  switch (comparison)
  {
    case detail::Comparison::Less:
      return value < reference;
    case detail::Comparison::LessEqual:
      return value <= reference;
    case detail::Comparison::Greater:
      return value > reference;
    case detail::Comparison::GreaterEqual:
      return value >= reference;
    case detail::Comparison::Equal:
      return value == reference;
    case detail::Comparison::NotEqual:
      break;
  }
  return value != reference;
}

Mask compare_mask(const SelectionNode& node, const Context& context)
{
  const auto value = field_values(node, context);
  Mask mask(context.atoms.size(), 0);
  for (std::size_t i = 0; i < mask.size(); ++i)
  {
    mask[i] = compare(value(i), node.comparison, node.value) ? 1 : 0;
  }
  return mask;
}

Mask ranges_mask(const SelectionNode& node, const Context& context)
{
  const auto value = field_values(node, context);
  const AtomTable& atoms = context.atoms;
  Mask mask(atoms.size(), 0);
  for (std::size_t i = 0; i < mask.size(); ++i)
  {
    const double v = value(i);
    mask[i] = std::any_of(node.ranges.begin(), node.ranges.end(),
                          [&](const detail::IntegerRange& range) {
                            return v >= double(range.low) && v <= double(range.high) &&
                              (range.insertion_code == 0 ||
                               atoms.insertion_codes[i] == range.insertion_code);
                          })
      ? 1
      : 0;
  }
  return mask;
}

Mask element_mask(const SelectionNode& node, const AtomTable& atoms)
{
  Mask mask(atoms.size(), 0);
  for (std::size_t i = 0; i < mask.size(); ++i)
  {
    mask[i] = std::find(node.atomic_numbers.begin(), node.atomic_numbers.end(),
                        int(atoms.atomic_numbers[i])) != node.atomic_numbers.end();
  }
  return mask;
}

/// Every atom of a group (residue, chain, molecule) that has a selected atom.
template<typename Key>
Mask whole_groups(const std::vector<Key>& keys, const Mask& selected)
{
  std::unordered_set<Key> chosen;
  for (std::size_t i = 0; i < keys.size(); ++i)
  {
    if (selected[i])
    {
      chosen.insert(keys[i]);
    }
  }
  Mask mask(keys.size(), 0);
  for (std::size_t i = 0; i < keys.size(); ++i)
  {
    mask[i] = chosen.count(keys[i]) ? 1 : 0;
  }
  return mask;
}

Mask evaluate_node(const SelectionNode& node, const Context& context);

Mask combine(const SelectionNode& node, const Context& context)
{
  const bool all = node.kind == SelectionNode::Kind::And;
  Mask mask = evaluate_node(*node.operands.front(), context);
  for (std::size_t k = 1; k < node.operands.size(); ++k)
  {
    const Mask other = evaluate_node(*node.operands[k], context);
    for (std::size_t i = 0; i < mask.size(); ++i)
    {
      mask[i] = all ? (mask[i] & other[i]) : (mask[i] | other[i]);
    }
  }
  return mask;
}

Mask within_mask(const SelectionNode& node, const Context& context)
{
  const Mask reference = evaluate_node(*node.operands.front(), context);
  Mask mask =
    detail::atoms_within(context.atoms.positions, reference, node.distance, context.parallel_for);
  if (node.exclusive)
  {
    for (std::size_t i = 0; i < mask.size(); ++i)
    {
      mask[i] &= reference[i] ? 0 : 1;
    }
  }
  return mask;
}

Mask same_mask(const SelectionNode& node, const Context& context)
{
  const Mask selected = evaluate_node(*node.operands.front(), context);
  switch (node.grouping)
  {
    case detail::Grouping::Residue:
      return whole_groups(context.atoms.residue_indices, selected);
    case detail::Grouping::Chain:
      return whole_groups(context.atoms.chain_ids, selected);
    case detail::Grouping::Molecule:
      break;
  }
  return whole_groups(context.atoms.molecule_ids, selected);
}

Mask evaluate_node(const SelectionNode& node, const Context& context)
{
  switch (node.kind)
  {
    case SelectionNode::Kind::Class:
      return class_mask(node.atom_class, context.atoms);
    case SelectionNode::Kind::Text:
      return text_mask(node, context.atoms);
    case SelectionNode::Kind::Element:
      return element_mask(node, context.atoms);
    case SelectionNode::Kind::Ranges:
      return ranges_mask(node, context);
    case SelectionNode::Kind::Compare:
      return compare_mask(node, context);
    case SelectionNode::Kind::Not: {
      Mask mask = evaluate_node(*node.operands.front(), context);
      for (auto& m : mask)
      {
        m = m ? 0 : 1;
      }
      return mask;
    }
    case SelectionNode::Kind::And:
    case SelectionNode::Kind::Or:
      return combine(node, context);
    case SelectionNode::Kind::Within:
      return within_mask(node, context);
    case SelectionNode::Kind::Same:
      break;
  }
  return same_mask(node, context);
}

void collect_array_names(const SelectionNode& node, std::set<std::string>& names)
{
  if (node.kind == SelectionNode::Kind::Compare && node.number_field == NumberField::Array)
  {
    names.insert(node.array_name);
  }
  for (const auto& operand : node.operands)
  {
    collect_array_names(*operand, names);
  }
}

} // namespace

AtomSelection::AtomSelection(const std::string& expression)
  : Expression(expression)
  , Root(detail::parse_selection(expression))
{
}

std::vector<std::uint8_t> AtomSelection::evaluate(const AtomTable& atoms,
                                                  const SelectionArrays& arrays,
                                                  const ParallelFor& parallel_for) const
{
  atoms.check_consistent();
  const Context context{ atoms, arrays, parallel_for, this->Expression };
  return evaluate_node(*this->Root, context);
}

std::vector<std::string> AtomSelection::array_names() const
{
  std::set<std::string> names;
  collect_array_names(*this->Root, names);
  return { names.begin(), names.end() };
}

std::vector<std::uint8_t> select_atoms(const AtomTable& atoms, const std::string& expression,
                                       const SelectionArrays& arrays)
{
  return AtomSelection(expression).evaluate(atoms, arrays);
}

} // namespace mesolens
