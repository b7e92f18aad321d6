// SPDX-License-Identifier: GPL-3.0-or-later
#include <Eigen/Dense>

#include "surface/detail/contour_tetrahedra.h"

#include "mesolens/common/errors.h"

#include "surface/detail/balanced_loop.h"
#include "common/detail/grid_cells.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <memory>
#include <mutex>

namespace mesolens {

namespace {
using Vec = Eigen::Vector3d;
/// Cells per block edge: the unit of parallel work and the root of its octree. Larger blocks
/// gather their boundary pieces less often; much larger ones leave threads idle at the end.
constexpr int block_cells = 16;

/// The points a cell (x, y, z) of the grid takes its tetrahedra from: 0 the grid's point
/// (x, y, z); 1 + d the next one along axis d; 4 + m the centred grid's point (x, y, z) plus the
/// bits of m (x 1, y 2, z 4), at the centre of the cell below it. The cell's tetrahedra are the
/// four about each of its three edges from point 0 (each edge of the grid is one cell's).
constexpr int cell_points = 12;
constexpr int edge_kinds = 14;

/// An edge between two cell points: the lattice point it is filed under (offset from the cell,
/// on the grid or the centred grid by its kind) and its kind.
struct CellEdge
{
  std::array<int, 3> point{};
  /// 0-2 the grid's edges along x, y, z, filed under their lower end; 3-5 the centred grid's;
  /// 6 + m the edge from a grid point to the centred grid's point m steps (bits as above) from
  /// it, filed under the grid point. -1 no edge.
  int kind = -1;
};

struct CellTables
{
  std::array<std::array<int, 4>, 12> tetrahedra{}; ///< each ordered with positive orientation
  std::array<std::array<CellEdge, cell_points>, cell_points> edges{};
  /// Per cell point: its lattice (0 the grid, 1 the centred grid), its index steps from the
  /// cell's own on it, and so its place in a block's arrays from the cell's.
  std::array<int, cell_points> lattice{};
  std::array<std::array<int, 3>, cell_points> step{};
  std::array<std::size_t, cell_points> place{};
};

CellTables cell_tables()
{
  CellTables tables;
  const auto bits = [](int m) { return std::array<int, 3>{ m & 1, (m >> 1) & 1, (m >> 2) & 1 }; };
  constexpr int side = ContourGrid::block_points;
  for (int k = 0; k < cell_points; ++k)
  {
    tables.lattice[std::size_t(k)] = k >= 4 ? 1 : 0;
    tables.step[std::size_t(k)] =
      k == 0 ? std::array<int, 3>{ 0, 0, 0 } : bits(k < 4 ? 1 << (k - 1) : k - 4);
    const auto& step = tables.step[std::size_t(k)];
    tables.place[std::size_t(k)] = std::size_t(step[0] + side * (step[1] + side * step[2]));
  }
  // Positions in spacings from the cell's grid point: a centred point lies half a step below
  // its index.
  const auto position = [&](int k) -> Vec {
    const auto& step = tables.step[std::size_t(k)];
    return Vec(step[0], step[1], step[2]) - Vec::Constant(0.5 * tables.lattice[std::size_t(k)]);
  };
  const int around[4][2] = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } };
  for (int d = 0; d < 3; ++d)
  {
    // About the edge from point 0 along d: the centred points half a step along d, half a step
    // either way along the other two axes, in turn.
    const int u = (d + 1) % 3, v = (d + 2) % 3;
    for (int q = 0; q < 4; ++q)
    {
      const auto centred = [&](int turn) {
        return 4 + (1 << d) + (around[turn % 4][0] << u) + (around[turn % 4][1] << v);
      };
      std::array<int, 4> tet = { 0, 1 + d, centred(q), centred(q + 1) };
      const Vec a = position(tet[0]);
      const double volume =
        (position(tet[1]) - a).cross(position(tet[2]) - a).dot(position(tet[3]) - a);
      if (volume < 0)
      {
        std::swap(tet[2], tet[3]);
      }
      tables.tetrahedra[std::size_t(4 * d + q)] = tet;
    }
  }
  for (int a = 0; a < cell_points; ++a)
  {
    for (int b = 0; b < cell_points; ++b)
    {
      CellEdge& edge = tables.edges[std::size_t(a)][std::size_t(b)];
      const int low = std::min(a, b), high = std::max(a, b);
      if (a == b)
      {
        continue;
      }
      const auto& low_step = tables.step[std::size_t(low)];
      const auto& high_step = tables.step[std::size_t(high)];
      if (high < 4)
      {
        if (low != 0)
        {
          continue; // not an edge of the cell's tetrahedra
        }
        edge.kind = high - 1;
        edge.point = low_step;
      }
      else if (low >= 4)
      {
        const int w = (low - 4) ^ (high - 4);
        if (w != 1 && w != 2 && w != 4)
        {
          continue;
        }
        edge.kind = 3 + (w == 1 ? 0 : (w == 2 ? 1 : 2));
        edge.point = low_step;
      }
      else
      {
        // From the grid point to a centred point 0 or 1 step above it on every axis.
        int mask = 0;
        for (int k = 0; k < 3 && mask >= 0; ++k)
        {
          const int step = high_step[std::size_t(k)] - low_step[std::size_t(k)];
          mask = step < 0 || step > 1 ? -1 : mask | (step << k);
        }
        if (mask < 0)
        {
          continue;
        }
        edge.kind = 6 + mask;
        edge.point = low_step;
      }
    }
  }
  return tables;
}

/// The cell (offset from the point an edge of `kind` is filed under) that makes the edge's
/// vertex: one whose tetrahedra hold the edge. A grid edge's is its lower end's; a centred
/// edge's, of the four cells about it, the one below it on both other axes; a diagonal's, the
/// grid point's own cell when the centred point lies above it on some axis (the cell's edge along
/// that axis holds it), else the cell below along x.
std::array<int, 3> owner_offset(int kind)
{
  if (kind >= 3 && kind < 6)
  {
    const int axis = kind - 3;
    return { axis == 0 ? 0 : -1, axis == 1 ? 0 : -1, axis == 2 ? 0 : -1 };
  }
  return { kind == 6 ? -1 : 0, 0, 0 };
}

// Even permutations of a positive tetrahedron putting the listed corners first (they keep the
// orientation): one corner alone, and each pair.
constexpr int first_alone[4][4] = { { 0, 1, 2, 3 },
                                    { 1, 0, 3, 2 },
                                    { 2, 0, 1, 3 },
                                    { 3, 0, 2, 1 } };
int pair_order(int a, int b, int order[4])
{
  static const int orders[6][4] = { { 0, 1, 2, 3 }, { 0, 2, 3, 1 }, { 0, 3, 1, 2 },
                                    { 1, 2, 0, 3 }, { 1, 3, 2, 0 }, { 2, 3, 0, 1 } };
  static const int which[4][4] = {
    { -1, 0, 1, 2 }, { 0, -1, 3, 4 }, { 1, 3, -1, 5 }, { 2, 4, 5, -1 }
  };
  const int k = which[a][b];
  std::copy(orders[k], orders[k] + 4, order);
  return k;
}

/// Triangle corners refer to a block's own vertices, or (with this bit) to its foreign ones.
constexpr std::uint32_t foreign_bit = 0x80000000u;

/// What one block made: the vertices it owns (those on edges whose lower point lies in it),
/// with the grid key of their edge; the keys of the edges it uses but another block owns; and
/// its triangles, as indices into those. (A cache line each: neighbouring blocks are filled at
/// once by different threads.)
struct alignas(64) BlockOutput
{
  std::vector<ContourVertex> vertices;
  std::vector<std::uint64_t> keys;
  std::vector<std::uint64_t> foreign_keys;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

/// Edges are keyed by the lattice point they are filed under and their kind; the block whose
/// cell owner_offset() names makes an edge's vertex.
class EdgeKeys
{
public:
  static constexpr std::uint64_t kinds = 16;
  static_assert(edge_kinds <= int(kinds), "an edge's kind must fit its key");

  explicit EdgeKeys(const ContourGrid& grid)
    : points_{ grid.cells[0] + 1, grid.cells[1] + 1, grid.cells[2] + 1 }
    , blocks_(grid.blocks)
  {
  }

  std::uint64_t key(std::int64_t x, std::int64_t y, std::int64_t z, int kind) const
  {
    return this->point_key(x, y, z) * kinds + std::uint64_t(kind);
  }
  /// The block making the vertex of the edge of `kind` filed under point (x, y, z).
  std::size_t owner_block(std::int64_t x, std::int64_t y, std::int64_t z, int kind) const
  {
    const auto offset = owner_offset(kind);
    return this->block_of_cell(x + offset[0], y + offset[1], z + offset[2]);
  }
  std::size_t owner_of(std::uint64_t key) const
  {
    const auto& points = this->points_;
    const std::uint64_t point = key / kinds;
    return this->owner_block(
      static_cast<std::int64_t>(point % std::uint64_t(points[0])),
      static_cast<std::int64_t>((point / std::uint64_t(points[0])) % std::uint64_t(points[1])),
      static_cast<std::int64_t>(point / std::uint64_t(points[0] * points[1])),
      static_cast<int>(key % kinds));
  }

private:
  std::uint64_t point_key(std::int64_t x, std::int64_t y, std::int64_t z) const
  {
    return static_cast<std::uint64_t>(x + this->points_[0] * (y + this->points_[1] * z));
  }
  std::size_t block_of_cell(std::int64_t x, std::int64_t y, std::int64_t z) const
  {
    const auto along = [&](std::int64_t c, int a) {
      return std::clamp<std::int64_t>(c / ContourGrid::block_cells, 0, this->blocks_[a] - 1);
    };
    return static_cast<std::size_t>(
      along(x, 0) + this->blocks_[0] * (along(y, 1) + this->blocks_[1] * along(z, 2)));
  }

  std::array<std::int64_t, 3> points_; ///< per axis
  std::array<std::int64_t, 3> blocks_; ///< per axis
};

/// Points per block edge, in a block's arrays.
constexpr int block_side = ContourGrid::block_points;

/// What a thread reuses from block to block: the field's local view and the block's tables.
struct BlockBuffers
{
  std::unique_ptr<LocalContourField> local;
  std::array<std::vector<double>, 2> values;       ///< of the grid and the centred grid
  std::array<std::vector<std::uint32_t>, 2> hints; ///< of the grid and the centred grid
  /// Per block point and edge kind, the block that made the vertex on that edge (its number
  /// plus one, in the high half) and the vertex's index: entries of earlier blocks are
  /// stale, so the table is never cleared.
  std::vector<std::uint64_t> made;
};

/// Block buffers kept from round to round of contour_blocks: a round's ranges each take one
/// (made on first use) and give it back when they end. Made afresh every round, they cost a
/// zeroed table of about 0.5 MB per round, which on a grid of many empty blocks was most of the
/// time.
class BlockBufferPool
{
public:
  std::unique_ptr<BlockBuffers> take()
  {
    const std::lock_guard<std::mutex> lock(this->mutex_);
    if (this->free_.empty())
    {
      return std::make_unique<BlockBuffers>();
    }
    std::unique_ptr<BlockBuffers> buffers = std::move(this->free_.back());
    this->free_.pop_back();
    return buffers;
  }
  void give(std::unique_ptr<BlockBuffers> buffers)
  {
    const std::lock_guard<std::mutex> lock(this->mutex_);
    this->free_.push_back(std::move(buffers));
  }

private:
  std::mutex mutex_;
  std::vector<std::unique_ptr<BlockBuffers>> free_;
};

/// One range's buffers from the pool, given back when the range ends.
struct PooledBlockBuffers
{
  BlockBufferPool* pool = nullptr;
  std::unique_ptr<BlockBuffers> buffers;

  BlockBuffers& from(BlockBufferPool& source)
  {
    if (!this->buffers)
    {
      this->pool = &source;
      this->buffers = source.take();
    }
    return *this->buffers;
  }
  ~PooledBlockBuffers()
  {
    if (this->buffers)
    {
      this->pool->give(std::move(this->buffers));
    }
  }
};

/// How the field's samples of a block came out.
enum class Sampled
{
  Crossed,  ///< a zero lies among its points
  Empty,    ///< none does
  OneSided, ///< the two grids disagree on that: the field is at fault
};

/// Samples the field on block `block` of both grids into `buffers` (made on first use).
Sampled sample_block(const ContourField& field, const ContourGrid& grid, const ContourGrid& centred,
                     std::size_t block, BlockBuffers& buffers)
{
  if (!buffers.local)
  {
    buffers.local = field.local();
    for (int g = 0; g < 2; ++g)
    {
      buffers.values[std::size_t(g)].resize(block_side * block_side * block_side);
      buffers.hints[std::size_t(g)].resize(block_side * block_side * block_side);
    }
    buffers.made.assign(std::size_t(block_side * block_side * block_side * edge_kinds), 0);
  }
  LocalContourField* const local = buffers.local.get();
  if (!local->sample_block(grid, block, buffers.values[0].data(), buffers.hints[0].data()))
  {
    return Sampled::Empty;
  }
  if (!local->sample_block(centred, block, buffers.values[1].data(), buffers.hints[1].data()))
  {
    return Sampled::OneSided;
  }
  return Sampled::Crossed;
}

/// Contours the cells of one sampled block into its output: a cell's tetrahedra whose corners
/// change sign, cut into triangles whose corners are the vertices on their crossed edges.
class BlockContour
{
public:
  BlockContour(const ContourGrid& grid, const ContourGrid& centred, const EdgeKeys& keys,
               const CellTables& tables, std::size_t block, BlockBuffers& buffers, BlockOutput& out)
    : grid_(grid)
    , centred_(centred)
    , keys_(keys)
    , tables_(tables)
    , block_(block)
    , buffers_(buffers)
    , out_(out)
    , local_(buffers.local.get())
    , first_(grid.block_first(block))
    , stamp_(std::uint64_t(block + 1) << 32)
  {
  }

  /// Contours the cells whose twelve points change sign.
  void contour_crossed_cells()
  {
    const auto& cells = this->grid_.cells;
    const auto& lattice = this->tables_.lattice;
    const auto& place = this->tables_.place;
    const double* const values[2] = { this->buffers_.values[0].data(),
                                      this->buffers_.values[1].data() };
    const std::int64_t x0 = this->first_[0], y0 = this->first_[1], z0 = this->first_[2];
    const std::int64_t x1 = std::min(x0 + ContourGrid::block_cells, cells[0]);
    const std::int64_t y1 = std::min(y0 + ContourGrid::block_cells, cells[1]);
    const std::int64_t z1 = std::min(z0 + ContourGrid::block_cells, cells[2]);
    for (std::int64_t z = z0; z < z1; ++z)
      for (std::int64_t y = y0; y < y1; ++y)
        for (std::int64_t x = x0; x < x1; ++x)
        {
          const std::size_t at =
            std::size_t((x - x0) + block_side * ((y - y0) + block_side * (z - z0)));
          int inside = 0;
          for (int k = 0; k < cell_points; ++k)
          {
            inside += values[lattice[std::size_t(k)]][at + place[std::size_t(k)]] > 0 ? 1 : 0;
          }
          if (inside != 0 && inside != cell_points)
          {
            this->contour_cell({ x, y, z }, at);
          }
        }
  }

private:
  /// Cell `cell` (at `at` in the block's arrays): its points' samples, then its tetrahedra.
  void contour_cell(const std::array<std::int64_t, 3>& cell, std::size_t at)
  {
    this->cell_ = cell;
    for (int k = 0; k < cell_points; ++k)
    {
      const std::size_t g = std::size_t(this->tables_.lattice[std::size_t(k)]);
      const std::size_t i = at + this->tables_.place[std::size_t(k)];
      const auto& d = this->tables_.step[std::size_t(k)];
      this->corner_[std::size_t(k)] = {
        (g ? this->centred_ : this->grid_).point(cell[0] + d[0], cell[1] + d[1], cell[2] + d[2]),
        this->buffers_.values[g][i], this->buffers_.hints[g][i]
      };
    }
    for (const auto& tet : this->tables_.tetrahedra)
    {
      this->cut_tetrahedron(tet);
    }
  }

  /// The triangles where the surface crosses tetrahedron `tet` (cell points, positively
  /// oriented), counter-clockwise seen from outside: one about a corner alone on its side, two
  /// where two corners lie on each side.
  void cut_tetrahedron(const std::array<int, 4>& tet)
  {
    const auto& corner = this->corner_;
    BlockOutput& out = this->out_;
    int inside_mask = 0, inside_count = 0;
    for (int k = 0; k < 4; ++k)
    {
      if (corner[std::size_t(tet[std::size_t(k)])].value > 0)
      {
        inside_mask |= 1 << k;
        ++inside_count;
      }
    }
    if (inside_count == 0 || inside_count == 4)
    {
      return;
    }
    if (inside_count == 1 || inside_count == 3)
    {
      int lone = 0;
      for (int k = 0; k < 4; ++k)
      {
        const bool in = (inside_mask >> k) & 1;
        if (in == (inside_count == 1))
        {
          lone = k;
        }
      }
      const int* order = first_alone[lone];
      const int a = tet[std::size_t(order[0])], b = tet[std::size_t(order[1])],
                c = tet[std::size_t(order[2])], d = tet[std::size_t(order[3])];
      if (inside_count == 1)
      {
        out.triangles.push_back({ this->edge_vertex(a, b, tet), this->edge_vertex(a, c, tet),
                                  this->edge_vertex(a, d, tet) });
      }
      else
      {
        out.triangles.push_back({ this->edge_vertex(a, b, tet), this->edge_vertex(a, d, tet),
                                  this->edge_vertex(a, c, tet) });
      }
      return;
    }
    int pair[2], p = 0;
    for (int k = 0; k < 4; ++k)
    {
      if ((inside_mask >> k) & 1)
      {
        pair[p++] = k;
      }
    }
    int order[4];
    pair_order(pair[0], pair[1], order);
    const int a = tet[std::size_t(order[0])], b = tet[std::size_t(order[1])],
              c = tet[std::size_t(order[2])], d = tet[std::size_t(order[3])];
    const std::uint32_t ac = this->edge_vertex(a, c, tet), ad = this->edge_vertex(a, d, tet),
                        bd = this->edge_vertex(b, d, tet), bc = this->edge_vertex(b, c, tet);
    out.triangles.push_back({ ac, ad, bd });
    out.triangles.push_back({ ac, bd, bc });
  }

  /// The vertex on the edge between cell points `a` and `b` of tetrahedron `tet`, as the
  /// block's own or foreign index: made once per block (the table of made edges remembers it),
  /// by this block when it owns the edge, else left to its owner and found by key.
  std::uint32_t edge_vertex(int a, int b, const std::array<int, 4>& tet)
  {
    const auto& corner = this->corner_;
    BlockOutput& out = this->out_;
    const CellEdge& kind = this->tables_.edges[std::size_t(a)][std::size_t(b)];
    const std::int64_t x = this->cell_[0] + kind.point[0], y = this->cell_[1] + kind.point[1],
                       z = this->cell_[2] + kind.point[2];
    std::uint64_t& entry = this->buffers_.made[std::size_t(
      edge_kinds *
        ((x - this->first_[0]) +
         block_side * ((y - this->first_[1]) + block_side * (z - this->first_[2]))) +
      kind.kind)];
    if ((entry & ~std::uint64_t(0xffffffffu)) != this->stamp_)
    {
      std::uint32_t index = 0;
      const std::uint64_t key = this->keys_.key(x, y, z, kind.kind);
      if (this->keys_.owner_block(x, y, z, kind.kind) == this->block_)
      {
        const int outside = corner[std::size_t(a)].value > 0 ? b : a;
        const int inside = corner[std::size_t(a)].value > 0 ? a : b;
        index = static_cast<std::uint32_t>(out.vertices.size());
        out.vertices.push_back(
          this->local_->vertex(corner[std::size_t(outside)], corner[std::size_t(inside)],
                               { corner[std::size_t(tet[0])], corner[std::size_t(tet[1])],
                                 corner[std::size_t(tet[2])], corner[std::size_t(tet[3])] }));
        out.keys.push_back(key);
      }
      else
      {
        // The owner computes it: every cell holding a crossed edge is contoured, as the
        // signs at lattice points do not depend on the block asking.
        index = static_cast<std::uint32_t>(out.foreign_keys.size()) | foreign_bit;
        out.foreign_keys.push_back(key);
      }
      entry = this->stamp_ | index;
    }
    return static_cast<std::uint32_t>(entry);
  }

  const ContourGrid& grid_;
  const ContourGrid& centred_;
  const EdgeKeys& keys_;
  const CellTables& tables_;
  const std::size_t block_;
  BlockBuffers& buffers_;
  BlockOutput& out_;
  LocalContourField* const local_;
  const std::array<std::int64_t, 3> first_; ///< the block's lowest grid point
  const std::uint64_t stamp_;               ///< the block's mark in the table of made edges
  std::array<std::int64_t, 3> cell_{};      ///< the cell being contoured
  std::array<LocalContourField::Sample, cell_points> corner_; ///< and its points' samples
};

/// The blocks that made something, in increasing order, with what they made: far fewer than
/// the grid's blocks where the molecule is sparse (every block's output would take gigabytes
/// for atoms thousands of Å apart).
struct ContouredBlocks
{
  std::vector<std::size_t> active;
  std::vector<BlockOutput> outputs;
  bool one_sided = false; ///< some block's grids disagreed on whether a zero lies among them
};

/// Contours every block of the grid, in rounds so that progress is reported from this thread.
ContouredBlocks contour_blocks(const ContourField& field, const ContourGrid& grid,
                               const EdgeKeys& keys, const ParallelFor& parallel_for,
                               const std::function<void(double)>& progress)
{
  static const CellTables tables = cell_tables();
  const ContourGrid centred = grid.centred();
  std::vector<std::size_t> to_sample;
  field.blocks_to_sample(to_sample);
  const std::size_t block_count = to_sample.size();
  ContouredBlocks blocks;
  std::atomic<bool> one_sided_block{ false };
  const std::size_t round = 256;
  std::vector<BlockOutput> round_outputs(round);
  BlockBufferPool pool;
  for (std::size_t first = 0; first < block_count; first += round)
  {
    const std::size_t count = std::min(round, block_count - first);
    // Blocks the surface crosses cost far more than the others: taken one at a time.
    run_balanced<PooledBlockBuffers>(
      parallel_for, count, [&](std::size_t k, PooledBlockBuffers& pooled) {
        BlockBuffers& buffers = pooled.from(pool);
        const std::size_t block = to_sample[first + k];
        const Sampled sampled = sample_block(field, grid, centred, block, buffers);
        if (sampled == Sampled::OneSided)
        {
          one_sided_block = true;
        }
        else if (sampled == Sampled::Crossed)
        {
          BlockContour(grid, centred, keys, tables, block, buffers, round_outputs[k])
            .contour_crossed_cells();
        }
      });
    for (std::size_t k = 0; k < count; ++k)
    {
      BlockOutput& out = round_outputs[k];
      if (!out.vertices.empty() || !out.triangles.empty() || !out.foreign_keys.empty())
      {
        blocks.active.push_back(to_sample[first + k]);
        blocks.outputs.push_back(std::move(out));
        out = {};
      }
    }
    if (progress)
    {
      progress(double(first + count) / double(block_count));
    }
  }
  blocks.one_sided = one_sided_block;
  return blocks;
}

/// Per active block, its own vertices' keys sorted, with their indices: the foreign vertices
/// are found in their owners' keys.
using OwnedKeys = std::vector<std::vector<std::pair<std::uint64_t, std::uint32_t>>>;

OwnedKeys sorted_owned_keys(const std::vector<BlockOutput>& outputs,
                            const ParallelFor& parallel_for)
{
  OwnedKeys owned(outputs.size());
  run_parallel(parallel_for, outputs.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t b = begin; b < end; ++b)
    {
      auto& sorted = owned[b];
      sorted.resize(outputs[b].keys.size());
      for (std::size_t k = 0; k < sorted.size(); ++k)
      {
        sorted[k] = { outputs[b].keys[k], static_cast<std::uint32_t>(k) };
      }
      std::sort(sorted.begin(), sorted.end());
    }
  });
  return owned;
}

/// The mesh index of the vertex its owner made for edge `key`; -1 when its owner made none.
std::int64_t global_vertex(std::uint64_t key, const std::vector<std::size_t>& active,
                           const OwnedKeys& owned, const std::vector<std::int64_t>& first_vertex,
                           const EdgeKeys& keys)
{
  const std::size_t block = keys.owner_of(key);
  const auto at = std::lower_bound(active.begin(), active.end(), block);
  if (at == active.end() || *at != block)
  {
    return -1;
  }
  const std::size_t owner = static_cast<std::size_t>(at - active.begin());
  const auto& sorted = owned[owner];
  const auto found =
    std::lower_bound(sorted.begin(), sorted.end(), std::pair<std::uint64_t, std::uint32_t>(key, 0));
  if (found == sorted.end() || found->first != key)
  {
    return -1;
  }
  return first_vertex[owner] + std::int64_t(found->second);
}

/// The blocks' outputs joined into one mesh, vertices numbered block by block and foreign
/// references resolved; false when some foreign vertex was made by no block.
bool join_blocks(ContouredBlocks& blocks, const EdgeKeys& keys, const ParallelFor& parallel_for,
                 ContourMesh& mesh)
{
  const std::vector<std::size_t>& active = blocks.active;
  std::vector<BlockOutput>& outputs = blocks.outputs;
  const std::size_t active_count = active.size();
  std::vector<std::int64_t> first_vertex(active_count + 1, 0), first_triangle(active_count + 1, 0);
  for (std::size_t b = 0; b < active_count; ++b)
  {
    first_vertex[b + 1] = first_vertex[b] + std::int64_t(outputs[b].vertices.size());
    first_triangle[b + 1] = first_triangle[b] + std::int64_t(outputs[b].triangles.size());
  }
  const OwnedKeys owned = sorted_owned_keys(outputs, parallel_for);
  // Room for twice as many again, which refinements fill in place (pages left unused are not
  // committed): otherwise their splits would copy the whole mesh. (3wip refined from the
  // coarsest lattice to 0.1 Å has 2.4 times the lattice's vertices.)
  mesh.vertices.reserve(3 * std::size_t(first_vertex[active_count]));
  mesh.triangles.reserve(9 * std::size_t(first_triangle[active_count]));
  mesh.vertices.resize(std::size_t(first_vertex[active_count]));
  mesh.triangles.resize(3 * std::size_t(first_triangle[active_count]));
  // Signs at lattice points do not depend on the block asking, so every cell holding a crossed
  // edge is contoured and each foreign vertex has been made by its owner.
  std::vector<char> complete(active_count, 1);
  run_parallel(parallel_for, active_count, [&](std::size_t begin, std::size_t end) {
    for (std::size_t b = begin; b < end; ++b)
    {
      BlockOutput& out = outputs[b];
      std::copy(out.vertices.begin(), out.vertices.end(), mesh.vertices.begin() + first_vertex[b]);
      std::vector<std::int64_t> foreign(out.foreign_keys.size());
      for (std::size_t k = 0; k < foreign.size(); ++k)
      {
        foreign[k] = global_vertex(out.foreign_keys[k], active, owned, first_vertex, keys);
        complete[b] = complete[b] && foreign[k] >= 0;
      }
      std::int64_t* corner = mesh.triangles.data() + 3 * first_triangle[b];
      for (const auto& triangle : out.triangles)
      {
        for (const std::uint32_t v : triangle)
        {
          *corner++ =
            (v & foreign_bit) ? foreign[v & ~foreign_bit] : first_vertex[b] + std::int64_t(v);
        }
      }
      out = {};
    }
  });
  return std::find(complete.begin(), complete.end(), 0) == complete.end();
}
} // namespace

ContourGrid::ContourGrid(const Vec& low_corner, const Vec& high, double grid_spacing)
  : low(low_corner)
  , spacing(grid_spacing)
{
  for (int a = 0; a < 3; ++a)
  {
    this->cells[a] = std::max<std::int64_t>(
      1, static_cast<std::int64_t>(std::ceil((high[a] - low_corner[a]) / grid_spacing)));
    this->blocks[a] = (this->cells[a] + block_cells - 1) / block_cells;
  }
}

ContourGrid ContourGrid::centred() const
{
  ContourGrid grid = *this;
  grid.low = this->low - Vec::Constant(0.5 * this->spacing);
  return grid;
}

std::array<std::int64_t, 3> ContourGrid::block_first(std::size_t block) const
{
  const std::int64_t b = static_cast<std::int64_t>(block);
  return { block_cells * (b % this->blocks[0]),
           block_cells * ((b / this->blocks[0]) % this->blocks[1]),
           block_cells * (b / (this->blocks[0] * this->blocks[1])) };
}

bool ContourGrid::blocks_meeting(const Vec& from, const Vec& to, std::array<std::int64_t, 3>& first,
                                 std::array<std::int64_t, 3>& last) const
{
  for (int a = 0; a < 3; ++a)
  {
    // Block b holds the points block_cells b .. block_cells (b + 1), and those of the centred
    // grid half a spacing lower.
    const double lower = (from[a] - this->low[a]) / (this->spacing * block_cells);
    const double upper =
      (to[a] + 0.5 * this->spacing - this->low[a]) / (this->spacing * block_cells);
    first[a] = std::max<std::int64_t>(0, static_cast<std::int64_t>(std::ceil(lower - 1.0)));
    last[a] =
      std::min<std::int64_t>(this->blocks[a] - 1, static_cast<std::int64_t>(std::floor(upper)));
    if (first[a] > last[a])
    {
      return false;
    }
  }
  return true;
}

bool ContourGrid::points_within(std::size_t block, const Vec& from, const Vec& to,
                                std::array<int, 3>& first, std::array<int, 3>& last) const
{
  const auto origin = this->block_first(block);
  for (int a = 0; a < 3; ++a)
  {
    const double base = this->low[a] + this->spacing * double(origin[a]);
    // Clamped to the block before rounding (far boxes would overflow an int).
    const double lower = std::clamp((from[a] - base) / this->spacing, -1.0, block_cells + 1.0);
    const double upper = std::clamp((to[a] - base) / this->spacing, -1.0, block_cells + 1.0);
    first[a] = std::max(0, ceil_to_int(lower));
    last[a] = std::min(block_cells, floor_to_int(upper));
    if (first[a] > last[a])
    {
      return false;
    }
  }
  return true;
}

ContourMesh contour_tetrahedra(ContourField& field, const Vec& low, const Vec& high, double spacing,
                               const ParallelFor& parallel_for,
                               const std::function<void(double)>& progress)
{
  const ContourGrid grid(low, high, spacing);
  const EdgeKeys keys(grid);
  field.prepare(grid, parallel_for);
  ContouredBlocks blocks = contour_blocks(field, grid, keys, parallel_for, progress);
  ContourMesh mesh;
  const bool complete = join_blocks(blocks, keys, parallel_for, mesh);
  if (blocks.one_sided || !complete)
  {
    // A defect of the field, not of the input; an error the caller reports rather than a
    // crash of the application around it.
    throw SolverFailure("the molecular surface's contour is inconsistent: a field gave a lattice "
                        "point different signs in different blocks, or a zero in one grid of a "
                        "block and not the other; please report the input");
  }
  return mesh;
}

} // namespace mesolens
