// SPDX-License-Identifier: GPL-3.0-or-later
// Biological assemblies: the copies of a structure file's asymmetric unit that make the molecule
// as it exists in nature (a dimer, a virus capsid), as PDB REMARK 350 BIOMT records and mmCIF
// _pdbx_struct_assembly* categories define them; given as expanded atoms or as instance matrices.
#pragma once

#include "mesolens/common/parallel_for.h"
#include "mesolens/molecules/atom_table.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

namespace mesolens {

/// An affine map as a 3x4 matrix [R | t] in row-major order:
/// {R00, R01, R02, t0, R10, R11, R12, t1, R20, R21, R22, t2}. It maps a point x (Å) to R·x + t
/// (Å). This is the layout of a BIOMT operator's three lines (BIOMT1, BIOMT2, BIOMT3) and of
/// mmCIF's `matrix[i][j]` and `vector[i]`. Assembly operators are rotations (or, rarely,
/// near-rotations) in Cartesian Ångström coordinates.
using AssemblyMatrix = std::array<double, 12>;

/// The identity map.
constexpr AssemblyMatrix identity_assembly_matrix()
{
  return { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0 };
}

/// The matrix product left·right: the map that applies `right` first, then `left` (the mmCIF
/// convention for a product of operators, see expand_operator_expression()).
AssemblyMatrix compose(const AssemblyMatrix& left, const AssemblyMatrix& right);

/// R·p + t for a point p (Å).
std::array<double, 3> transform_point(const AssemblyMatrix& matrix, const std::array<double, 3>& p);

/// The rotation R of `matrix` as a unit quaternion (w, x, y, z), w >= 0: what instanced
/// drawing (vtkGlyph3DMapper's QUATERNION orientation) takes. Precondition: R is a proper
/// rotation to 1e-3 (R Rᵀ = I and det R = 1 within 1e-3 per entry, as the PDB writes them with
/// six decimals); throws InvalidInput otherwise (a reflection or a scaling cannot be drawn as a
/// rotated copy: expand the assembly instead).
std::array<double, 4> rotation_quaternion(const AssemblyMatrix& matrix);

/// One copy of the atoms an AssemblyGenerator names.
struct AssemblyOperator
{
  /// The file's id of the operator ("1", "P", "X0"; a BIOMT serial). For a product of mmCIF
  /// operators, the factors' ids joined by 'x' in the expression's order: "1x61" is operator 61
  /// applied first, then operator 1.
  std::string name;
  AssemblyMatrix matrix = identity_assembly_matrix();
};

/// Which ids an AssemblyGenerator's `chains` are.
enum class AssemblyChainIds : std::uint8_t
{
  /// Author chain ids, matched against AtomTable::chain_ids (PDB REMARK 350 "APPLY THE
  /// FOLLOWING TO CHAINS").
  Author,
  /// mmCIF label_asym_ids, matched against AtomTable::label_asym_ids
  /// (`_pdbx_struct_assembly_gen.asym_id_list`): one author chain may hold several, e.g. its
  /// polymer, its ligands and its waters, which an assembly may take apart.
  Label,
};

/// Operators and the chains they apply to: each operator makes one copy of those chains' atoms.
struct AssemblyGenerator
{
  /// Ids of the chains the operators apply to, each once, in the file's order.
  std::vector<std::string> chains;
  /// Whether `chains` holds author chain ids (PDB) or label_asym_ids (mmCIF).
  AssemblyChainIds chain_ids = AssemblyChainIds::Author;
  /// One operator per copy, in the file's order (mmCIF products expanded, see
  /// expand_operator_expression()).
  std::vector<AssemblyOperator> operators;
};

/// A biological assembly of a structure file. Its copies are numbered from 0 over the
/// generators in order and, within a generator, over its operators in order: generator 0's
/// operators are copies 0 .. n0 - 1, generator 1's are n0 .. n0 + n1 - 1, and so on. Callers
/// choose an assembly by name (find_assembly()); the asymmetric unit, the atoms as the file
/// gives them, is no assembly.
struct Assembly
{
  /// The file's name: the BIOMOLECULE number ("1", "2") of a PDB file, `_pdbx_struct_assembly.id`
  /// ("1", "PAU") of an mmCIF file.
  std::string name;
  /// Free text: `_pdbx_struct_assembly.details` ("complete icosahedral assembly",
  /// "author_and_software_defined_assembly"), or a PDB file's "AUTHOR DETERMINED BIOLOGICAL
  /// UNIT: ..." (else "SOFTWARE DETERMINED QUATERNARY STRUCTURE: ...") line; may be empty.
  std::string details;
  std::vector<AssemblyGenerator> generators;

  /// Number of copies: the operators of all generators.
  std::size_t copy_count() const;
};

/// The most copies read_structure() accepts in one assembly, and in all the assemblies of one
/// file together; an assembly past it is skipped with a warning. The largest assemblies in the
/// PDB have a few thousand copies (1m4x: 1680).
constexpr std::size_t max_assembly_copies = 1000000;

/// The most atoms an expanded assembly may have: AtomTable numbers atoms, residues and
/// molecules with int (2^31 - 1).
constexpr std::size_t max_assembly_atoms = 2147483647;

/// The assembly named `name`, or nullptr when there is none (the caller then keeps the
/// asymmetric unit).
const Assembly* find_assembly(const std::vector<Assembly>& assemblies, const std::string& name);

/// The operators an mmCIF operator expression may name, by id (`_pdbx_struct_oper_list.id`).
using AssemblyOperatorTable = std::unordered_map<std::string, AssemblyMatrix>;

/// Expands an mmCIF operator expression (`_pdbx_struct_assembly_gen.oper_expression`) into its
/// operators, in order. Grammar (blanks between tokens are ignored):
///
///     expression := factor { factor }
///     factor     := "(" list ")" | list
///     list       := item { "," item }
///     item       := id | integer "-" integer       a range: every integer id from first to last
///     id         := one or more characters other than ( ) , - and blanks
///
/// e.g. `1`, `1,2,5`, `(1-60)`, `(1,2,5-8)`, `P`, `X0`. Several factors form a product, the
/// composition of one operator of each list: `(1-60)(61-88)` gives the 1680 matrices
/// M1·M61, M1·M62, ..., M1·M88, M2·M61, ..., M60·M88 (the rightmost operator is applied
/// first; the first factor varies slowest), named "1x61", "1x62", ... A range's ends are
/// decimal integers (first <= last) and name the ids written as decimals without leading zeros.
/// A list may name an operator more than once.
///
/// Throws InvalidInput, naming the offending part, for an empty expression, an unbalanced
/// parenthesis, an empty list item, a reversed range (`(5-1)`), a range end that is not an
/// integer, an id not in `operators`, or more than `max_operators` operators (counted before
/// any is composed: a product of large lists is refused without work).
std::vector<AssemblyOperator> expand_operator_expression(
  const std::string& expression, const AssemblyOperatorTable& operators,
  std::size_t max_operators = max_assembly_copies);

/// The chain id an atom of chain `chain` gets in copy `copy` (0-based) of an expanded assembly:
/// copy 0 keeps `chain`, copy c > 0 gets `chain` + "-" + (c + 1): chain "A" of copies 0, 1, 2 is
/// "A", "A-2", "A-3". Unambiguous as long as the file's chain ids contain no '-' (PDB chain ids
/// are one character; mmCIF files of the PDB use letters and digits). The label_asym_ids of
/// expanded atoms are renamed the same way.
std::string assembly_chain_name(const std::string& chain, std::size_t copy);

/// The rows of `table` that `generator` applies to, increasing. Throws InvalidInput when the
/// table lacks the ids the generator names (label_asym_ids not one per atom).
std::vector<std::uint32_t> generator_atoms(const AtomTable& table,
                                           const AssemblyGenerator& generator);

/// Number of atoms expand_assembly() would make: the sum over the generators of their atoms
/// times their operators. Cheap (no atom is copied): use it to decide between expanding and
/// instancing.
std::size_t assembly_atom_count(const AtomTable& asymmetric_unit, const Assembly& assembly);

/// Parameters of expand_assembly().
struct AssemblyExpansionParams
{
  /// Refuse (InvalidInput) an expansion with more atoms than this. Default and upper bound
  /// max_assembly_atoms. Mind the memory: an expanded atom takes about 175 bytes with its
  /// bonds (1m4x's 16.3 million atoms: 2.8 GB).
  std::size_t max_atoms = max_assembly_atoms;
  /// Runs the per-copy loop; empty: the calling thread only. The result does not depend on it.
  ParallelFor parallel_for;
};

/// An expanded assembly.
struct AssemblyExpansion
{
  /// The copies' atoms, copy after copy (copy order of Assembly), each copy's atoms in the
  /// asymmetric unit's order. Positions are transformed (float, Å); chain ids and label_asym_ids
  /// renamed by assembly_chain_name(); bonds copied within each copy (a bond whose atoms belong
  /// to different generators is dropped); residue indices, molecule ids and secondary-structure
  /// span ids renumbered so that every copy has its own; everything else (serials, residue
  /// numbers, names) kept. No periodic box (an assembly is not a crystal).
  AtomTable atoms;
  /// Per atom, its copy (0-based): the `AssemblyCopy` array.
  std::vector<int> copy_of_atom;
};

/// The assembly's atoms: every generator's operators applied to its atoms of
/// `asymmetric_unit` (the file's model, as read_structure() gives it, filtered or not; a
/// consistent table, AtomTable::check_consistent()). Throws InvalidInput when the result would
/// have more than params.max_atoms (at most max_assembly_atoms) atoms, naming both numbers;
/// when an operator may move atoms beyond float's range (|x| > 3.4e38 Å), naming it; and when
/// the generators name label_asym_ids the table does not have.
AssemblyExpansion expand_assembly(const AtomTable& asymmetric_unit, const Assembly& assembly,
                                  const AssemblyExpansionParams& params = {});

/// The atoms of the asymmetric unit that one or more copies are drawn from.
struct AssemblyAtomSet
{
  /// Rows of the asymmetric unit, increasing.
  std::vector<std::uint32_t> atoms;
  /// True when `atoms` holds every row: a renderer may draw the whole table per instance.
  bool whole_table = false;
  /// A sphere (Å) holding the atoms' centres, in the asymmetric unit's frame; radius 0 when the
  /// set is empty.
  std::array<double, 3> center{ { 0, 0, 0 } };
  double radius = 0;
};

/// One copy to draw: the set's atoms transformed by `matrix`.
struct AssemblyInstance
{
  AssemblyMatrix matrix = identity_assembly_matrix();
  /// Index into AssemblyInstances::atom_sets.
  std::size_t atom_set = 0;
  /// A sphere (Å) holding this copy's atom centres (the set's sphere transformed; its radius
  /// grows by the largest singular value of the matrix's R), for culling per copy.
  std::array<double, 3> center{ { 0, 0, 0 } };
  double radius = 0;
};

/// An assembly as the asymmetric unit drawn once per matrix: what an instanced mapper needs.
/// instances[c] is copy c (the same numbering as AssemblyExpansion::copy_of_atom), and the
/// atoms of copy c in expand_assembly() are atom_sets[instances[c].atom_set].atoms transformed
/// by instances[c].matrix, in that order.
struct AssemblyInstances
{
  /// The distinct atom sets: generators that select the same rows share one. In the common
  /// case of one generator over all chains, one set with whole_table set.
  std::vector<AssemblyAtomSet> atom_sets;
  /// One per copy, in copy order.
  std::vector<AssemblyInstance> instances;
};

/// The assembly as instance transforms over `asymmetric_unit` (nothing is copied). Throws
/// InvalidInput as expand_assembly() does for operators beyond float's range and missing ids.
AssemblyInstances assembly_instances(const AtomTable& asymmetric_unit, const Assembly& assembly);

/// The asymmetric unit's atoms grouped by the atom sets holding them, so that an instanced
/// draw can give every copy one motion per group and hide the groups its set leaves out.
struct AssemblyAtomClasses
{
  /// Per row of the asymmetric unit, its class: rows in the same sets share one. Classes are
  /// numbered by their first row.
  std::vector<std::uint32_t> class_of_atom;
  std::size_t count = 0; ///< classes
  /// Per class and atom set (class k, set s at k * sets + s): 1 where the set holds the class.
  std::vector<std::uint8_t> in_set;
  /// Whether copy `copy` of `instances` shows class `k`.
  bool shows(const AssemblyInstances& instances, std::size_t copy, std::size_t k) const
  {
    return this->in_set[k * instances.atom_sets.size() + instances.instances[copy].atom_set] != 0;
  }
};

/// The classes of the `atom_count` rows of the asymmetric unit under `instances`' atom sets (a
/// single class when one set holds every row). Linear in the sets' sizes. Throws InvalidInput
/// when a set names a row beyond `atom_count` (copies of another table) or a copy names a set
/// that does not exist.
AssemblyAtomClasses assembly_atom_classes(const AssemblyInstances& instances,
                                          std::size_t atom_count);

} // namespace mesolens
