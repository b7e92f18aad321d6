// SPDX-License-Identifier: GPL-3.0-or-later
#include "protein/detail/assembly_reach.h"

#include "mesolens/common/errors.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mesolens {
namespace detail {

void check_float_reach(const AtomTable& table, const std::vector<std::uint32_t>& rows,
                       const AssemblyGenerator& generator, const std::string& assembly_name)
{
  double largest = 0; // the rows' largest |coordinate|, Å
  for (const std::uint32_t i : rows)
  {
    for (std::size_t d = 0; d < 3; ++d)
    {
      largest = std::max(largest, double(std::abs(table.positions[3 * i + d])));
    }
  }
  if (rows.empty())
  {
    return;
  }
  const double limit = std::numeric_limits<float>::max();
  for (const AssemblyOperator& op : generator.operators)
  {
    for (std::size_t r = 0; r < 3; ++r)
    {
      const double* row = op.matrix.data() + 4 * r;
      const double reach =
        (std::abs(row[0]) + std::abs(row[1]) + std::abs(row[2])) * largest + std::abs(row[3]);
      if (!(reach <= limit))
      {
        throw InvalidInput("assembly '" + assembly_name + "': operator " + op.name +
                           " may move atoms to coordinates beyond float's range (3.4e38 Å)");
      }
    }
  }
}

} // namespace detail
} // namespace mesolens
