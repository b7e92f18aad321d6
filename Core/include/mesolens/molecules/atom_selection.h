// SPDX-License-Identifier: GPL-3.0-or-later
// Atom selections written as text ("resname CHOL", "chain A and within 5 of resname LIG"), in
// a language close to VMD's and MDAnalysis'.
#pragma once

#include "mesolens/common/errors.h"
#include "mesolens/common/parallel_for.h"
#include "mesolens/molecules/atom_table.h"

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace mesolens {

/// A selection that cannot be parsed or evaluated. what() is one line that quotes the
/// expression and names the character where the problem is, e.g.
/// `selection "name CA and (resid 5": missing ')' at character 24`.
class SelectionError : public InvalidInput
{
public:
  SelectionError(const std::string& message, std::size_t position);
  /// 0-based offset of the offending character in the expression.
  std::size_t position() const
  {
    return this->Position;
  }

private:
  std::size_t Position;
};

/// Per-atom numeric arrays that a selection may compare by name, besides the built-in fields
/// ("charge > 0" where a filter passes its `charge` point array): one value per atom.
using SelectionArrays = std::map<std::string, std::vector<double>>;

namespace detail {
struct SelectionNode;
}

/// A parsed selection, evaluated on any AtomTable (every model or trajectory frame).
///
/// Grammar (keywords are lower case; values are case-sensitive except element symbols):
///
///     expression := term ("or" term)*
///     term       := factor ("and" factor)*
///     factor     := "not" factor | "(" expression ")" | clause
///     clause     := "all" | "none" | "protein" | "nucleic" | "water" | "lipid" | "backbone"
///                 | "hydrogen" | "hetero"
///                 | ("name" | "resname" | "chain" | "chainid" | "altloc") pattern+
///                 | "element" symbol+
///                 | ("resid" | "resnum" | "index" | "bynum" | "serial" | "id" | "residue"
///                   | "resindex" | "molecule") range+
///                 | ["prop"] field ("<" | "<=" | ">" | ">=" | "==" | "=" | "!=") number
///                 | "within" distance "of" factor | "exwithin" distance "of" factor
///                 | "around" distance factor
///                 | "same" ("residue" | "chain" | "molecule") "as" factor | "byres" factor
///
/// - `and` binds tighter than `or`; `not`, `within`, `around`, `same` and `byres` apply to the
///   factor that follows (one clause or a parenthesis): `within 5 of resname LIG and chain A`
///   is `(within 5 of resname LIG) and chain A`.
/// - A pattern is a word or a "double-quoted" string (for names with blanks or keywords);
///   `*`, `?` and `[...]` are shell wildcards (`name C*`). Lists end at `and`, `or`, `)` or
///   the next keyword.
/// - A range is `5`, `5-10`, `5:10` or `5 to 10` (inclusive; negative numbers allowed); a
///   resid may carry an insertion code (`52A`).
/// - `resid`/`resnum`: the author residue number; `index`: 0-based atom position; `bynum`:
///   1-based position (MDAnalysis); `serial`/`id`: the file's serial number; `residue` and
///   `resindex`: 0-based running residue index (VMD's `residue`); `molecule`: the molecule id.
/// - Fields: x, y, z (Å), occupancy, beta (also bfactor, tempfactor; Å²), charge (formal),
///   mass (Da), the integer keywords above, and any name in SelectionArrays.
/// - `protein`: amino-acid residues (PDB chemical components and force-field variants);
///   `nucleic`: nucleotides; `water`: is_water_residue(); `lipid`: is_lipid_residue();
///   `backbone`: atoms N, CA, C, O of protein residues (MDAnalysis' definition); `hydrogen`:
///   element H (and D); `hetero`: HETATM records.
/// - `within D of X`: atoms at most D Å from an atom of X, X included (VMD); `exwithin`
///   excludes X; `around D X` is exwithin (MDAnalysis). Plain distances: periodic images are
///   not considered.
/// - `same residue as X` (or `byres X`): every atom of a residue that has an atom in X.
class AtomSelection
{
public:
  /// Parses `expression`. Throws SelectionError for a syntax error, an unknown keyword, an
  /// element symbol that names no element, a reversed range or a negative or non-finite
  /// distance.
  explicit AtomSelection(const std::string& expression);

  /// 1 for each selected atom of `atoms`, 0 for the others (size atoms.size()). `arrays`
  /// holds the numeric arrays the expression compares beyond the built-in fields;
  /// `parallel_for` runs the distance searches. Throws SelectionError when the expression
  /// compares an array that `arrays` lacks or that has the wrong length, InvalidInput when the
  /// table is inconsistent.
  std::vector<std::uint8_t> evaluate(const AtomTable& atoms, const SelectionArrays& arrays = {},
                                     const ParallelFor& parallel_for = {}) const;

  /// Names the expression compares that are not built-in fields (what `arrays` must hold).
  std::vector<std::string> array_names() const;

  /// The expression as given.
  const std::string& expression() const
  {
    return this->Expression;
  }

private:
  std::string Expression;
  std::shared_ptr<const detail::SelectionNode> Root;
};

/// AtomSelection(expression).evaluate(atoms, arrays).
std::vector<std::uint8_t> select_atoms(const AtomTable& atoms, const std::string& expression,
                                       const SelectionArrays& arrays = {});

} // namespace mesolens
