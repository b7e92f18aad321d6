// SPDX-License-Identifier: GPL-3.0-or-later
// Radius and nearest-neighbour queries over a fixed point cloud (private to MesoLensCore): a
// CGAL kd-tree, built once, queried from several threads at a time.
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <vector>

namespace mesolens {

/// The points of a cloud (3 coordinates each, any unit), indexed for queries. The cloud must
/// outlive the index and stay unchanged. Queries are const and thread-safe.
class PointSearch
{
public:
  explicit PointSearch(const std::vector<double>& points);
  ~PointSearch();
  PointSearch(const PointSearch&) = delete;
  PointSearch& operator=(const PointSearch&) = delete;

  /// Fills `found` (cleared first) with the indices of the points within `radius` (>= 0) of
  /// `centre`, in an order fixed by the cloud (the tree is built the same way each time), so
  /// that sums over them are the same whatever the thread that asks.
  void within(const std::array<double, 3>& centre, double radius,
              std::vector<std::size_t>& found) const;

  /// Fills `found` with the indices of the `count` points nearest to `centre` (fewer when the
  /// cloud has fewer), nearest first.
  void nearest(const std::array<double, 3>& centre, std::size_t count,
               std::vector<std::size_t>& found) const;

private:
  struct Tree;
  std::unique_ptr<Tree> Index;
};

} // namespace mesolens
