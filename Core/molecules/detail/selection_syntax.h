// SPDX-License-Identifier: GPL-3.0-or-later
// The syntax tree of an atom selection and its parser (private to MesoLensCore; the grammar is
// documented in mesolens/molecules/atom_selection.h).
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace mesolens {
namespace detail {

/// Residue classes and atom classes named by one keyword.
enum class AtomClass
{
  All,
  None,
  Protein,
  Nucleic,
  Water,
  Lipid,
  Backbone,
  Hydrogen,
  Hetero,
};

/// Per-atom text fields matched against patterns.
enum class TextField
{
  Name,
  ResidueName,
  Chain,
  AltLoc,
};

/// Per-atom numbers: compared with numbers or matched against integer ranges.
enum class NumberField
{
  X,
  Y,
  Z,
  Occupancy,
  BFactor,
  FormalCharge,
  Mass,
  ResidueNumber,
  Index,
  PositionNumber, ///< index + 1
  Serial,
  ResidueIndex,
  Molecule,
  Array, ///< a caller's array, named by SelectionNode::array_name
};

enum class Comparison
{
  Less,
  LessEqual,
  Greater,
  GreaterEqual,
  Equal,
  NotEqual,
};

/// An inclusive integer range; `insertion_code` (0 = any) only for residue numbers.
struct IntegerRange
{
  long long low = 0;
  long long high = 0;
  char insertion_code = 0;
};

/// What `same ... as` groups by.
enum class Grouping
{
  Residue,
  Chain,
  Molecule,
};

/// One node of the tree. Which members count depends on `kind`.
struct SelectionNode
{
  enum class Kind
  {
    Class,   ///< atom_class
    Text,    ///< text_field matches one of patterns
    Element, ///< atomic number in integers
    Ranges,  ///< number_field in one of ranges
    Compare, ///< number_field (or array_name) compared with value
    Not,     ///< operands[0]
    And,     ///< every operand
    Or,      ///< any operand
    Within,  ///< distance of operands[0]; exclusive drops operands[0] itself
    Same,    ///< grouping as operands[0]
  };
  Kind kind = Kind::Class;
  std::size_t position = 0; ///< 0-based offset of the clause in the expression
  AtomClass atom_class = AtomClass::All;
  TextField text_field = TextField::Name;
  std::vector<std::string> patterns;
  std::vector<int> atomic_numbers;
  NumberField number_field = NumberField::Index;
  std::string array_name;
  std::vector<IntegerRange> ranges;
  Comparison comparison = Comparison::Equal;
  double value = 0.0;
  double distance = 0.0;
  bool exclusive = false;
  Grouping grouping = Grouping::Residue;
  std::vector<std::unique_ptr<SelectionNode>> operands;
};

/// Parses `expression` into a tree. Throws SelectionError (with the offending character).
std::unique_ptr<SelectionNode> parse_selection(const std::string& expression);

/// Formats a SelectionError message: the quoted expression, the problem and the 1-based
/// character it is at.
std::string selection_error_message(const std::string& expression, const std::string& problem,
                                    std::size_t position);

} // namespace detail
} // namespace mesolens
