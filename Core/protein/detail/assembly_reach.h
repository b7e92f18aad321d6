// SPDX-License-Identifier: GPL-3.0-or-later
// How far an assembly's operators move atoms: the guard that keeps copies in float range
// (private to protein).
#pragma once

#include "mesolens/protein/assembly.h"

#include <cstdint>
#include <string>
#include <vector>

namespace mesolens {
namespace detail {

/// Throws InvalidInput, naming the assembly and the operator, when an operator of `generator`
/// may move one of `rows` of `table` to a coordinate that is not finite or beyond float's range
/// (|x| > 3.4e38 Å; a bound from the rows' largest coordinate, so it never misses one).
void check_float_reach(const AtomTable& table, const std::vector<std::uint32_t>& rows,
                       const AssemblyGenerator& generator, const std::string& assembly_name);

} // namespace detail
} // namespace mesolens
