// SPDX-License-Identifier: GPL-3.0-or-later
// The biological assemblies of PDB and mmCIF files, read for read_structure() (private to io).
#pragma once

#include "mesolens/molecules/atom_table.h"
#include "mesolens/protein/assembly.h"

#include "io/detail/text_fields.h"

#include <cstddef>
#include <string>
#include <vector>

namespace gemmi {
namespace cif {
struct Block;
}
}

namespace mesolens {
namespace detail {

/// The assemblies of a PDB file's REMARK 350 records: per "BIOMOLECULE: n", the generators
/// that "APPLY THE FOLLOWING TO CHAINS:" (continued by "AND CHAINS:" lines) starts, each with
/// the operators of its BIOMT1-3 lines. The BIOMT fields are read as blank-separated words,
/// not by column: gemmi 0.5 reads them by column and misreads the matrices of files whose
/// serials outgrow their field (1m4x: from serial 100 on, the numbers are pushed right).
/// An assembly with a malformed BIOMT line (not "serial m1 m2 m3 t", rows out of order, a
/// serial that changes within an operator, an operator before any chain list) is left out with
/// a warning; so are BIOMT lines before any BIOMOLECULE. `remarks` are the file's REMARK
/// records in order (others are passed over).
std::vector<Assembly> read_pdb_assemblies(const std::vector<NumberedLine>& remarks,
                                          std::vector<std::string>& warnings);

/// The assemblies of an mmCIF block (`_pdbx_struct_assembly`, `_pdbx_struct_assembly_gen`,
/// `_pdbx_struct_oper_list`), operator expressions expanded by expand_operator_expression(). An
/// assembly whose expression does not parse is left out with a warning; so are the assemblies
/// past max_assembly_copies copies in all (counted before anything is composed). Generators of
/// an assembly id that `_pdbx_struct_assembly` does not list make an assembly of their own.
/// Then removes `_pdbx_struct_assembly_gen` from the block: gemmi's own reading of it expands
/// only the first list of a product and can spend unbounded time on a range like (1-2000000000).
std::vector<Assembly> read_mmcif_assemblies(gemmi::cif::Block& block,
                                            std::vector<std::string>& warnings);

/// Leaves out, with a warning naming the assembly and the reason: assemblies without copies,
/// with a generator that names no chain, with a non-finite matrix entry (given or composed),
/// with the name of an earlier assembly, and those past max_assembly_copies copies in all.
void check_assemblies(std::vector<Assembly>& assemblies, std::vector<std::string>& warnings);

/// Adds one warning per assembly that names chains (author ids or label_asym_ids) that `model`
/// (the file's first model, before any atom is removed) does not have; the assembly is kept.
void warn_missing_chains(const std::vector<Assembly>& assemblies, const AtomTable& model,
                         std::vector<std::string>& warnings);

} // namespace detail
} // namespace mesolens
