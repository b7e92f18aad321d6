// SPDX-License-Identifier: GPL-3.0-or-later
#include <Eigen/Dense>

#include "contour_tetrahedra.h"

#include "balanced_loop.h"
#include "grid_cells.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace mesolens {

namespace {
using Vec = Eigen::Vector3d;
/// Cells per block edge: the unit of parallel work and the root of its octree. Larger blocks
/// gather their boundary pieces less often; much larger ones leave threads idle at the end.
constexpr int block_cells = 16;

/// Kuhn's six tetrahedra of the unit cube, corners as bit masks (x 1, y 2, z 4), each ordered
/// so that its orientation is positive.
std::array<std::array<int, 4>, 6> kuhn_tetrahedra()
{
  const int axes[6][3] = { { 1, 2, 4 }, { 1, 4, 2 }, { 2, 1, 4 },
                           { 2, 4, 1 }, { 4, 1, 2 }, { 4, 2, 1 } };
  std::array<std::array<int, 4>, 6> tets{};
  for (int t = 0; t < 6; ++t)
  {
    std::array<int, 4> tet = { 0, axes[t][0], axes[t][0] | axes[t][1], 7 };
    const auto corner = [](int mask) {
      return Vec(mask & 1 ? 1 : 0, mask & 2 ? 1 : 0, mask & 4 ? 1 : 0);
    };
    const Vec a = corner(tet[0]);
    const double det = (corner(tet[1]) - a).cross(corner(tet[2]) - a).dot(corner(tet[3]) - a);
    if (det < 0)
    {
      std::swap(tet[2], tet[3]);
    }
    tets[t] = tet;
  }
  return tets;
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
/// its triangles, as indices into those.
struct BlockOutput
{
  std::vector<ContourVertex> vertices;
  std::vector<std::uint64_t> keys;
  std::vector<std::uint64_t> foreign_keys;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};
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
    // Block b holds the points block_cells b .. block_cells (b + 1).
    const double lower = (from[a] - this->low[a]) / (this->spacing * block_cells);
    const double upper = (to[a] - this->low[a]) / (this->spacing * block_cells);
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
  ContourMesh mesh;
  const ContourGrid grid(low, high, spacing);
  const auto& cells = grid.cells;
  const auto& blocks = grid.blocks;
  constexpr int block_cells = ContourGrid::block_cells;
  const std::array<std::int64_t, 3> points = { cells[0] + 1, cells[1] + 1, cells[2] + 1 };
  const std::size_t block_count = grid.block_count();
  const auto tets = kuhn_tetrahedra();
  const auto point_key = [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    return static_cast<std::uint64_t>(x + points[0] * (y + points[1] * z));
  };
  // The block owning a grid point (points on the far faces belong to the last blocks).
  const auto owner_of = [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    const std::int64_t bx = std::min(x / block_cells, blocks[0] - 1);
    const std::int64_t by = std::min(y / block_cells, blocks[1] - 1);
    const std::int64_t bz = std::min(z / block_cells, blocks[2] - 1);
    return static_cast<std::size_t>(bx + blocks[0] * (by + blocks[1] * bz));
  };
  const auto key_point = [&](std::uint64_t key) {
    const std::uint64_t point = key / 8;
    return std::array<std::int64_t, 3>{
      static_cast<std::int64_t>(point % std::uint64_t(points[0])),
      static_cast<std::int64_t>((point / std::uint64_t(points[0])) % std::uint64_t(points[1])),
      static_cast<std::int64_t>(point / std::uint64_t(points[0] * points[1]))
    };
  };

  field.prepare(grid, parallel_for);
  // The blocks that made triangles, in increasing order, with what they made: far fewer than
  // the grid's blocks where the molecule is sparse (every block's output would take gigabytes
  // for atoms thousands of Å apart).
  std::vector<std::size_t> active;
  std::vector<BlockOutput> outputs;
  // What a thread reuses from block to block: the field's local view and the block's tables.
  struct BlockBuffers
  {
    std::unique_ptr<LocalContourField> local;
    std::vector<double> values;
    std::vector<std::uint32_t> hints;
    /// Per block point and Kuhn direction (1 to 7), the block that made the vertex on that edge
    /// (its number plus one, in the high half) and the vertex's index: entries of earlier blocks
    /// are stale, so the table is never cleared.
    std::vector<std::uint64_t> made;
  };
  constexpr int side = ContourGrid::block_points;
  const auto run_block = [&](std::size_t block, BlockOutput& out, BlockBuffers& buffers) {
    if (!buffers.local)
    {
      buffers.local = field.local();
      buffers.values.resize(side * side * side);
      buffers.hints.resize(side * side * side);
      buffers.made.assign(std::size_t(side * side * side * 8), 0);
    }
    LocalContourField* const local = buffers.local.get();
    if (!local->sample_block(grid, block, buffers.values.data(), buffers.hints.data()))
    {
      return;
    }
    const auto first = grid.block_first(block);
    const std::int64_t x0 = first[0], y0 = first[1], z0 = first[2];
    const double* const values = buffers.values.data();
    const std::uint32_t* const hints = buffers.hints.data();
    const auto sample_at = [&](std::int64_t x, std::int64_t y, std::int64_t z) {
      const std::size_t at = std::size_t((x - x0) + side * ((y - y0) + side * (z - z0)));
      return LocalContourField::Sample{ grid.point(x, y, z), values[at], hints[at] };
    };
    std::vector<std::uint64_t>& made = buffers.made;
    const std::uint64_t stamp = std::uint64_t(block + 1) << 32;
    const auto contour_cell = [&](const std::array<std::int64_t, 3>& cell) {
      std::array<LocalContourField::Sample, 8> corner;
      for (int m = 0; m < 8; ++m)
      {
        corner[m] =
          sample_at(cell[0] + (m & 1), cell[1] + ((m >> 1) & 1), cell[2] + ((m >> 2) & 1));
      }
      const auto edge = [&](int a, int b) {
        // Kuhn edges join a corner to one whose bits include its own: key by the lower corner
        // and the offset.
        const int from = std::min(a, b), to = std::max(a, b);
        const std::int64_t x = cell[0] + (from & 1), y = cell[1] + ((from >> 1) & 1),
                           z = cell[2] + ((from >> 2) & 1);
        std::uint64_t& entry =
          made[std::size_t(8 * ((x - x0) + side * ((y - y0) + side * (z - z0))) + (to ^ from))];
        if ((entry & ~std::uint64_t(0xffffffffu)) != stamp)
        {
          std::uint32_t index = 0;
          const std::uint64_t key = point_key(x, y, z) * 8 + std::uint64_t(to ^ from);
          if (owner_of(x, y, z) == block)
          {
            const int outside = corner[a].value > 0 ? b : a;
            const int inside = corner[a].value > 0 ? a : b;
            index = static_cast<std::uint32_t>(out.vertices.size());
            out.vertices.push_back(local->vertex(corner[outside], corner[inside], corner.data()));
            out.keys.push_back(key);
          }
          else
          {
            // The owner computes it: every cell holding a crossed edge is contoured, as the
            // signs at grid points do not depend on the block asking.
            index = static_cast<std::uint32_t>(out.foreign_keys.size()) | foreign_bit;
            out.foreign_keys.push_back(key);
          }
          entry = stamp | index;
        }
        return static_cast<std::uint32_t>(entry);
      };
      for (const auto& tet : tets)
      {
        int inside_mask = 0, inside_count = 0;
        for (int k = 0; k < 4; ++k)
        {
          if (corner[tet[k]].value > 0)
          {
            inside_mask |= 1 << k;
            ++inside_count;
          }
        }
        if (inside_count == 0 || inside_count == 4)
        {
          continue;
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
          const int a = tet[order[0]], b = tet[order[1]], c = tet[order[2]], d = tet[order[3]];
          if (inside_count == 1)
          {
            out.triangles.push_back({ edge(a, b), edge(a, c), edge(a, d) });
          }
          else
          {
            out.triangles.push_back({ edge(a, b), edge(a, d), edge(a, c) });
          }
          continue;
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
        const int a = tet[order[0]], b = tet[order[1]], c = tet[order[2]], d = tet[order[3]];
        const std::uint32_t ac = edge(a, c), ad = edge(a, d), bd = edge(b, d), bc = edge(b, c);
        out.triangles.push_back({ ac, ad, bd });
        out.triangles.push_back({ ac, bd, bc });
      }
    };
    // The cells whose corners change sign.
    const std::int64_t x1 = std::min(x0 + block_cells, cells[0]);
    const std::int64_t y1 = std::min(y0 + block_cells, cells[1]);
    const std::int64_t z1 = std::min(z0 + block_cells, cells[2]);
    for (std::int64_t z = z0; z < z1; ++z)
      for (std::int64_t y = y0; y < y1; ++y)
        for (std::int64_t x = x0; x < x1; ++x)
        {
          const double* corner = values + ((x - x0) + side * ((y - y0) + side * (z - z0)));
          int inside = 0;
          for (const std::ptrdiff_t offset : { 0, 1, side, side + 1, side * side, side * side + 1,
                                               side * side + side, side * side + side + 1 })
          {
            inside += corner[offset] > 0 ? 1 : 0;
          }
          if (inside != 0 && inside != 8)
          {
            contour_cell({ x, y, z });
          }
        }
  };

  // Blocks in rounds, so progress is reported from this thread.
  const std::size_t round = 256;
  std::vector<BlockOutput> round_outputs(round);
  for (std::size_t first = 0; first < block_count; first += round)
  {
    const std::size_t count = std::min(round, block_count - first);
    // Blocks the surface crosses cost far more than the others: taken one at a time.
    run_balanced<BlockBuffers>(parallel_for, count, [&](std::size_t k, BlockBuffers& buffers) {
      run_block(first + k, round_outputs[k], buffers);
    });
    for (std::size_t k = 0; k < count; ++k)
    {
      BlockOutput& out = round_outputs[k];
      if (!out.vertices.empty() || !out.triangles.empty() || !out.foreign_keys.empty())
      {
        active.push_back(first + k);
        outputs.push_back(std::move(out));
        out = {};
      }
    }
    if (progress)
    {
      progress(double(first + count) / double(block_count));
    }
  }

  // Vertices numbered block by block; foreign references found in their owners' keys.
  const std::size_t active_count = active.size();
  std::vector<std::int64_t> first_vertex(active_count + 1, 0), first_triangle(active_count + 1, 0);
  for (std::size_t b = 0; b < active_count; ++b)
  {
    first_vertex[b + 1] = first_vertex[b] + std::int64_t(outputs[b].vertices.size());
    first_triangle[b + 1] = first_triangle[b] + std::int64_t(outputs[b].triangles.size());
  }
  std::vector<std::vector<std::pair<std::uint64_t, std::uint32_t>>> owned(active_count);
  run_parallel(parallel_for, active_count, [&](std::size_t begin, std::size_t end) {
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
  const auto global_of = [&](std::uint64_t key) -> std::int64_t {
    const auto point = key_point(key);
    const std::size_t block = owner_of(point[0], point[1], point[2]);
    const auto at = std::lower_bound(active.begin(), active.end(), block);
    if (at == active.end() || *at != block)
    {
      return -1;
    }
    const std::size_t owner = static_cast<std::size_t>(at - active.begin());
    const auto& sorted = owned[owner];
    const auto found = std::lower_bound(sorted.begin(), sorted.end(),
                                        std::pair<std::uint64_t, std::uint32_t>(key, 0));
    if (found == sorted.end() || found->first != key)
    {
      return -1;
    }
    return first_vertex[owner] + std::int64_t(found->second);
  };
  // Room for as many again, which refinements fill in place (pages left unused are not
  // committed): otherwise their first splits would copy the whole mesh.
  mesh.vertices.reserve(2 * std::size_t(first_vertex[active_count]));
  mesh.triangles.reserve(6 * std::size_t(first_triangle[active_count]));
  mesh.vertices.resize(std::size_t(first_vertex[active_count]));
  mesh.triangles.resize(3 * std::size_t(first_triangle[active_count]));
  // Signs at grid points do not depend on the block asking, so every cell holding a crossed
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
        foreign[k] = global_of(out.foreign_keys[k]);
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
  if (std::find(complete.begin(), complete.end(), 0) != complete.end())
  {
    throw std::logic_error("contour_tetrahedra: a field gave a grid point different signs in "
                           "different blocks");
  }
  return mesh;
}

} // namespace mesolens
