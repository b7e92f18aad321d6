// SPDX-License-Identifier: GPL-3.0-or-later
// Which atoms lie within a distance of a set of atoms (private to MesoLensCore; the `within`
// and `around` of atom selections).
#pragma once

#include "mesolens/common/parallel_for.h"
#include "mesolens/common/point_span.h"

#include <cstdint>
#include <vector>

namespace mesolens {
namespace detail {

/// 1 for every atom at most `distance` Å (>= 0, finite) from an atom whose `reference` entry is
/// nonzero, the reference atoms included; 0 for the others and for atoms with a non-finite
/// coordinate. The reference atoms are binned in a dense grid over their bounding box, so the
/// cost is about one grid lookup per atom plus the distance tests near the reference.
std::vector<std::uint8_t> atoms_within(PointSpan<const float> positions,
                                       const std::vector<std::uint8_t>& reference, double distance,
                                       const ParallelFor& parallel_for);

} // namespace detail
} // namespace mesolens
