// SPDX-License-Identifier: GPL-3.0-or-later
// A structure's triangle mesh made from the centres of its molecules (the cutaway's wireframe):
// surface reconstruction through the points, then isotropic remeshing to a chosen size.
#pragma once

#include "mesolens/parallel_for.h"
#include "mesolens/triangle_mesh.h"

#include <cstddef>
#include <vector>

namespace mesolens {

/// How even a mesh's triangles are.
struct MeshQuality
{
  double min_angle = 0;   ///< degrees, over all triangles
  double max_angle = 0;   ///< degrees
  double mean_edge = 0;   ///< mesh units
  double edge_spread = 0; ///< standard deviation of the edge lengths over their mean
  std::size_t boundary_edges = 0;
};

/// The quality of a triangle mesh.
MeshQuality mesh_quality(const TriangleMesh& mesh);

/// Sizes for structure_mesh: the target edge length in mesh units, or (when it is <= 0) the
/// vertex count N the remeshed surface should have (about; N >= 4); and the radius over which
/// the points are averaged onto their middle sheet, larger than half the structure's thickness
/// (a bilayer's lipid centres: about 30 Å); <= 0: 4 times the points' median spacing.
struct StructureMeshSize
{
  std::size_t vertices = 500;
  double edge_length = 0;
  double mid_surface_radius = 0;
};

/// A surface through the middle of `points` (3 coordinates each, e.g. the centres of a
/// vesicle's lipids, both leaflets): the points are thinned to a Poisson-disk set and moved to
/// their middle sheet (mid_surface_points), thinned again to half the target edge length, made
/// into a surface by CGAL's advancing-front reconstruction, its small holes closed, then
/// remeshed isotropically (CGAL) so that its triangles are near-equilateral and of the
/// requested size.
/// Holes whose border has fewer than max(20, 5 % of the vertices) edges are closed; a larger
/// border (an open membrane patch) stays. Throws InvalidInput for fewer than 4 points,
/// non-finite points, N < 4 or a negative length; TopologyError when the points describe no
/// surface (all on a line, for instance).
TriangleMesh structure_mesh(const std::vector<double>& points, const StructureMeshSize& size,
                            MeshQuality* quality = nullptr, const ParallelFor& parallel_for = {});

} // namespace mesolens
