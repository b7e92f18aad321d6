// SPDX-License-Identifier: GPL-3.0-or-later
// The checks every assembly a structure file gives passes (PDB and mmCIF alike).
#include "io/detail/assembly_records.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <unordered_set>

namespace mesolens {
namespace detail {

namespace {

/// Why the assembly cannot be used, or "" when it can.
std::string assembly_problem(const Assembly& assembly, std::size_t copies_before)
{
  const std::size_t copies = assembly.copy_count();
  if (assembly.name.empty())
  {
    return "has no name";
  }
  if (copies == 0)
  {
    return "has no operators";
  }
  if (copies > max_assembly_copies - std::min(copies_before, max_assembly_copies))
  {
    return "has " + std::to_string(copies) + " copies, which with the " +
      std::to_string(copies_before) + " of the assemblies before it passes the limit of " +
      std::to_string(max_assembly_copies);
  }
  for (const AssemblyGenerator& generator : assembly.generators)
  {
    if (generator.chains.empty())
    {
      return "a generator that names no chain";
    }
    for (const AssemblyOperator& op : generator.operators)
    {
      if (!std::all_of(op.matrix.begin(), op.matrix.end(),
                       [](double v) { return std::isfinite(v); }))
      {
        return "operator " + op.name + ", whose matrix has a non-finite entry";
      }
    }
  }
  return std::string();
}

} // namespace

void check_assemblies(std::vector<Assembly>& assemblies, std::vector<std::string>& warnings)
{
  std::vector<Assembly> kept;
  std::set<std::string> names;
  std::size_t copies = 0;
  for (Assembly& assembly : assemblies)
  {
    std::string problem = assembly_problem(assembly, copies);
    if (problem.empty() && !names.insert(assembly.name).second)
    {
      problem = "the name of an earlier assembly";
    }
    if (!problem.empty())
    {
      warnings.push_back("assembly '" + assembly.name.substr(0, 32) + "' " +
                         (problem.compare(0, 4, "has ") == 0 ? "" : "has ") + problem +
                         "; the assembly was left out");
      continue;
    }
    copies += assembly.copy_count();
    kept.push_back(std::move(assembly));
  }
  assemblies = std::move(kept);
}

void warn_missing_chains(const std::vector<Assembly>& assemblies, const AtomTable& model,
                         std::vector<std::string>& warnings)
{
  const std::unordered_set<std::string> authors(model.chain_ids.begin(), model.chain_ids.end());
  const std::unordered_set<std::string> labels(model.label_asym_ids.begin(),
                                               model.label_asym_ids.end());
  for (const Assembly& assembly : assemblies)
  {
    std::set<std::string> missing;
    for (const AssemblyGenerator& generator : assembly.generators)
    {
      const auto& present = generator.chain_ids == AssemblyChainIds::Label ? labels : authors;
      for (const std::string& chain : generator.chains)
      {
        if (present.count(chain) == 0)
        {
          missing.insert(chain);
        }
      }
    }
    if (missing.empty())
    {
      continue;
    }
    std::string list;
    std::size_t shown = 0;
    for (auto chain = missing.begin(); chain != missing.end() && shown < 8; ++chain, ++shown)
    {
      list += (shown > 0 ? ", " : "") + chain->substr(0, 8);
    }
    warnings.push_back("assembly '" + assembly.name.substr(0, 32) + "' names " +
                       std::to_string(missing.size()) + " chains the file does not have (" + list +
                       (missing.size() > shown ? ", ..." : "") + "); its copies lack them");
  }
}

} // namespace detail
} // namespace mesolens
