// SPDX-License-Identifier: GPL-3.0-or-later
// Refining a mesh on a known surface to a chord error (a private part of MesoLensCore, the
// molecular surfaces' fine level): an icosahedron refined onto its sphere.
#include "surface/detail/chord_refinement.h"
#include "surface/detail/frozen_creases.h"

#include "mesolens_test_threads.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

namespace {
using Vec = Eigen::Vector3d;
using mesolens::ContourMesh;
using mesolens::ContourVertex;
constexpr double pi = 3.14159265358979323846;
constexpr double radius = 2.0;

/// The ellipsoid with semi-axes `axes` about the origin (the sphere of `radius` by default),
/// points projected radially; `refuse` makes every projection fail.
class EllipsoidProjection final : public mesolens::LocalSurfaceProjection
{
public:
  EllipsoidProjection(const Vec& axes, bool refuse)
    : axes_(axes)
    , refuse_(refuse)
  {
  }
  void focus(const Vec&, double) override {}
  bool project(const Vec& x, ContourVertex& vertex) override
  {
    if (this->refuse_ || x.norm() == 0)
    {
      return false;
    }
    vertex.position = this->onto(x);
    vertex.normal =
      vertex.position.cwiseQuotient(this->axes_.cwiseProduct(this->axes_)).normalized();
    return true;
  }
  double piece_gap(const ContourVertex&, const ContourVertex&, const Vec& x) const override
  {
    return (this->onto(x) - x).norm();
  }
  Vec onto(const Vec& x) const
  {
    return x / x.cwiseQuotient(this->axes_).norm();
  }

private:
  Vec axes_;
  bool refuse_;
};

/// The sphere of `radius` as if every vertex lay on a piece of its own: edges are settled by
/// their bend and by end_pieces_gap(), which claims `claimed_gap` (NaN: unknown).
class SeparatePiecesSphere final : public mesolens::LocalSurfaceProjection
{
public:
  explicit SeparatePiecesSphere(double claimed_gap)
    : claimed_gap_(claimed_gap)
  {
  }
  void focus(const Vec&, double) override {}
  bool project(const Vec& x, ContourVertex& vertex) override
  {
    return EllipsoidProjection(Vec::Constant(radius), false).project(x, vertex);
  }
  double piece_gap(const ContourVertex&, const ContourVertex&, const Vec&) const override
  {
    return std::numeric_limits<double>::quiet_NaN();
  }
  double end_pieces_gap(const ContourVertex&, const ContourVertex&, const Vec&) const override
  {
    return this->claimed_gap_;
  }

private:
  double claimed_gap_;
};

/// The icosahedron inscribed in the sphere, counter-clockwise seen from outside.
ContourMesh icosahedron()
{
  ContourMesh mesh;
  const double phi = (1 + std::sqrt(5.0)) / 2;
  for (const double a : { -1.0, 1.0 })
  {
    for (const double b : { -phi, phi })
    {
      for (const Vec& corner : { Vec(0, a, b), Vec(a, b, 0), Vec(b, 0, a) })
      {
        ContourVertex vertex;
        vertex.normal = corner.normalized();
        vertex.position = radius * vertex.normal;
        mesh.vertices.push_back(vertex);
      }
    }
  }
  // Faces: the triples of mutual neighbours (the shortest distance apart).
  const auto near = [&](std::size_t i, std::size_t j) {
    return std::abs((mesh.vertices[i].position - mesh.vertices[j].position).norm() -
                    radius * 2 / std::sqrt(phi * phi + 1)) < 1e-9;
  };
  for (std::size_t i = 0; i < 12; ++i)
    for (std::size_t j = i + 1; j < 12; ++j)
      for (std::size_t k = j + 1; k < 12; ++k)
      {
        if (near(i, j) && near(j, k) && near(i, k))
        {
          const Vec& a = mesh.vertices[i].position;
          const bool outwards =
            (mesh.vertices[j].position - a).cross(mesh.vertices[k].position - a).dot(a) > 0;
          mesh.triangles.insert(
            mesh.triangles.end(),
            { std::int64_t(i), std::int64_t(outwards ? j : k), std::int64_t(outwards ? k : j) });
        }
      }
  return mesh;
}

ContourMesh refined(double tolerance, int rounds, int thread_count, bool refuse = false,
                    const Vec& axes = Vec::Constant(radius))
{
  ContourMesh mesh = icosahedron();
  if (axes != Vec::Constant(radius))
  {
    // Twice as fine, moved onto the ellipsoid: neighbours' normals stay well under the 70
    // degrees that mark a crease.
    mesolens::refine_chords(
      mesh, [] { return std::make_unique<EllipsoidProjection>(Vec::Constant(radius), false); },
      1e-3, 1.0, 1, mesolens::ParallelFor());
    for (ContourVertex& vertex : mesh.vertices)
    {
      EllipsoidProjection(axes, false).project(vertex.position, vertex);
    }
  }
  mesolens::refine_chords(
    mesh, [refuse, axes] { return std::make_unique<EllipsoidProjection>(axes, refuse); }, tolerance,
    1.0, rounds, thread_count == 1 ? mesolens::ParallelFor() : mesolens_test::two_threads());
  return mesh;
}

/// Each directed edge once and its reverse once (closed, 2-manifold, oriented); V - E + F.
int euler_characteristic(const ContourMesh& mesh)
{
  std::map<std::pair<std::int64_t, std::int64_t>, int> directed;
  for (std::size_t t = 0; t < mesh.triangles.size(); t += 3)
  {
    for (std::size_t k = 0; k < 3; ++k)
    {
      ++directed[{ mesh.triangles[t + k], mesh.triangles[t + (k + 1) % 3] }];
    }
  }
  for (const auto& [edge, count] : directed)
  {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(directed.count({ edge.second, edge.first }), 1u);
  }
  return int(mesh.vertices.size()) - int(directed.size() / 2) + int(mesh.triangles.size() / 3);
}

double largest_chord_error(const ContourMesh& mesh)
{
  double worst = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); t += 3)
  {
    for (std::size_t k = 0; k < 3; ++k)
    {
      const Vec middle = 0.5 *
        (mesh.vertices[std::size_t(mesh.triangles[t + k])].position +
         mesh.vertices[std::size_t(mesh.triangles[t + (k + 1) % 3])].position);
      worst = std::max(worst, radius - middle.norm());
    }
  }
  return worst;
}
} // namespace

TEST(ChordRefinement, SplitsUntilEveryEdgeFollowsTheSphere)
{
  const double tolerance = 0.01;
  const ContourMesh mesh = refined(tolerance, 10, 2);
  EXPECT_EQ(euler_characteristic(mesh), 2);
  EXPECT_LE(largest_chord_error(mesh), tolerance);
  double area = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); t += 3)
  {
    const Vec& a = mesh.vertices[std::size_t(mesh.triangles[t])].position;
    const Vec& b = mesh.vertices[std::size_t(mesh.triangles[t + 1])].position;
    const Vec& c = mesh.vertices[std::size_t(mesh.triangles[t + 2])].position;
    const Vec normal = (b - a).cross(c - a);
    EXPECT_GT(normal.dot(a + b + c), 0) << "triangle " << t / 3 << " turned inwards";
    area += 0.5 * normal.norm();
  }
  for (const ContourVertex& vertex : mesh.vertices)
  {
    ASSERT_NEAR(vertex.position.norm(), radius, 1e-12);
  }
  // Inscribed: a little less than the sphere, by about a third of the chord error over the
  // radius.
  const double sphere = 4 * pi * radius * radius;
  EXPECT_LT(area, sphere);
  EXPECT_GT(area, sphere * (1 - tolerance / radius));
}

TEST(ChordRefinement, UnevenSplitsKeepTheMeshClosedAndFacingOut)
{
  // A flattened ellipsoid: edges near its rim need more splits than those near its poles, so
  // triangles are cut along one, two or three edges.
  const Vec axes(2.0, 1.8, 1.5);
  const double tolerance = 0.01;
  const ContourMesh mesh = refined(tolerance, 10, 2, false, axes);
  EXPECT_EQ(euler_characteristic(mesh), 2);
  const EllipsoidProjection ellipsoid(axes, false);
  // A split that would turn a piece of a sliver away from the surface is not made, so a few
  // edges may stay above the tolerance, but far below the coarse mesh's error.
  std::size_t edges = 0, above = 0;
  double worst = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); t += 3)
  {
    const Vec& a = mesh.vertices[std::size_t(mesh.triangles[t])].position;
    const Vec& b = mesh.vertices[std::size_t(mesh.triangles[t + 1])].position;
    const Vec& c = mesh.vertices[std::size_t(mesh.triangles[t + 2])].position;
    const Vec outwards = ((a + b + c) / 3).cwiseQuotient(axes.cwiseProduct(axes));
    ASSERT_GT((b - a).cross(c - a).dot(outwards), 0) << "triangle " << t / 3 << " turned inwards";
    for (const auto& [from, to] :
         { std::make_pair(a, b), std::make_pair(b, c), std::make_pair(c, a) })
    {
      const double error = (ellipsoid.onto(0.5 * (from + to)) - 0.5 * (from + to)).norm();
      ++edges;
      above += error > tolerance ? 1 : 0;
      worst = std::max(worst, error);
    }
  }
  EXPECT_LT(above, edges / 200);
  EXPECT_LT(worst, 3 * tolerance);
  for (const ContourVertex& vertex : mesh.vertices)
  {
    ASSERT_NEAR(vertex.position.cwiseQuotient(axes).norm(), 1.0, 1e-12);
  }
}

TEST(ChordRefinement, RoundsAreCountedAndResultsIndependentOfThreads)
{
  ASSERT_EQ(icosahedron().triangles.size(), 3u * 20u);
  // The icosahedron's 30 edges each split once in one round: 12 + 30 vertices, 80 triangles.
  const ContourMesh once = refined(0.01, 1, 1);
  EXPECT_EQ(once.vertices.size(), 42u);
  EXPECT_EQ(once.triangles.size(), 3u * 80u);
  EXPECT_EQ(euler_characteristic(once), 2);
  const ContourMesh one = refined(0.003, 10, 1), two = refined(0.003, 10, 2);
  ASSERT_EQ(one.triangles, two.triangles);
  ASSERT_EQ(one.vertices.size(), two.vertices.size());
  for (std::size_t v = 0; v < one.vertices.size(); ++v)
  {
    ASSERT_EQ(one.vertices[v].position, two.vertices[v].position);
  }
}

TEST(ChordRefinement, EdgesWithinTheToleranceOrWithoutAProjectionStay)
{
  const ContourMesh coarse = icosahedron();
  // The icosahedron's edges stray this far from the sphere at their middles.
  const double sagitta = radius -
    0.5 *
      (coarse.vertices[std::size_t(coarse.triangles[0])].position +
       coarse.vertices[std::size_t(coarse.triangles[1])].position)
        .norm();
  EXPECT_GT(sagitta, 0.2);
  const ContourMesh loose = refined(sagitta + 1e-9, 10, 2);
  EXPECT_EQ(loose.triangles, coarse.triangles);
  const ContourMesh tight = refined(sagitta - 1e-9, 1, 2);
  EXPECT_EQ(tight.triangles.size(), 3u * 80u);
  const ContourMesh refused = refined(0.01, 10, 2, true);
  EXPECT_EQ(refused.triangles, coarse.triangles);
  EXPECT_EQ(refused.vertices.size(), coarse.vertices.size());
}

TEST(ChordRefinement, EdgesBendingLittleStayWhenTheirEndsPiecesAreNear)
{
  // The icosahedron's edges (2.103 Å on the sphere of 2 Å) bend by 1.107 rad, an estimated
  // sagitta of 0.2910 Å; their true one is 0.2987 Å. At 0.295 Å the bend alone does not settle
  // them (it settles estimated sagittas below half the tolerance), so end_pieces_gap() does:
  // within the tolerance they stay unprojected, even where the projection would have split
  // them; beyond it, or unknown, they are projected and split.
  const double tolerance = 0.295;
  const auto refine_with = [&](double claimed_gap) {
    ContourMesh mesh = icosahedron();
    mesolens::refine_chords(
      mesh, [claimed_gap] { return std::make_unique<SeparatePiecesSphere>(claimed_gap); },
      tolerance, 1.0, 1, mesolens::ParallelFor());
    return mesh;
  };
  EXPECT_EQ(refine_with(0.0).triangles, icosahedron().triangles);
  EXPECT_EQ(refine_with(tolerance).triangles, icosahedron().triangles);
  EXPECT_EQ(refine_with(1.001 * tolerance).triangles.size(), 3u * 80u);
  EXPECT_EQ(refine_with(std::numeric_limits<double>::quiet_NaN()).triangles.size(), 3u * 80u);
  // Edges bending by more than twice the limit are projected whatever the claim.
  ContourMesh sharp = icosahedron();
  mesolens::refine_chords(
    sharp, [] { return std::make_unique<SeparatePiecesSphere>(0.0); }, 0.14, 1.0, 1,
    mesolens::ParallelFor());
  EXPECT_EQ(sharp.triangles.size(), 3u * 80u);
}

TEST(ChordRefinement, TrianglesAtACreaseStayAndTheOnesBesideThemAreRefined)
{
  // Corner 0's normal turned inwards: its five triangles lie across the surface as it says,
  // like those spanning a crease. They stay whole; the triangles around them are refined
  // (all but the edges they share with them), and no piece passes through them.
  ContourMesh coarse = icosahedron();
  coarse.vertices[0].normal = -coarse.vertices[0].normal;
  std::vector<std::array<std::int64_t, 3>> at_corner;
  for (std::size_t t = 0; t < coarse.triangles.size(); t += 3)
  {
    if (coarse.triangles[t] == 0 || coarse.triangles[t + 1] == 0 || coarse.triangles[t + 2] == 0)
    {
      at_corner.push_back(
        { coarse.triangles[t], coarse.triangles[t + 1], coarse.triangles[t + 2] });
    }
  }
  ASSERT_EQ(at_corner.size(), 5u);
  ContourMesh mesh = coarse;
  mesolens::refine_chords(
    mesh, [] { return std::make_unique<EllipsoidProjection>(Vec::Constant(radius), false); }, 0.01,
    1.0, 10, mesolens_test::two_threads());
  EXPECT_EQ(euler_characteristic(mesh), 2);
  // Which coarse triangles are still whole: the five alone (the triangles around them have
  // edges of their own to split).
  std::size_t whole = 0, whole_at_corner = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); t += 3)
  {
    const std::array<std::int64_t, 3> triangle = { mesh.triangles[t], mesh.triangles[t + 1],
                                                   mesh.triangles[t + 2] };
    if (*std::max_element(triangle.begin(), triangle.end()) < 12)
    {
      ++whole;
      whole_at_corner += std::find(at_corner.begin(), at_corner.end(), triangle) != at_corner.end();
    }
    for (const auto& frozen : at_corner)
    {
      ASSERT_FALSE(mesolens::triangles_meet(triangle, frozen, mesh.vertices))
        << "triangle " << t / 3 << " passes through a triangle at the crease";
    }
  }
  EXPECT_EQ(whole_at_corner, 5u);
  EXPECT_EQ(whole, 5u);
  EXPECT_GT(mesh.triangles.size(), 3u * 200u);
}
