// SPDX-License-Identifier: GPL-3.0-or-later
// Union-find over 0 .. n - 1 (private to MesoLensCore; any subsystem may use it).
#pragma once

#include <cstddef>
#include <numeric>
#include <vector>

namespace mesolens {
namespace detail {

/// Disjoint sets of 0 .. n - 1, each named by its root; path halving keeps finds short.
class DisjointSets
{
public:
  explicit DisjointSets(std::size_t n)
    : Parent(n)
  {
    std::iota(this->Parent.begin(), this->Parent.end(), std::size_t(0));
  }

  std::size_t root(std::size_t x)
  {
    while (this->Parent[x] != x)
    {
      x = this->Parent[x] = this->Parent[this->Parent[x]];
    }
    return x;
  }

  /// Merges the sets of a and b under b's root.
  void join(std::size_t a, std::size_t b)
  {
    this->Parent[this->root(a)] = this->root(b);
  }

private:
  std::vector<std::size_t> Parent;
};

} // namespace detail
} // namespace mesolens
