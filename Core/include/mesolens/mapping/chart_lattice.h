// SPDX-License-Identifier: GPL-3.0-or-later
// A regular triangle lattice laid on a chart's surface: the structure a cutaway cuts a mapped
// membrane along (the disk's own triangles are about one lipid wide, too fine to show as a
// wireframe).
#pragma once

#include "mesolens/mapping/surface_chart.h"
#include "mesolens/mesh/triangle_mesh.h"

namespace mesolens {

/// Equilateral triangles of edge `edge` (the chart's (u, v) units, which are the mesh's: the
/// parameterization is nearly isometric), laid out in (u, v) with a vertex at the centre of the
/// disk's (u, v) box and carried onto the disk's flat triangles. Keeps the triangles whose three
/// corners lie on the disk, their vertices numbered in lattice order (rows from -v to +v).
/// Throws InvalidInput unless `edge` is positive and finite and no more than 4 million lattice
/// points cover the disk (edge too small for it).
TriangleMesh chart_lattice(const SurfaceChart& chart, const std::vector<double>& uv, double edge);

} // namespace mesolens
