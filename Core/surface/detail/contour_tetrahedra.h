// SPDX-License-Identifier: GPL-3.0-or-later
// The zero set of a field as a closed triangle mesh, by marching tetrahedra on a body-centred
// cubic lattice sampled a block at a time (private to MesoLensCore): the molecular surfaces'
// tessellation.
#pragma once

#include "mesolens/common/parallel_for.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace mesolens {

/// A mesh vertex with what the field knows about where it lies.
struct ContourVertex
{
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  std::int32_t atom = -1;
  std::uint8_t patch = 0;
  std::uint32_t piece = 0; ///< the field's own label (which boundary piece)
};

/// How contour_tetrahedra() lays out its grid: the points low + spacing (x, y, z) for integers
/// 0 <= x <= cells[0] (and so on), in cubic blocks of block_cells cells a side, the unit of
/// work. A block holds block_points points a side (those on its upper faces are the next
/// block's lower ones), some beyond the grid in the last blocks of an axis.
///
/// The lattice contoured is body-centred: these points and those of centred(), the same grid
/// half a spacing lower on every axis, whose point (x, y, z) is the centre of the cell below
/// point (x, y, z) of this one. Block b of either grid holds the points its cells' tetrahedra
/// use.
struct ContourGrid
{
  static constexpr int block_cells = 16;
  static constexpr int block_points = block_cells + 1;

  Eigen::Vector3d low = Eigen::Vector3d::Zero();
  double spacing = 1; ///< Å, > 0
  std::array<std::int64_t, 3> cells{};
  std::array<std::int64_t, 3> blocks{};

  /// The grid over the box [low, high] (Å) at `spacing` (> 0): at least one cell per axis.
  ContourGrid(const Eigen::Vector3d& low, const Eigen::Vector3d& high, double spacing);

  std::size_t block_count() const
  {
    return static_cast<std::size_t>(this->blocks[0] * this->blocks[1] * this->blocks[2]);
  }
  /// The grid of the lattice's other points: low less half a spacing on every axis, the same
  /// cells and blocks.
  ContourGrid centred() const;
  /// The grid indices of block `block`'s lowest point.
  std::array<std::int64_t, 3> block_first(std::size_t block) const;
  Eigen::Vector3d point(std::int64_t x, std::int64_t y, std::int64_t z) const
  {
    return this->low + this->spacing * Eigen::Vector3d(double(x), double(y), double(z));
  }
  /// The blocks whose points' box, with those of the same block of centred(), meets the box
  /// [from, to] (Å), as inclusive ranges of block indices per axis; false when none does.
  bool blocks_meeting(const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                      std::array<std::int64_t, 3>& first, std::array<std::int64_t, 3>& last) const;
  /// Within block `block`, the inclusive ranges of its own point indices (0 to block_cells)
  /// inside the box [from, to] (Å); false when empty.
  bool points_within(std::size_t block, const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                     std::array<int, 3>& first, std::array<int, 3>& last) const;
};

/// The field on one block at a time, with buffers of its own (one per thread).
class LocalContourField
{
public:
  virtual ~LocalContourField() = default;
  /// The values and hints at the points of `block` of `grid` (ContourGrid::block_points cubed
  /// of each, x fastest): the value is positive inside, negative outside; the hint, what the
  /// field may want to know about the point when it places a vertex near it (its own label).
  /// `grid` is the one prepare() was given or its centred() one. False when no zero lies among
  /// the block's points of either grid (the arrays may then be left as they were); the answer
  /// must be the same for both.
  virtual bool sample_block(const ContourGrid& grid, std::size_t block, double* values,
                            std::uint32_t* hints) = 0;
  /// A grid point's value and hint, as sample_block() gave them.
  struct Sample
  {
    Eigen::Vector3d position;
    double value;
    std::uint32_t hint;
  };
  /// The surface vertex on the segment (a lattice edge of the last block sampled) from
  /// `outside` (value <= 0) to `inside` (value > 0), an edge of the tetrahedron whose four
  /// corners are `corners` (their hints tell which pieces lie near; the corners lie sqrt(5) / 4
  /// spacings from their mean).
  virtual ContourVertex vertex(const Sample& outside, const Sample& inside,
                               const std::array<Sample, 4>& corners) = 0;
};

/// The field to contour. Values at a grid point must not depend on the block asking (their
/// signs at least), as neighbouring blocks share points; contour_tetrahedra() throws
/// SolverFailure ("contour is inconsistent") when they do.
class ContourField
{
public:
  virtual ~ContourField() = default;
  /// Called once, before any local(), with the grid about to be sampled (to gather what each
  /// block needs: the points of both its grids, see ContourGrid::blocks_meeting()).
  virtual void prepare(const ContourGrid& grid, const ParallelFor& parallel_for) = 0;
  /// After prepare(): the blocks that may hold a zero, in increasing order, into `blocks`. The
  /// others are not sampled, so that space far from any atom costs nothing.
  virtual void blocks_to_sample(std::vector<std::size_t>& blocks) const = 0;
  /// A new local view of the field (called once per thread, from that thread).
  virtual std::unique_ptr<LocalContourField> local() const = 0;
};

/// A contour's mesh. contour_tetrahedra() leaves room for as many vertices and triangles again
/// (capacity, not committed memory until used), for refinements that add them in place.
struct ContourMesh
{
  std::vector<ContourVertex> vertices;
  std::vector<std::int64_t> triangles; ///< 3 per triangle, counter-clockwise seen from outside
};

/// Contours `field` over the box [low, high] on the body-centred cubic lattice of `spacing`
/// (> 0, the cubes' side) laid out as ContourGrid does; the field must be negative on the box's
/// faces for the mesh to be closed. Each of the lattice's tetrahedra (twelve per cube, all
/// alike: an edge of the cubes, length `spacing`, and the edge joining two of the cube centres
/// beside it, the four others sqrt(3) / 2 spacings long) whose corners change sign is cut, so
/// the mesh is watertight and 2-manifold without ambiguous cases. Every point lies within
/// sqrt(5) / 4 spacings of a lattice point: about half as many points as a cubic grid with that
/// reach, and 0.6 times as many edges crossing a surface, in better shaped tetrahedra. Each block
/// is sampled once (on both grids). `progress` (may be empty) gets the fraction done from the
/// calling thread. Deterministic whatever `parallel_for`.
ContourMesh contour_tetrahedra(ContourField& field, const Eigen::Vector3d& low,
                               const Eigen::Vector3d& high, double spacing,
                               const ParallelFor& parallel_for,
                               const std::function<void(double)>& progress);

} // namespace mesolens
