// SPDX-License-Identifier: GPL-3.0-or-later
// The structured cutaway of the SirTom thesis: where a cut opens a dense membrane, molecules are
// removed in an order that leaves a wireframe of the structure's triangle mesh (molecules near
// triangle centres first, those on edges last), instead of at random as cellVIEW's Visibility
// Equalizer does.
#pragma once

#include "mesolens/common/parallel_for.h"
#include "mesolens/common/point_span.h"
#include "mesolens/mesh/triangle_mesh.h"

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <vector>

namespace mesolens {

/// Dino Dini's normalized tunable sigmoid on [-1, 1]: (n - k n) / (k - 2 k |n| + 1). It maps
/// -1, 0, 1 to themselves for every k; k = 0 is the identity, k towards -1 pushes values to
/// +-1 (a step), k towards 1 pulls them to 0. Throws InvalidInput unless -1 < k < 1.
double tunable_sigmoid(double n, double k);

/// Where a cut applies: the union of half-spaces (the side a plane's normal points to), balls
/// and axis-aligned boxes, in the molecules' units. Empty: nowhere.
struct CutRegion
{
  struct Plane
  {
    std::array<double, 3> point{};
    std::array<double, 3> normal{ { 0, 0, 1 } };
  };
  struct Ball
  {
    std::array<double, 3> centre{};
    double radius = 0;
  };
  struct Box
  {
    std::array<double, 3> low{};
    std::array<double, 3> high{};
  };
  std::vector<Plane> planes;
  std::vector<Ball> balls;
  std::vector<Box> boxes;

  bool contains(const std::array<double, 3>& point) const;
};

/// How much a cut removes, and in which order.
struct CutawayParams
{
  /// The sigmoid's k (tunable_sigmoid), -1 < k < 1; default 0 (the minimal barycentric
  /// coordinate as it is).
  double k = 0;
  /// Fraction of the molecules inside the cut that are hidden, [0, 1]; default 0.5.
  double fraction_hidden = 0.5;
  /// Per molecule type, a fraction instead of fraction_hidden, [0, 1]. Default: none.
  std::map<int, double> fraction_by_type;
  /// Hide molecules on the mesh's edges first (patches instead of a wireframe). Default false.
  bool inverted = false;
  /// The Visibility Equalizer's order: by a random key alone (for comparison). Default false.
  bool random = false;
  /// The priorities as probabilities instead of a strict order: a weighted random order
  /// (Efraimidis-Spirakis: key u^(1 / p) from the seeded uniform u), so a molecule of priority
  /// p goes before one of priority q with odds p : q. k then matters: towards -1 the priorities
  /// are nearly 0 or 1 (two classes, random within each), at 0 they are 3x, towards 1 all near
  /// 1/2 (nearly random). In the strict order (false, default) k changes the priorities' values
  /// but not their order, so every k gives the same mask.
  bool probabilistic = false;
  /// Seed of the per-molecule random keys that break ties (and order the random mode): the same
  /// seed gives the same order, frame after frame. Any value; default 1.
  std::uint64_t seed = 1;
};

/// The molecules inside a cut, per molecule type, in the order they are hidden.
struct RemovalOrder
{
  std::map<int, std::vector<std::uint32_t>> by_type;
  std::size_t molecule_count = 0; ///< all molecules, inside the cut or not
  /// How many molecules are inside the cut.
  std::size_t in_cut() const;
};

/// The structured cutaway for one set of molecules on one structure mesh. The costly part, each
/// molecule's nearest triangle (exact closest point, an AABB tree), is done once here; changing
/// the settings or the cut then only reorders.
class StructuredCutaway
{
public:
  /// `structure`: the structure's triangle mesh; `centres`: one per molecule (the molecules'
  /// centres, the mesh's units); `types`: one type per molecule, or empty (all type 0).
  /// Throws InvalidInput for an empty or non-finite set of centres, a types list of another
  /// length, or a mesh without triangles. `parallel_for` runs the closest-point searches.
  StructuredCutaway(const TriangleMesh& structure, PointSpan<const double> centres,
                    std::vector<int> types = {}, const ParallelFor& parallel_for = {});

  std::size_t molecule_count() const
  {
    return this->MinimalBarycentric.size();
  }

  /// Per molecule, the smallest barycentric coordinate of its projection on its nearest
  /// triangle: 0 on an edge, 1/3 at the triangle's centre.
  const std::vector<double>& minimal_barycentric() const
  {
    return this->MinimalBarycentric;
  }

  /// Per molecule, the triangle it was assigned to.
  const std::vector<std::int64_t>& triangles() const
  {
    return this->Triangles;
  }

  /// Per molecule, the removal priority in [0, 1]: (f(6 x - 1, k) + 1) / 2 with f the tunable
  /// sigmoid and x the minimal barycentric coordinate (1 at triangle centres, 0 on edges).
  std::vector<double> priorities(double k) const;

  /// Per molecule, 1 visible or 0 hidden: of the molecules whose centre (`centres`, one per
  /// molecule, e.g. a later trajectory frame; empty: the centres given at construction) lies
  /// in `cut`, the round(fraction x count) of highest priority (lowest when inverted; in
  /// random order in random mode) are hidden, per type; molecules outside the cut stay. Throws
  /// InvalidInput for settings out of range or centres of another count.
  std::vector<std::uint8_t> visibility(const CutRegion& cut, const CutawayParams& settings,
                                       PointSpan<const double> centres = {}) const;

  /// The same with the cut given as a test of a point (true: inside the cut).
  std::vector<std::uint8_t> visibility(
    const std::function<bool(const std::array<double, 3>&)>& inside_cut,
    const CutawayParams& settings, PointSpan<const double> centres = {}) const;

  /// The first, costlier half of visibility(): which molecules are in the cut and in which
  /// order they go (all settings but the fractions count). Keep it while only the fractions
  /// change (a slider): visibility(order, settings) is then O(molecules).
  RemovalOrder removal_order(const std::function<bool(const std::array<double, 3>&)>& inside_cut,
                             const CutawayParams& settings,
                             PointSpan<const double> centres = {}) const;

  /// The mask for `order` with the fractions of `settings` (the rest of the settings are those
  /// the order was made with). Throws InvalidInput for fractions out of [0, 1] or an order
  /// made for another number of molecules.
  std::vector<std::uint8_t> visibility(const RemovalOrder& order,
                                       const CutawayParams& settings) const;

private:
  std::vector<double> Centres;
  std::vector<int> Types;
  std::vector<double> MinimalBarycentric;
  std::vector<std::int64_t> Triangles;
};

} // namespace mesolens
