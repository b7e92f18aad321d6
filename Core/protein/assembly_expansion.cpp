// SPDX-License-Identifier: GPL-3.0-or-later
// expand_assembly(): the copies of an assembly as one atom table.
#include "mesolens/common/errors.h"
#include "mesolens/protein/assembly.h"
#include "protein/detail/assembly_reach.h"

#include <unordered_map>

namespace mesolens {

namespace {

/// What every copy of one generator shares: its rows, the bonds among them and the dense
/// numbering of their residues, molecules and secondary-structure spans.
struct GeneratorPlan
{
  std::vector<std::uint32_t> rows;
  std::vector<Bond> bonds; ///< between positions in `rows`
  std::vector<int> residues, molecules, spans;
  int residue_count = 0, molecule_count = 0, span_count = 0;
};

/// Where one copy goes in the expanded table.
struct CopyPlan
{
  const GeneratorPlan* generator = nullptr;
  const AssemblyMatrix* matrix = nullptr;
  std::size_t atom_offset = 0, bond_offset = 0;
  int residue_offset = 0, molecule_offset = 0, span_offset = 0;
};

/// Per row of `rows`, the rank of values[row] among the distinct values in order of first
/// appearance; negative values (no span) stay -1. Returns the number of distinct values.
int dense_ranks(const std::vector<int>& values, const std::vector<std::uint32_t>& rows,
                std::vector<int>& ranks)
{
  std::unordered_map<int, int> rank_of;
  ranks.resize(rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k)
  {
    const int value = values[rows[k]];
    ranks[k] = value < 0 ? -1 : rank_of.emplace(value, int(rank_of.size())).first->second;
  }
  return int(rank_of.size());
}

GeneratorPlan plan_generator(const AtomTable& table, const AssemblyGenerator& generator)
{
  GeneratorPlan plan;
  plan.rows = generator_atoms(table, generator);
  std::vector<std::int64_t> local(table.size(), -1);
  for (std::size_t k = 0; k < plan.rows.size(); ++k)
  {
    local[plan.rows[k]] = std::int64_t(k);
  }
  for (const Bond& bond : table.bonds) // rows increase, so the local bonds stay sorted
  {
    if (local[bond.first] >= 0 && local[bond.second] >= 0)
    {
      plan.bonds.push_back({ std::uint32_t(local[bond.first]), std::uint32_t(local[bond.second]) });
    }
  }
  plan.residue_count = dense_ranks(table.residue_indices, plan.rows, plan.residues);
  plan.molecule_count = dense_ranks(table.molecule_ids, plan.rows, plan.molecules);
  plan.span_count = dense_ranks(table.secondary_structure_ids, plan.rows, plan.spans);
  return plan;
}

void resize_atoms(AtomTable& table, std::size_t count)
{
  table.positions.resize(3 * count);
  table.atom_names.resize(count);
  table.atomic_numbers.resize(count);
  table.residue_names.resize(count);
  table.residue_numbers.resize(count);
  table.insertion_codes.resize(count);
  table.chain_ids.resize(count);
  table.label_asym_ids.resize(count);
  table.alt_locs.resize(count);
  table.occupancies.resize(count);
  table.b_factors.resize(count);
  table.is_hetero.resize(count);
  table.serials.resize(count);
  table.formal_charges.resize(count);
  table.secondary_structure.resize(count);
  table.secondary_structure_ids.resize(count);
  table.residue_indices.resize(count);
  table.molecule_ids.resize(count);
}

/// A chain id renamed for one copy, computed once per run of equal ids.
class ChainRenamer
{
public:
  explicit ChainRenamer(std::size_t copy)
    : Copy(copy)
  {
  }
  const std::string& operator()(const std::string& chain)
  {
    if (!this->Valid || chain != this->Last)
    {
      this->Last = chain;
      this->Renamed = assembly_chain_name(chain, this->Copy);
      this->Valid = true;
    }
    return this->Renamed;
  }

private:
  std::size_t Copy;
  bool Valid = false;
  std::string Last, Renamed;
};

/// Writes copy `copy` into `out`.
void write_copy(const AtomTable& in, const CopyPlan& plan, std::size_t copy, AssemblyExpansion& out)
{
  const GeneratorPlan& generator = *plan.generator;
  const AssemblyMatrix& m = *plan.matrix;
  AtomTable& t = out.atoms;
  ChainRenamer chain_name(copy), label_name(copy);
  for (std::size_t k = 0; k < generator.rows.size(); ++k)
  {
    const std::size_t i = generator.rows[k];
    const std::size_t o = plan.atom_offset + k;
    const std::array<double, 3> p =
      transform_point(m, { in.positions[3 * i], in.positions[3 * i + 1], in.positions[3 * i + 2] });
    for (std::size_t d = 0; d < 3; ++d)
    {
      t.positions[3 * o + d] = float(p[d]);
    }
    t.atom_names[o] = in.atom_names[i];
    t.atomic_numbers[o] = in.atomic_numbers[i];
    t.residue_names[o] = in.residue_names[i];
    t.residue_numbers[o] = in.residue_numbers[i];
    t.insertion_codes[o] = in.insertion_codes[i];
    t.chain_ids[o] = chain_name(in.chain_ids[i]);
    t.label_asym_ids[o] = in.label_asym_ids[i].empty() ? "" : label_name(in.label_asym_ids[i]);
    t.alt_locs[o] = in.alt_locs[i];
    t.occupancies[o] = in.occupancies[i];
    t.b_factors[o] = in.b_factors[i];
    t.is_hetero[o] = in.is_hetero[i];
    t.serials[o] = in.serials[i];
    t.formal_charges[o] = in.formal_charges[i];
    t.secondary_structure[o] = in.secondary_structure[i];
    const int span = generator.spans[k];
    t.secondary_structure_ids[o] = span < 0 ? -1 : plan.span_offset + span;
    t.residue_indices[o] = plan.residue_offset + generator.residues[k];
    t.molecule_ids[o] = plan.molecule_offset + generator.molecules[k];
    out.copy_of_atom[o] = int(copy);
  }
  const auto base = std::uint32_t(plan.atom_offset);
  for (std::size_t b = 0; b < generator.bonds.size(); ++b)
  {
    t.bonds[plan.bond_offset + b] = { base + generator.bonds[b].first,
                                      base + generator.bonds[b].second };
  }
}

} // namespace

AssemblyExpansion expand_assembly(const AtomTable& asymmetric_unit, const Assembly& assembly,
                                  const AssemblyExpansionParams& params)
{
  asymmetric_unit.check_consistent();
  std::vector<GeneratorPlan> generators;
  generators.reserve(assembly.generators.size());
  std::vector<CopyPlan> copies;
  std::size_t atoms = 0, bonds = 0;
  const std::size_t limit = std::min(params.max_atoms, max_assembly_atoms);
  CopyPlan next;
  for (const AssemblyGenerator& generator : assembly.generators)
  {
    generators.push_back(plan_generator(asymmetric_unit, generator));
    const GeneratorPlan& plan = generators.back();
    detail::check_float_reach(asymmetric_unit, plan.rows, generator, assembly.name);
    const std::size_t per_copy = plan.rows.size();
    if (per_copy > 0 && generator.operators.size() > (limit - atoms) / per_copy)
    {
      throw InvalidInput("assembly '" + assembly.name + "' has " +
                         std::to_string(assembly_atom_count(asymmetric_unit, assembly)) +
                         " atoms, more than the limit of " + std::to_string(limit) +
                         (limit < max_assembly_atoms ? " (AssemblyExpansionParams::max_atoms)"
                                                     : " (AtomTable numbers atoms with int)") +
                         "; draw it by instancing (assembly_instances())");
    }
    for (const AssemblyOperator& op : generator.operators)
    {
      next.generator = &plan;
      next.matrix = &op.matrix;
      copies.push_back(next);
      next.atom_offset += per_copy;
      next.bond_offset += plan.bonds.size();
      next.residue_offset += plan.residue_count;
      next.molecule_offset += plan.molecule_count;
      next.span_offset += plan.span_count;
    }
    atoms = next.atom_offset;
    bonds = next.bond_offset;
  }
  AssemblyExpansion result;
  resize_atoms(result.atoms, atoms);
  result.atoms.bonds.resize(bonds);
  result.copy_of_atom.resize(atoms);
  run_parallel(params.parallel_for, copies.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c)
    {
      write_copy(asymmetric_unit, copies[c], c, result);
    }
  });
  return result;
}

} // namespace mesolens
