// SPDX-License-Identifier: GPL-3.0-or-later
// One key per undirected mesh edge, for hashing and sorting edges (private).
#pragma once

#include <algorithm>
#include <cstdint>

namespace mesolens {
namespace detail {

/// The same key for (a, b) and (b, a); vertex indices in [0, 2^32).
inline std::uint64_t edge_key(std::int64_t a, std::int64_t b)
{
  return (std::uint64_t(std::min(a, b)) << 32) | std::uint64_t(std::max(a, b));
}

} // namespace detail
} // namespace mesolens
