// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/mapping/membrane_warp.h"

#include "mesolens/common/errors.h"
#include "mesolens/mapping/membrane_mapper.h"

#include <array>
#include <cmath>
#include <string>
#include <utility>

namespace mesolens {

MembranePatch MembraneWarp::frame() const
{
  MembranePatch patch;
  patch.origin = this->origin;
  patch.a = this->a;
  patch.b = this->b;
  patch.centre_height = this->centre_height;
  return patch;
}

namespace {
/// The warp's patch frame, tiling and place on the surface: everything but the method's arrays.
MembraneWarp warp_without_arrays(const MapResult& result, const MembranePatch& patch,
                                 const MapRequest& request)
{
  MembraneWarp warp;
  const MappingParams& params = request.mapping;
  warp.method = params.method;
  warp.tiles = result.tiles_mapped;
  warp.tiles_requested = result.tiles_asked;
  warp.cut_to_disk = result.cut_to_disk;
  warp.note = result.note;
  warp.scale = params.scale;
  warp.origin = patch.origin;
  warp.a = patch.a;
  warp.b = patch.b;
  warp.centre_height = patch.centre_height;
  warp.layer_half_thickness = params.layer_half_thickness;
  if (result.chart)
  {
    warp.geodesic_radius = result.chart->radius;
    warp.seed_uv = result.chart->seed_uv;
    warp.refinement_levels = result.chart->disk.refinement_levels;
    SurfaceFrame frame;
    if (result.chart->chart.frame(warp.seed_uv[0], warp.seed_uv[1], frame))
    {
      warp.seed_normal = frame.normal;
    }
  }
  return warp;
}

/// The method's arrays of `mapped`, copied from an lvalue, moved from an rvalue.
template<typename Mapped>
void take_arrays(Mapped&& mapped, MembraneWarp& warp)
{
  warp.polynomial_coefficients = std::forward<Mapped>(mapped).polynomial_coefficients;
  warp.polynomial_splits = std::forward<Mapped>(mapped).polynomial_splits;
  warp.polynomial_rms_residual = std::forward<Mapped>(mapped).polynomial_rms_residual;
  warp.polynomial_max_residual = std::forward<Mapped>(mapped).polynomial_max_residual;
  warp.tile_fallback = std::forward<Mapped>(mapped).tile_fallback;
  warp.instance_matrices = std::forward<Mapped>(mapped).instance_matrices;
  warp.instance_molecules = std::forward<Mapped>(mapped).instance_molecules;
  warp.instance_tiles = std::forward<Mapped>(mapped).instance_tiles;
}
} // namespace

MembraneWarp membrane_warp(const MapResult& result, const MembranePatch& patch,
                           const MapRequest& request)
{
  MembraneWarp warp = warp_without_arrays(result, patch, request);
  take_arrays(result.mapped, warp);
  return warp;
}

MembraneWarp membrane_warp(MapResult&& result, const MembranePatch& patch,
                           const MapRequest& request)
{
  MembraneWarp warp = warp_without_arrays(result, patch, request);
  take_arrays(std::move(result.mapped), warp);
  return warp;
}

std::vector<std::size_t> polynomial_first_pieces(const MembraneWarp& warp)
{
  const std::size_t tiles = warp.tile_count();
  const bool split = !warp.polynomial_splits.empty();
  if (split && warp.polynomial_splits.size() != tiles)
  {
    throw InvalidInput("the polynomial warp has pieces per side for " +
                       std::to_string(warp.polynomial_splits.size()) + " tiles, not " +
                       std::to_string(tiles));
  }
  std::vector<std::size_t> first(tiles + 1, 0);
  for (std::size_t t = 0; t < tiles; ++t)
  {
    const int m = split ? warp.polynomial_splits[t] : 1;
    if (m < 1 || m > 64)
    {
      throw InvalidInput("tile " + std::to_string(t) + " of the polynomial warp has " +
                         std::to_string(m) + " pieces per side (1 to 64)");
    }
    first[t + 1] = first[t] + std::size_t(m) * std::size_t(m);
  }
  if (warp.polynomial_coefficients.size() != 30 * first.back())
  {
    throw InvalidInput("the polynomial coefficients should hold 30 values for each piece of the " +
                       std::to_string(tiles) + " tiles (" + std::to_string(first.back()) +
                       " pieces), not " + std::to_string(warp.polynomial_coefficients.size()));
  }
  return first;
}

std::size_t molecules_per_tile(const MembraneWarp& warp)
{
  std::size_t count = 0;
  while (count < warp.instance_tiles.size() && warp.instance_tiles[count] == 0)
  {
    ++count;
  }
  return count;
}

void check_drawable(const MembraneWarp& warp)
{
  if (warp.tile_count() < 1)
  {
    throw InvalidInput("the warp has no tiles");
  }
  if (!(warp.layer_half_thickness > 0))
  {
    throw InvalidInput("the warp's layer half thickness is not positive");
  }
  if (warp.cut_to_disk)
  {
    throw InvalidInput("the mapping cut its one tile to the disk (molecules outside it are "
                       "dropped); draw its mapped atoms instead");
  }
  const double determinant = warp.a[0] * warp.b[1] - warp.a[1] * warp.b[0];
  if (!(std::abs(determinant) > 0))
  {
    throw InvalidInput("the patch cell is degenerate");
  }
  switch (warp.method)
  {
    case MappingMethod::Polynomial:
      polynomial_first_pieces(warp);
      return;
    case MappingMethod::MoleculeInstancing: {
      const std::size_t instances = warp.tile_count() * molecules_per_tile(warp);
      if (warp.instance_molecules.size() != instances || warp.instance_tiles.size() != instances ||
          warp.instance_matrices.size() != 16 * instances || instances == 0)
      {
        throw InvalidInput("the instancing warp should hold " + std::to_string(instances) +
                           " molecule motions (" + std::to_string(molecules_per_tile(warp)) +
                           " per tile), with a molecule and a tile for each");
      }
      return;
    }
    case MappingMethod::Displacement:
      break;
  }
  throw InvalidInput("a DISPLACEMENT mapping has no warp of the patch to draw: only POLYNOMIAL "
                     "and MOLECULE_INSTANCING do (draw the DISPLACEMENT output directly)");
}

std::vector<double> warped_molecule_centres(const MembraneWarp& warp, const MembranePatch& patch,
                                            const MoleculeGroups& groups,
                                            const ParallelFor& parallel_for)
{
  check_drawable(warp);
  const std::size_t molecules = groups.count();
  if (groups.of_atom.size() != patch.atom_count())
  {
    throw InvalidInput("warped_molecule_centres: the groups hold " +
                       std::to_string(groups.of_atom.size()) + " atoms, the patch " +
                       std::to_string(patch.atom_count()));
  }
  const bool polynomial = warp.method == MappingMethod::Polynomial;
  if (!polynomial && molecules_per_tile(warp) != molecules)
  {
    throw InvalidInput("warped_molecule_centres: the warp moves " +
                       std::to_string(molecules_per_tile(warp)) +
                       " molecules per tile, the patch has " + std::to_string(molecules));
  }
  const std::vector<std::size_t> first =
    polynomial ? polynomial_first_pieces(warp) : std::vector<std::size_t>{};
  const std::size_t tiles = warp.tile_count();
  std::vector<double> centres(3 * tiles * molecules);
  run_parallel(parallel_for, tiles, [&](std::size_t begin, std::size_t end) {
    for (std::size_t tile = begin; tile < end; ++tile)
    {
      const int splits =
        polynomial && !warp.polynomial_splits.empty() ? warp.polynomial_splits[tile] : 1;
      for (std::size_t m = 0; m < molecules; ++m)
      {
        // As MoleculeMapper and molecule_centres: each atom warped in double, summed in the
        // molecule's atom order, divided by the count.
        const double* matrix =
          polynomial ? nullptr : warp.instance_matrices.data() + 16 * (tile * molecules + m);
        double sum[3] = { 0, 0, 0 };
        double total = 0;
        for (const std::uint32_t a : groups.atoms_of(m))
        {
          const float* p = patch.positions[a];
          std::array<double, 3> x{};
          if (polynomial)
          {
            x = evaluate_tile_polynomial(patch, warp.layer_half_thickness, splits,
                                         warp.polynomial_coefficients.data() + 30 * first[tile], p);
          }
          else
          {
            for (std::size_t r = 0; r < 3; ++r)
            {
              x[r] = matrix[4 * r] * p[0] + matrix[4 * r + 1] * p[1] + matrix[4 * r + 2] * p[2] +
                matrix[4 * r + 3];
            }
          }
          for (std::size_t d = 0; d < 3; ++d)
          {
            sum[d] += x[d];
          }
          total += 1;
        }
        for (std::size_t d = 0; d < 3; ++d)
        {
          centres[3 * (tile * molecules + m) + d] = sum[d] / total;
        }
      }
    }
  });
  return centres;
}

} // namespace mesolens
