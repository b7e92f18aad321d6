// SPDX-License-Identifier: GPL-3.0-or-later
// The triangles a chord refinement leaves at creases and the test that keeps the triangles cut
// beside them from passing through them (a private part of MesoLensCore).
#include "surface/detail/frozen_creases.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

namespace {
using Vec = Eigen::Vector3d;
using mesolens::ContourMesh;
using mesolens::ContourVertex;

/// The unit triangle in the plane z = 0.
const Vec a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);

/// A mesh of the given points and triangles.
ContourMesh mesh_of(const std::vector<Vec>& points, const std::vector<std::int64_t>& triangles)
{
  ContourMesh mesh;
  for (const Vec& point : points)
  {
    ContourVertex vertex;
    vertex.position = point;
    mesh.vertices.push_back(vertex);
  }
  mesh.triangles = triangles;
  return mesh;
}
} // namespace

TEST(FrozenCreases, SegmentsMeetTrianglesTheyPassThroughOrTouch)
{
  using mesolens::segment_meets_triangle;
  // Through the inside, either way.
  EXPECT_TRUE(segment_meets_triangle(Vec(0.2, 0.2, -1), Vec(0.2, 0.2, 1), a, b, c));
  EXPECT_TRUE(segment_meets_triangle(Vec(0.2, 0.2, 1), Vec(0.3, 0.1, -1), a, b, c));
  // Past an edge, short of the plane, or ending on the far side.
  EXPECT_FALSE(segment_meets_triangle(Vec(0.8, 0.8, -1), Vec(0.8, 0.8, 1), a, b, c));
  EXPECT_FALSE(segment_meets_triangle(Vec(0.2, 0.2, 0.5), Vec(0.2, 0.2, 1), a, b, c));
  EXPECT_FALSE(segment_meets_triangle(Vec(0.2, 0.2, -1), Vec(0.2, 0.2, -0.1), a, b, c));
  // Touching: an edge crossed, or an end on the triangle, counts (the test is conservative).
  EXPECT_TRUE(segment_meets_triangle(Vec(0.5, 0.5, -1), Vec(0.5, 0.5, 1), a, b, c));
  EXPECT_TRUE(segment_meets_triangle(Vec(0.2, 0.2, 0), Vec(0.2, 0.2, 1), a, b, c));
  // In the plane: never.
  EXPECT_FALSE(segment_meets_triangle(Vec(-1, 0.2, 0), Vec(2, 0.2, 0), a, b, c));
}

TEST(FrozenCreases, TrianglesMeetWhereTheyCrossNotWhereTheyShareCorners)
{
  using mesolens::triangles_meet;
  // 0-2: the unit triangle; 3-5: one standing through it; 6-8: one beside it; 9-10 with corner 0
  // and 11 with 1 and 2 below.
  const ContourMesh mesh =
    mesh_of({ a, b, c, Vec(0.2, 0.2, -1), Vec(0.3, 0.2, 1), Vec(0.2, 0.3, 1), Vec(2, 2, -1),
              Vec(3, 2, 1), Vec(2, 3, 1), Vec(0.6, 0.6, -1), Vec(0.6, 0.6, 1), Vec(0.5, 0.5, -1) },
            {});
  EXPECT_TRUE(triangles_meet({ 0, 1, 2 }, { 3, 4, 5 }, mesh.vertices));
  EXPECT_TRUE(triangles_meet({ 3, 4, 5 }, { 0, 1, 2 }, mesh.vertices));
  EXPECT_FALSE(triangles_meet({ 0, 1, 2 }, { 6, 7, 8 }, mesh.vertices));
  // Sharing corner 0 and standing on the line x = y: they cross along it from that corner.
  EXPECT_TRUE(triangles_meet({ 0, 1, 2 }, { 0, 9, 10 }, mesh.vertices));
  // Sharing corner 0 and leaning away from it (below the plane throughout).
  EXPECT_FALSE(triangles_meet({ 0, 1, 2 }, { 0, 11, 9 }, mesh.vertices));
  // Sharing an edge: they meet along it alone.
  EXPECT_FALSE(triangles_meet({ 0, 1, 2 }, { 1, 2, 11 }, mesh.vertices));
  EXPECT_FALSE(triangles_meet({ 0, 1, 2 }, { 2, 1, 0 }, mesh.vertices));
}

TEST(FrozenCreases, FrozenTrianglesAreFoundByTheirEdgesAndInSpace)
{
  // Two triangles sharing edge 1-2; the first is frozen.
  const ContourMesh mesh = mesh_of({ a, b, c, Vec(1, 1, 0.2), Vec(0.2, 0.2, -1), Vec(0.3, 0.2, 1),
                                     Vec(0.2, 0.3, 1), Vec(5, 5, 5), Vec(6, 5, 5), Vec(5, 6, 5),
                                     Vec(0.7, 0.1, -1), Vec(0.8, 0.1, 1), Vec(0.7, 0.15, 1) },
                                   { 0, 1, 2, 1, 3, 2 });
  const mesolens::FrozenCreases frozen(mesh, { 1, 0 }, 0.5);
  EXPECT_FALSE(frozen.empty());
  // The first triangle's three edges, either way round; not the second's own.
  EXPECT_TRUE(frozen.frozen_edge(0, 1));
  EXPECT_TRUE(frozen.frozen_edge(2, 1));
  EXPECT_TRUE(frozen.frozen_edge(0, 2));
  EXPECT_FALSE(frozen.frozen_edge(1, 3));
  EXPECT_FALSE(frozen.frozen_edge(3, 2));
  EXPECT_FALSE(frozen.frozen_edge(13, 0)); // a vertex made after
  // A piece standing through the frozen triangle, among others, meets it; pieces far away or
  // sharing its edge do not.
  EXPECT_TRUE(frozen.meets({ 7, 8, 9, 4, 5, 6 }, mesh.vertices));
  // The frozen triangle spans several cells of 0.5 Å; a piece standing through it in another
  // cell than its first meets it too.
  EXPECT_TRUE(frozen.meets({ 10, 11, 12 }, mesh.vertices));
  EXPECT_FALSE(frozen.meets({ 7, 8, 9 }, mesh.vertices));
  EXPECT_FALSE(frozen.meets({ 1, 3, 2 }, mesh.vertices));
  EXPECT_FALSE(frozen.meets({}, mesh.vertices));
  const mesolens::FrozenCreases none(mesh, { 0, 0 }, 0.5);
  EXPECT_TRUE(none.empty());
  EXPECT_FALSE(none.meets({ 4, 5, 6 }, mesh.vertices));
}
