// SPDX-License-Identifier: GPL-3.0-or-later
#include <Eigen/Dense>

#include "surface/detail/frozen_creases.h"

#include "common/detail/grid_cells.h"

#include <algorithm>

namespace mesolens {

namespace {
using Vec = Eigen::Vector3d;

/// Six times the signed volume of tetrahedron (a, b, c, d).
double orientation(const Vec& a, const Vec& b, const Vec& c, const Vec& d)
{
  return (b - a).cross(c - a).dot(d - a);
}

const Vec& at(const std::vector<ContourVertex>& vertices, std::int64_t v)
{
  return vertices[std::size_t(v)].position;
}

/// The box of the triangle whose corners start at `corners`.
std::array<Vec, 2> box_of(const std::int64_t* corners, const std::vector<ContourVertex>& vertices)
{
  std::array<Vec, 2> box = { at(vertices, corners[0]), at(vertices, corners[0]) };
  for (int k = 1; k < 3; ++k)
  {
    box[0] = box[0].cwiseMin(at(vertices, corners[k]));
    box[1] = box[1].cwiseMax(at(vertices, corners[k]));
  }
  return box;
}

bool overlap(const std::array<Vec, 2>& a, const std::array<Vec, 2>& b)
{
  return (a[0].array() <= b[1].array()).all() && (b[0].array() <= a[1].array()).all();
}

/// The cell of width `width` holding `x`.
GridCell cell_of(const Vec& x, double width)
{
  return grid_cell({ x[0], x[1], x[2] }, width);
}

/// A triangle's plane as orientation() sees it: the side of p is orientation(a, b, c, p),
/// computed the same way (the same rounding) with the cross product made once.
struct TrianglePlane
{
  TrianglePlane(const Vec& a, const Vec& b, const Vec& c)
    : corner(a)
    , normal((b - a).cross(c - a))
  {
  }
  double side(const Vec& p) const
  {
    return this->normal.dot(p - this->corner);
  }
  Vec corner, normal;
};

/// Whether the segment [p, q], whose ends lie on sides `from` and `to` of triangle (a, b, c)'s
/// plane, meets the triangle (see segment_meets_triangle()).
bool crossing_meets_triangle(double from, double to, const Vec& p, const Vec& q, const Vec& a,
                             const Vec& b, const Vec& c)
{
  if ((from > 0 && to > 0) || (from < 0 && to < 0) || (from == 0 && to == 0))
  {
    return false;
  }
  const double ab = orientation(p, q, a, b), bc = orientation(p, q, b, c),
               ca = orientation(p, q, c, a);
  return (ab >= 0 && bc >= 0 && ca >= 0) || (ab <= 0 && bc <= 0 && ca <= 0);
}
} // namespace

bool segment_meets_triangle(const Vec& p, const Vec& q, const Vec& a, const Vec& b, const Vec& c)
{
  const TrianglePlane plane(a, b, c);
  return crossing_meets_triangle(plane.side(p), plane.side(q), p, q, a, b, c);
}

bool triangles_meet(const std::array<std::int64_t, 3>& first,
                    const std::array<std::int64_t, 3>& second,
                    const std::vector<ContourVertex>& vertices)
{
  int shared = 0, first_shared = -1, second_shared = -1;
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      if (first[std::size_t(i)] == second[std::size_t(j)])
      {
        ++shared;
        first_shared = i;
        second_shared = j;
      }
    }
  }
  if (shared >= 2)
  {
    return false;
  }
  // Each triangle's corners against the other's plane, once: most edges stay on one side.
  const std::array<const Vec*, 3> one = { &at(vertices, first[0]), &at(vertices, first[1]),
                                          &at(vertices, first[2]) };
  const std::array<const Vec*, 3> other = { &at(vertices, second[0]), &at(vertices, second[1]),
                                            &at(vertices, second[2]) };
  const TrianglePlane one_plane(*one[0], *one[1], *one[2]),
    other_plane(*other[0], *other[1], *other[2]);
  const std::array<double, 3> one_sides = { other_plane.side(*one[0]), other_plane.side(*one[1]),
                                            other_plane.side(*one[2]) };
  const std::array<double, 3> other_sides = { one_plane.side(*other[0]), one_plane.side(*other[1]),
                                              one_plane.side(*other[2]) };
  // Edge k (from corner k to k + 1) of `edges` against triangle `into`.
  const auto edge_meets = [](const std::array<const Vec*, 3>& edges,
                             const std::array<double, 3>& sides, int k,
                             const std::array<const Vec*, 3>& into) {
    const std::size_t from = std::size_t(k), to = std::size_t((k + 1) % 3);
    return crossing_meets_triangle(sides[from], sides[to], *edges[from], *edges[to], *into[0],
                                   *into[1], *into[2]);
  };
  if (shared == 1)
  {
    // The edge opposite corner k starts at corner k + 1.
    return edge_meets(one, one_sides, (first_shared + 1) % 3, other) ||
      edge_meets(other, other_sides, (second_shared + 1) % 3, one);
  }
  for (int k = 0; k < 3; ++k)
  {
    if (edge_meets(one, one_sides, k, other) || edge_meets(other, other_sides, k, one))
    {
      return true;
    }
  }
  return false;
}

FrozenCreases::FrozenCreases(const ContourMesh& mesh, const std::vector<char>& frozen,
                             double cell_width)
  : cell_width_(cell_width)
{
  const std::size_t vertex_count = mesh.vertices.size();
  this->around_start_.assign(vertex_count + 1, 0);
  for (std::size_t t = 0; t < frozen.size(); ++t)
  {
    if (!frozen[t])
    {
      continue;
    }
    const std::int64_t* corners = &mesh.triangles[3 * t];
    const std::uint32_t index = static_cast<std::uint32_t>(this->corners_.size());
    this->corners_.push_back({ corners[0], corners[1], corners[2] });
    for (int k = 0; k < 3; ++k)
    {
      ++this->around_start_[std::size_t(corners[k]) + 1];
    }
    const Box box = box_of(corners, mesh.vertices);
    this->boxes_.push_back(box);
    const GridCell from = cell_of(box[0], cell_width), to = cell_of(box[1], cell_width);
    this->first_cells_.push_back(from);
    for (std::int64_t z = from[2]; z <= to[2]; ++z)
      for (std::int64_t y = from[1]; y <= to[1]; ++y)
        for (std::int64_t x = from[0]; x <= to[0]; ++x)
        {
          this->cells_.emplace_back(grid_cell_key({ x, y, z }), index);
        }
  }
  std::sort(this->cells_.begin(), this->cells_.end());
  for (std::size_t e = 0; e < this->cells_.size();)
  {
    std::size_t end = e;
    while (end < this->cells_.size() && this->cells_[end].first == this->cells_[e].first)
    {
      ++end;
    }
    this->cell_ranges_.emplace(this->cells_[e].first,
                               std::make_pair(std::uint32_t(e), std::uint32_t(end)));
    e = end;
  }
  for (std::size_t v = 0; v < vertex_count; ++v)
  {
    this->around_start_[v + 1] += this->around_start_[v];
  }
  this->around_.resize(this->around_start_[vertex_count]);
  std::vector<std::uint32_t> cursor(this->around_start_.begin(), this->around_start_.end() - 1);
  for (std::size_t k = 0; k < this->corners_.size(); ++k)
  {
    for (const std::int64_t v : this->corners_[k])
    {
      this->around_[cursor[std::size_t(v)]++] = static_cast<std::uint32_t>(k);
    }
  }
}

bool FrozenCreases::frozen_edge(std::int64_t a, std::int64_t b) const
{
  if (std::size_t(a) + 1 >= this->around_start_.size())
  {
    return false;
  }
  for (std::uint32_t k = this->around_start_[std::size_t(a)];
       k < this->around_start_[std::size_t(a) + 1]; ++k)
  {
    const auto& corners = this->corners_[this->around_[k]];
    if (std::find(corners.begin(), corners.end(), b) != corners.end())
    {
      return true;
    }
  }
  return false;
}

bool FrozenCreases::meets(const std::vector<std::int64_t>& triangles,
                          const std::vector<ContourVertex>& vertices) const
{
  if (this->cells_.empty() || triangles.empty())
  {
    return false;
  }
  // Boxes first: most frozen triangles in the cells lie clear of the pieces. (The boxes of the
  // first few pieces, as many as a triangle cut along its edges gives, are kept.)
  constexpr std::size_t kept_boxes = 4;
  std::array<Box, kept_boxes> boxes;
  Box all = box_of(&triangles[0], vertices);
  boxes[0] = all;
  for (std::size_t k = 3; k < triangles.size(); k += 3)
  {
    const Box box = box_of(&triangles[k], vertices);
    if (k < 3 * kept_boxes)
    {
      boxes[k / 3] = box;
    }
    all = { all[0].cwiseMin(box[0]), all[1].cwiseMax(box[1]) };
  }
  const GridCell from = cell_of(all[0], this->cell_width_), to = cell_of(all[1], this->cell_width_);
  for (std::int64_t z = from[2]; z <= to[2]; ++z)
    for (std::int64_t y = from[1]; y <= to[1]; ++y)
      for (std::int64_t x = from[0]; x <= to[0]; ++x)
      {
        const auto range = this->cell_ranges_.find(grid_cell_key({ x, y, z }));
        if (range == this->cell_ranges_.end())
        {
          continue;
        }
        for (auto entry = this->cells_.begin() + range->second.first;
             entry != this->cells_.begin() + range->second.second; ++entry)
        {
          const Box& box = this->boxes_[entry->second];
          // A frozen triangle lies in every cell its box meets: tested in the first cell that
          // both boxes meet alone.
          const GridCell& first = this->first_cells_[entry->second];
          if (!overlap(all, box) || std::max(first[0], from[0]) != x ||
              std::max(first[1], from[1]) != y || std::max(first[2], from[2]) != z)
          {
            continue;
          }
          const auto& frozen = this->corners_[entry->second];
          for (std::size_t k = 0; k < triangles.size(); k += 3)
          {
            if (overlap(k < 3 * kept_boxes ? boxes[k / 3] : box_of(&triangles[k], vertices), box) &&
                triangles_meet({ triangles[k], triangles[k + 1], triangles[k + 2] }, frozen,
                               vertices))
            {
              return true;
            }
          }
        }
      }
  return false;
}

} // namespace mesolens
