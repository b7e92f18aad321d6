// SPDX-License-Identifier: GPL-3.0-or-later
// Contouring a field a block at a time on a body-centred lattice (a private part of
// MesoLensCore, under the molecular surfaces' meshes): the grid's blocks and the points of a box
// in them, items binned to the blocks they reach, and the mesh of an analytic field.
#include "surface/detail/block_bins.h"
#include "surface/detail/contour_tetrahedra.h"

#include "mesolens/common/errors.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <stdexcept>
#include <tuple>

namespace {
using Vec = Eigen::Vector3d;
using Point = std::tuple<std::int64_t, std::int64_t, std::int64_t>;
constexpr int side = mesolens::ContourGrid::block_points;

/// The grid points (indices) in the box [from, to], found by looking at every point.
std::set<Point> points_in_box(const mesolens::ContourGrid& grid, const Vec& from, const Vec& to)
{
  std::set<Point> inside;
  const std::int64_t cells = mesolens::ContourGrid::block_cells;
  for (std::int64_t z = 0; z <= grid.blocks[2] * cells; ++z)
    for (std::int64_t y = 0; y <= grid.blocks[1] * cells; ++y)
      for (std::int64_t x = 0; x <= grid.blocks[0] * cells; ++x)
      {
        const Vec p = grid.point(x, y, z);
        if ((p.array() >= from.array()).all() && (p.array() <= to.array()).all())
        {
          inside.insert({ x, y, z });
        }
      }
  return inside;
}

/// `count` cubes (from, to) of half-sides up to 4 around centres in [-3, 33]^3.
std::vector<std::pair<Vec, Vec>> random_boxes(unsigned seed, int count)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> where(-3.0, 33.0), reach(0.0, 4.0);
  std::vector<std::pair<Vec, Vec>> boxes;
  for (int k = 0; k < count; ++k)
  {
    const Vec centre(where(random), where(random), where(random));
    const Vec half = Vec::Constant(reach(random));
    boxes.emplace_back(centre - half, centre + half);
  }
  return boxes;
}

/// A sphere's field (positive inside) with a label per grid point, sampled a block at a time.
class SphereBlock final : public mesolens::LocalContourField
{
public:
  SphereBlock(const Vec& centre, double radius, bool inconsistent)
    : centre_(centre)
    , radius_(radius)
    , inconsistent_(inconsistent)
  {
  }
  bool sample_block(const mesolens::ContourGrid& grid, std::size_t block, double* values,
                    std::uint32_t* hints) override
  {
    const auto first = grid.block_first(block);
    for (int z = 0; z < side; ++z)
      for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x)
        {
          const std::size_t at = std::size_t(x + side * (y + side * z));
          values[at] = this->radius_ -
            (grid.point(first[0] + x, first[1] + y, first[2] + z) - this->centre_).norm();
          // A field whose sign at shared points depends on the block asking.
          if (this->inconsistent_ && block % 2 == 1 && x == 0)
          {
            values[at] = -values[at];
          }
          hints[at] = 7;
        }
    return true;
  }
  mesolens::ContourVertex vertex(const Sample& outside, const Sample& inside,
                                 const std::array<Sample, 4>& corners) override
  {
    EXPECT_EQ(outside.hint, 7u);
    EXPECT_EQ(corners[0].hint, 7u);
    // The root of the sphere's field on the edge, by bisection.
    Vec a = outside.position, b = inside.position;
    for (int k = 0; k < 60; ++k)
    {
      const Vec m = 0.5 * (a + b);
      ((m - this->centre_).norm() > this->radius_ ? a : b) = m;
    }
    mesolens::ContourVertex vertex;
    vertex.position = 0.5 * (a + b);
    vertex.normal = (vertex.position - this->centre_).normalized();
    return vertex;
  }

private:
  Vec centre_;
  double radius_;
  bool inconsistent_;
};

class SphereField final : public mesolens::ContourField
{
public:
  SphereField(const Vec& centre, double radius, bool inconsistent = false)
    : centre_(centre)
    , radius_(radius)
    , inconsistent_(inconsistent)
  {
  }
  void prepare(const mesolens::ContourGrid& grid, const mesolens::ParallelFor&) override
  {
    this->blocks = grid.block_count();
  }
  void blocks_to_sample(std::vector<std::size_t>& blocks) const override
  {
    blocks.resize(this->blocks);
    std::iota(blocks.begin(), blocks.end(), std::size_t(0));
  }
  std::unique_ptr<mesolens::LocalContourField> local() const override
  {
    return std::make_unique<SphereBlock>(this->centre_, this->radius_, this->inconsistent_);
  }
  std::size_t blocks = 0;

private:
  Vec centre_;
  double radius_;
  bool inconsistent_;
};
} // namespace

TEST(ContourTetrahedra, EachBlockFindsThePointsOfABoxItHolds)
{
  const mesolens::ContourGrid grid(Vec(-1.3, 0.2, 5.0), Vec(40.0, 30.0, 50.0), 0.7);
  ASSERT_EQ(grid.block_count(), std::size_t(grid.blocks[0] * grid.blocks[1] * grid.blocks[2]));
  ASSERT_GT(grid.block_count(), 8u);
  std::mt19937 random(3);
  std::uniform_real_distribution<double> corner(-5.0, 55.0), size(0.0, 15.0);
  for (int trial = 0; trial < 40; ++trial)
  {
    const Vec from(corner(random), corner(random), corner(random));
    const Vec to = from + Vec(size(random), size(random), size(random));
    const std::set<Point> expected = points_in_box(grid, from, to);
    std::set<Point> found;
    std::array<std::int64_t, 3> first_block{}, last_block{};
    if (grid.blocks_meeting(from, to, first_block, last_block))
    {
      for (std::size_t b = 0; b < grid.block_count(); ++b)
      {
        const auto origin = grid.block_first(b);
        std::array<int, 3> first{}, last{};
        const bool meets = grid.points_within(b, from, to, first, last);
        const std::array<std::int64_t, 3> index = { origin[0] / mesolens::ContourGrid::block_cells,
                                                    origin[1] / mesolens::ContourGrid::block_cells,
                                                    origin[2] /
                                                      mesolens::ContourGrid::block_cells };
        bool listed = true;
        for (int a = 0; a < 3; ++a)
        {
          listed = listed && index[a] >= first_block[a] && index[a] <= last_block[a];
        }
        // Every block holding a point of the box is among those said to meet it.
        EXPECT_TRUE(!meets || listed);
        if (!meets)
        {
          continue;
        }
        for (int z = first[2]; z <= last[2]; ++z)
          for (int y = first[1]; y <= last[1]; ++y)
            for (int x = first[0]; x <= last[0]; ++x)
            {
              found.insert({ origin[0] + x, origin[1] + y, origin[2] + z });
            }
      }
    }
    EXPECT_EQ(found, expected) << "box " << from.transpose() << " to " << to.transpose();
  }
}

TEST(ContourTetrahedra, ItemsAreBinnedToTheBlocksTheirBoxesMeet)
{
  const mesolens::ContourGrid grid(Vec(0, 0, 0), Vec(30.0, 20.0, 25.0), 0.5);
  const mesolens::ContourGrid centred = grid.centred();
  EXPECT_EQ(centred.low, Vec::Constant(-0.25));
  EXPECT_EQ(centred.blocks, grid.blocks);
  const std::vector<std::pair<Vec, Vec>> boxes = random_boxes(11, 300);
  const mesolens::BlockBins bins(grid, boxes.size(), [&](std::size_t k, Vec& from, Vec& to) {
    from = boxes[k].first;
    to = boxes[k].second;
    return k % 7 != 3; // some items left out
  });
  for (std::size_t b = 0; b < grid.block_count(); ++b)
  {
    std::set<std::uint32_t> expected;
    for (std::size_t k = 0; k < boxes.size(); ++k)
    {
      std::array<int, 3> first{}, last{};
      if (k % 7 != 3 &&
          (grid.points_within(b, boxes[k].first, boxes[k].second, first, last) ||
           centred.points_within(b, boxes[k].first, boxes[k].second, first, last)))
      {
        expected.insert(static_cast<std::uint32_t>(k));
      }
    }
    // Each block lists (in order) at least every item with a point of it (of either grid) in
    // its box; items binned but holding none of its points only cost a look.
    const mesolens::BlockBins::Items items = bins.items(b);
    std::vector<std::uint32_t> listed(items.begin(), items.end());
    EXPECT_TRUE(std::is_sorted(listed.begin(), listed.end()));
    for (const std::uint32_t k : expected)
    {
      EXPECT_TRUE(std::binary_search(listed.begin(), listed.end(), k)) << "block " << b;
    }
    EXPECT_EQ(items.empty(), listed.empty());
    EXPECT_EQ(std::binary_search(bins.occupied_blocks().begin(), bins.occupied_blocks().end(), b),
              !listed.empty());
  }
}

TEST(ContourTetrahedra, BinsHoldOnlyTheOccupiedBlocksOfAnyGrid)
{
  // The same boxes binned on a grid of a few thousand blocks (counted per block) and on one
  // of 60 million, nearly all empty (sorted): the same items per block, blocks no box meets
  // stored nowhere.
  std::vector<std::pair<Vec, Vec>> boxes = random_boxes(5, 200);
  boxes.emplace_back(Vec(29990, 1, 1), Vec(29991, 2, 2)); // far along x, alone
  for (const double high_x : { 40.0, 30000.0 })
  {
    const mesolens::ContourGrid grid(Vec(0, 0, 0), Vec(high_x, 30.0, 30.0), 0.1);
    std::map<std::size_t, std::vector<std::uint32_t>> expected;
    for (std::size_t k = 0; k < boxes.size(); ++k)
    {
      std::array<std::int64_t, 3> first{}, last{};
      if (grid.blocks_meeting(boxes[k].first, boxes[k].second, first, last))
      {
        for (std::int64_t z = first[2]; z <= last[2]; ++z)
          for (std::int64_t y = first[1]; y <= last[1]; ++y)
            for (std::int64_t x = first[0]; x <= last[0]; ++x)
            {
              const auto block = std::size_t(x + grid.blocks[0] * (y + grid.blocks[1] * z));
              expected[block].push_back(static_cast<std::uint32_t>(k));
            }
      }
    }
    const mesolens::BlockBins bins(grid, boxes.size(), [&](std::size_t k, Vec& from, Vec& to) {
      from = boxes[k].first;
      to = boxes[k].second;
      return true;
    });
    std::vector<std::size_t> occupied;
    for (const auto& [block, items] : expected)
    {
      occupied.push_back(block);
      const mesolens::BlockBins::Items listed = bins.items(block);
      EXPECT_EQ(std::vector<std::uint32_t>(listed.begin(), listed.end()), items) << block;
    }
    EXPECT_EQ(bins.occupied_blocks(), occupied) << "grid of " << grid.block_count() << " blocks";
    EXPECT_TRUE(bins.items(grid.block_count() - 1).empty());
    EXPECT_GT(expected.size(), 1000u);
  }
}

TEST(ContourTetrahedra, ASphereAcrossBlocksGivesAClosedMeshOnIt)
{
  const Vec centre(5.3, 4.9, 5.1);
  const double radius = 4.0;
  SphereField field(centre, radius);
  const double spacing = 0.3; // blocks of 4.8 A: the sphere spans several a side
  const mesolens::ContourMesh mesh =
    mesolens::contour_tetrahedra(field, Vec(0, 0, 0), Vec(11, 11, 11), spacing, {}, [](double) {});
  EXPECT_GE(field.blocks, 27u);
  ASSERT_FALSE(mesh.triangles.empty());
  for (const auto& vertex : mesh.vertices)
  {
    EXPECT_NEAR((vertex.position - centre).norm(), radius, 1e-9);
  }
  // Closed and 2-manifold: each edge in two triangles, in opposite directions; a sphere's
  // Euler characteristic; triangles facing outwards.
  std::map<std::pair<std::int64_t, std::int64_t>, int> directed;
  double volume = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); t += 3)
  {
    for (int k = 0; k < 3; ++k)
    {
      ++directed[{ mesh.triangles[t + std::size_t(k)],
                   mesh.triangles[t + std::size_t(k + 1) % 3] }];
    }
    const Vec& a = mesh.vertices[std::size_t(mesh.triangles[t])].position;
    const Vec& b = mesh.vertices[std::size_t(mesh.triangles[t + 1])].position;
    const Vec& c = mesh.vertices[std::size_t(mesh.triangles[t + 2])].position;
    volume += (a - centre).dot((b - centre).cross(c - centre)) / 6.0;
  }
  for (const auto& [edge, count] : directed)
  {
    ASSERT_EQ(count, 1);
    ASSERT_EQ(directed.count({ edge.second, edge.first }), 1u);
  }
  const std::int64_t faces = std::int64_t(mesh.triangles.size() / 3);
  const std::int64_t edges = std::int64_t(directed.size() / 2);
  EXPECT_EQ(std::int64_t(mesh.vertices.size()) - edges + faces, 2);
  EXPECT_NEAR(volume, 4.0 / 3.0 * 3.14159265358979 * radius * radius * radius, 0.02 * 268.0);
}

TEST(ContourTetrahedra, AFieldWhoseSignsDependOnTheBlockIsRefused)
{
  SphereField field(Vec(5.3, 4.9, 5.1), 4.0, true);
  EXPECT_THROW(
    mesolens::contour_tetrahedra(field, Vec(0, 0, 0), Vec(11, 11, 11), 0.3, {}, [](double) {}),
    mesolens::SolverFailure);
}
