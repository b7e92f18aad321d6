// SPDX-License-Identifier: GPL-3.0-or-later
// Even samples of the middle of a thick point cloud (a bilayer's two leaflets of lipid centres),
// the input a surface reconstruction needs: one sheet of points, evenly spread, no noise.
#pragma once

#include "mesolens/common/parallel_for.h"
#include "mesolens/common/point_span.h"

#include <cstddef>
#include <vector>

namespace mesolens {

/// The median distance from a point to its nearest other point, over up to `probes` points
/// spread through the cloud (at least 2 distinct points). Deterministic.
/// Throws InvalidInput for fewer than 2 points or when all points coincide.
double median_spacing(PointSpan<const double> points, std::size_t probes = 1000);

/// A Poisson-disk subset of `points`: walking the points in order, a point is kept when no
/// kept point lies closer than `spacing` (> 0). Deterministic; O(n). A surface sampled this
/// way has 0.7 (random order) to 0.9 (an order that sweeps the surface) / spacing^2 points per
/// unit of area.
std::vector<double> poisson_disk_subset(PointSpan<const double> points, double spacing);

/// Points on the middle sheet of a cloud of thickness below `radius` (e.g. both leaflets of a
/// membrane): a Poisson-disk subset at `spacing`, each point moved `iterations` times to the
/// mean of the cloud's points within `radius` of it (mean shift, which settles where the cloud
/// is balanced on both sides), then thinned again at spacing / 2 where the sheets met. Samples
/// with fewer than a tenth of the median count of points within `radius` (strays far from the
/// sheet) are dropped. On a
/// sheet curved with radius r the points end up about radius^2 / (4 r) inside the middle.
/// `spacing` and `radius` in the points' units, > 0. Deterministic whatever `parallel_for`.
std::vector<double> mid_surface_points(PointSpan<const double> points, double spacing,
                                       double radius, int iterations = 4,
                                       const ParallelFor& parallel_for = {});

} // namespace mesolens
