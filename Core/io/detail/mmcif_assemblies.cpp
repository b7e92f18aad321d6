// SPDX-License-Identifier: GPL-3.0-or-later
// _pdbx_struct_assembly, _pdbx_struct_assembly_gen and _pdbx_struct_oper_list of mmCIF files.
#include "io/detail/assembly_records.h"
#include "io/detail/text_fields.h"
#include "mesolens/common/errors.h"

#include <gemmi/cifdoc.hpp>
#include <gemmi/numb.hpp>

#include <algorithm>
#include <unordered_map>

namespace mesolens {
namespace detail {

namespace {

namespace cif = gemmi::cif;

AssemblyOperatorTable read_operator_list(cif::Block& block, std::vector<std::string>& warnings)
{
  std::vector<std::string> tags = { "id" };
  for (int i = 1; i <= 3; ++i)
  {
    for (int j = 1; j <= 3; ++j)
    {
      tags.push_back("matrix[" + std::to_string(i) + "][" + std::to_string(j) + "]");
    }
    tags.push_back("vector[" + std::to_string(i) + "]");
  }
  cif::Table table = block.find("_pdbx_struct_oper_list.", tags);
  AssemblyOperatorTable operators;
  if (!table.ok())
  {
    if (block.find_values("_pdbx_struct_oper_list.id").item())
    {
      warnings.push_back("_pdbx_struct_oper_list lacks some of its matrix[i][j] and vector[i] "
                         "items; its operators were ignored");
    }
    return operators;
  }
  std::size_t repeated = 0;
  for (const cif::Table::Row row : table)
  {
    AssemblyMatrix matrix{};
    for (std::size_t k = 0; k < 12; ++k)
    {
      matrix[k] = cif::as_number(row[k + 1]);
    }
    repeated += operators.emplace(row.str(0), matrix).second ? 0 : 1;
  }
  if (repeated > 0)
  {
    warnings.push_back(std::to_string(repeated) +
                       " _pdbx_struct_oper_list ids are repeated; the first of each was used");
  }
  return operators;
}

std::vector<std::string> asym_ids(const std::string& list)
{
  std::string text = list;
  std::replace(text.begin(), text.end(), ',', ' ');
  std::vector<std::string> ids;
  for (const std::string_view word : split_words(text))
  {
    if (std::find(ids.begin(), ids.end(), word) == ids.end())
    {
      ids.emplace_back(word);
    }
  }
  return ids;
}

/// Removes the category's pairs and loops from the block.
void erase_category(cif::Block& block, const std::string& prefix)
{
  for (cif::Item& item : block.items)
  {
    if (item.type == cif::ItemType::Pair && gemmi::istarts_with(item.pair[0], prefix))
    {
      item.erase();
    }
    else if (item.type == cif::ItemType::Loop &&
             std::any_of(
               item.loop.tags.begin(), item.loop.tags.end(),
               [&prefix](const std::string& tag) { return gemmi::istarts_with(tag, prefix); }))
    {
      item.erase();
    }
  }
}

/// The assemblies being read, by name, with the first problem of each.
struct AssemblyList
{
  std::vector<Assembly> assemblies;
  std::vector<std::string> problems;
  std::unordered_map<std::string, std::size_t> index;

  std::size_t find_or_add(const std::string& name)
  {
    const auto found = this->index.emplace(name, this->assemblies.size());
    if (found.second)
    {
      this->assemblies.emplace_back();
      this->assemblies.back().name = name;
      this->problems.emplace_back();
    }
    return found.first->second;
  }
};

void read_generators(cif::Block& block, const AssemblyOperatorTable& operators, AssemblyList& list,
                     std::vector<std::string>& warnings)
{
  cif::Table table =
    block.find("_pdbx_struct_assembly_gen.", { "assembly_id", "oper_expression", "asym_id_list" });
  if (!table.ok() && block.find_values("_pdbx_struct_assembly_gen.assembly_id").item())
  {
    warnings.push_back("_pdbx_struct_assembly_gen lacks its oper_expression or asym_id_list; "
                       "its assemblies were left out");
  }
  std::size_t copies = 0; // of all assemblies: the budget is max_assembly_copies
  for (const cif::Table::Row row : table)
  {
    const std::size_t a = list.find_or_add(row.str(0));
    if (!list.problems[a].empty())
    {
      continue;
    }
    AssemblyGenerator generator;
    generator.chain_ids = AssemblyChainIds::Label;
    generator.chains = asym_ids(row.str(2));
    try
    {
      generator.operators =
        expand_operator_expression(row.str(1), operators, max_assembly_copies - copies);
    }
    catch (const InvalidInput& e)
    {
      list.problems[a] = e.what();
      if (copies > 0 && list.problems[a].find(" more than ") != std::string::npos)
      {
        list.problems[a] += " (" + std::to_string(max_assembly_copies) +
          " copies at most are read from one file; " + std::to_string(copies) + " were before)";
      }
      continue;
    }
    copies += generator.operators.size();
    list.assemblies[a].generators.push_back(std::move(generator));
  }
}

} // namespace

std::vector<Assembly> read_mmcif_assemblies(cif::Block& block, std::vector<std::string>& warnings)
{
  const AssemblyOperatorTable operators = read_operator_list(block, warnings);
  AssemblyList list;
  for (const cif::Table::Row row : block.find("_pdbx_struct_assembly.", { "id", "?details" }))
  {
    const std::size_t a = list.find_or_add(row.str(0));
    list.assemblies[a].details = row.has(1) ? row.str(1) : std::string();
  }
  read_generators(block, operators, list, warnings);
  erase_category(block, "_pdbx_struct_assembly_gen.");
  std::vector<Assembly> assemblies;
  for (std::size_t a = 0; a < list.assemblies.size(); ++a)
  {
    if (list.problems[a].empty())
    {
      assemblies.push_back(std::move(list.assemblies[a]));
      continue;
    }
    warnings.push_back("assembly '" + list.assemblies[a].name + "' (_pdbx_struct_assembly_gen): " +
                       list.problems[a] + "; the assembly was left out");
  }
  check_assemblies(assemblies, warnings);
  return assemblies;
}

} // namespace detail
} // namespace mesolens
