// SPDX-License-Identifier: GPL-3.0-or-later
// Local mesh operations that bound every triangle's angles (private to MesoLensCore): the last
// pass of the structure mesh, whose triangles the cutaway's barycentric removal order needs to
// be near-equilateral.
#pragma once

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

namespace mesolens {

using RepairKernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using RepairMesh = CGAL::Surface_mesh<RepairKernel::Point_3>;
/// Closest points on a RepairMesh's triangles (the surface a repair or remeshing keeps to).
using RepairSurfaceTree = CGAL::AABB_tree<
  CGAL::AABB_traits<RepairKernel, CGAL::AABB_face_graph_triangle_primitive<RepairMesh>>>;

/// The smallest and largest corner angle (degrees) over a mesh's triangles.
struct AngleRange
{
  double smallest = 180;
  double largest = 0;
};

/// The angle range of `mesh`'s triangles (smallest 180, largest 0 without triangles).
AngleRange angle_range(const RepairMesh& mesh);

/// Raises the smallest angle of every triangle of `mesh` (a triangulated 2-manifold, boundary
/// allowed) to at least `goal` degrees (in (0, 40]; every largest angle then is at most
/// 180 - 2 goal), in up to `rounds` rounds of: edge flips that raise the two triangles' smallest
/// angle (not across creases of more than 40°); moves of the vertices of bad triangles and
/// their neighbours (towards their neighbours' centroid, then a pattern search in the tangent
/// plane), projected back onto the mesh as it was; and collapses of the shortest edge of
/// triangles that stay bad. No operation is kept unless it raises the smallest angle around it
/// and tilts no triangle by more than 60°. When none helps, bad triangles on the boundary of an
/// open mesh are removed (not where that would pinch it; at most 5 % of the triangles). The
/// shape and topology stay (the boundary may lose a few triangles). Stops early when five
/// rounds in a row leave no fewer bad triangles than the fewest so far. Returns the angle range
/// reached, which may still miss the goal: the caller checks.
AngleRange repair_angles(RepairMesh& mesh, double goal, int rounds = 30);

} // namespace mesolens
