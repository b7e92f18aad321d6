// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/membrane_mapping.h"

#include "mesolens/errors.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

namespace mesolens {

namespace {
/// Where the patch and its tiles lie in (u, v).
struct TileLayout
{
  const MembranePatch& patch;
  const MappingParams& params;
  std::array<double, 4> inverse{}; // inverse of the cell matrix [a b] (column-major)

  TileLayout(const MembranePatch& p, const MappingParams& m)
    : patch(p)
    , params(m)
  {
    const double determinant = p.a[0] * p.b[1] - p.a[1] * p.b[0];
    if (!(std::abs(determinant) > 0) || !std::isfinite(determinant))
    {
      throw InvalidInput("the membrane patch's cell vectors a and b are parallel or zero; the "
                         "patch needs a periodic box to be tiled");
    }
    this->inverse = { p.b[1] / determinant, -p.a[1] / determinant, -p.b[0] / determinant,
                      p.a[0] / determinant };
  }

  /// (u, v) of patch point (x, y) in tile (i, j).
  std::array<double, 2> uv(double x, double y, int i, int j) const
  {
    const double k = this->params.tiles;
    const double shift_a = i - k / 2;
    const double shift_b = j - k / 2;
    const double qx =
      x - this->patch.origin[0] + shift_a * this->patch.a[0] + shift_b * this->patch.b[0];
    const double qy =
      y - this->patch.origin[1] + shift_a * this->patch.a[1] + shift_b * this->patch.b[1];
    return { this->params.centre_uv[0] + this->params.scale * qx,
             this->params.centre_uv[1] + this->params.scale * qy };
  }

  /// Patch point (x, y) at local polynomial coordinates (s, t) of a tile.
  std::array<double, 2> patch_point(double s, double t) const
  {
    const double fa = (s + 1) / 2;
    const double fb = (t + 1) / 2;
    return { this->patch.origin[0] + fa * this->patch.a[0] + fb * this->patch.b[0],
             this->patch.origin[1] + fa * this->patch.a[1] + fb * this->patch.b[1] };
  }
};

std::string outside_message(std::size_t atom, int i, int j, const std::array<double, 2>& uv)
{
  return "atom " + std::to_string(atom) + " of tile (" + std::to_string(i) + ", " +
    std::to_string(j) + ") maps to (u, v) = (" + std::to_string(uv[0]) + ", " +
    std::to_string(uv[1]) +
    "), outside the geodesic disk; grow the disk (radius = twice the "
    "tiled width) or use fewer tiles";
}

/// The displacement map: surface point at (u, v) pushed along the normal by w (mesh units).
bool displaced(const SurfaceChart& chart, const std::array<double, 2>& uv, double w,
               std::array<double, 3>& out, SurfaceFrame& frame)
{
  if (!chart.frame(uv[0], uv[1], frame))
  {
    return false;
  }
  for (int d = 0; d < 3; ++d)
  {
    out[std::size_t(d)] = frame.position[std::size_t(d)] + w * frame.normal[std::size_t(d)];
  }
  return true;
}

void check_params(const MembranePatch& patch, const MappingParams& params)
{
  if (params.tiles < 1)
  {
    throw InvalidInput("the number of tiles per side must be at least 1, got " +
                       std::to_string(params.tiles));
  }
  if (!(params.scale > 0) || !std::isfinite(params.scale))
  {
    throw InvalidInput("the membrane-to-mesh scale must be positive and finite");
  }
  if (!(params.layer_half_thickness > 0) || params.samples < 3)
  {
    throw InvalidInput(
      "the polynomial fit needs a positive layer thickness and at least 3 samples per edge");
  }
  if (!std::isfinite(params.centre_uv[0]) || !std::isfinite(params.centre_uv[1]) ||
      !std::isfinite(patch.centre_height))
  {
    throw InvalidInput("the mapping centre is not finite");
  }
  if (patch.atom_count > 0 && !patch.positions)
  {
    throw InvalidInput("the membrane patch has no positions");
  }
  for (std::size_t i = 0; i < 3 * patch.atom_count; ++i)
  {
    if (!std::isfinite(patch.positions[i]))
    {
      throw InvalidInput("membrane atom " + std::to_string(i / 3) + " has a non-finite coordinate");
    }
  }
}

/// Atoms of each molecule, and their centres (mass-weighted when masses are given).
struct Molecules
{
  std::vector<int> ids;
  std::vector<std::vector<std::uint32_t>> atoms;
  std::vector<std::array<double, 3>> centres;
};

Molecules group_molecules(const MembranePatch& patch)
{
  if (!patch.molecule_ids)
  {
    throw InvalidInput(
      "molecule instancing needs molecule ids (the MoleculeId array of a MesoLens reader)");
  }
  std::map<int, std::size_t> index_of;
  Molecules molecules;
  for (std::uint32_t i = 0; i < patch.atom_count; ++i)
  {
    const int id = patch.molecule_ids[i];
    if (id < 0)
    {
      throw InvalidInput("membrane atom " + std::to_string(i) + " has a negative molecule id");
    }
    const auto found = index_of.emplace(id, molecules.ids.size());
    if (found.second)
    {
      molecules.ids.push_back(id);
      molecules.atoms.emplace_back();
    }
    molecules.atoms[found.first->second].push_back(i);
  }
  for (const auto& atoms : molecules.atoms)
  {
    std::array<double, 3> centre{ 0, 0, 0 };
    double total = 0;
    for (const std::uint32_t i : atoms)
    {
      const double m = patch.masses ? double(patch.masses[i]) : 1.0;
      for (int d = 0; d < 3; ++d)
      {
        centre[std::size_t(d)] += m * patch.positions[3 * i + std::size_t(d)];
      }
      total += m;
    }
    for (double& c : centre)
    {
      c /= total > 0 ? total : 1.0;
    }
    molecules.centres.push_back(centre);
  }
  return molecules;
}
} // namespace

std::array<double, 3> polynomial_coordinates(const MembranePatch& patch,
                                             double layer_half_thickness, const float* position)
{
  const double qx = position[0] - patch.origin[0];
  const double qy = position[1] - patch.origin[1];
  const double determinant = patch.a[0] * patch.b[1] - patch.a[1] * patch.b[0];
  const double fa = (patch.b[1] * qx - patch.b[0] * qy) / determinant;
  const double fb = (-patch.a[1] * qx + patch.a[0] * qy) / determinant;
  return { 2 * fa - 1, 2 * fb - 1, (position[2] - patch.centre_height) / layer_half_thickness };
}

MappedMembrane map_membrane(const SurfaceChart& chart, const MembranePatch& patch,
                            const MappingParams& params, const ParallelFor& parallel_for)
{
  check_params(patch, params);
  const TileLayout layout(patch, params);
  const int k = params.tiles;
  const std::size_t tile_count = std::size_t(k) * std::size_t(k);
  const std::size_t n = patch.atom_count;
  MappedMembrane mapped;
  const bool map_atoms = params.map_atoms || params.method == MappingMethod::Displacement;
  if (map_atoms)
  {
    mapped.positions.resize(3 * n * tile_count);
  }
  std::vector<std::string> failures(tile_count);
  const double scale = params.scale;

  Molecules molecules;
  if (params.method == MappingMethod::MoleculeInstancing)
  {
    molecules = group_molecules(patch);
    mapped.instance_matrices.resize(16 * molecules.ids.size() * tile_count);
    mapped.instance_molecules.resize(molecules.ids.size() * tile_count);
    mapped.instance_tiles.resize(molecules.ids.size() * tile_count);
  }
  if (params.method == MappingMethod::Polynomial)
  {
    mapped.polynomial_coefficients.resize(3 * quadratic_terms * tile_count);
    mapped.polynomial_rms_residual.resize(tile_count);
    mapped.polynomial_max_residual.resize(tile_count);
  }

  const std::vector<std::uint32_t> no_atoms;
  auto map_tile = [&](std::size_t tile) {
    const int i = int(tile % std::size_t(k));
    const int j = int(tile / std::size_t(k));
    double* out = map_atoms ? mapped.positions.data() + 3 * n * tile : nullptr;
    SurfaceFrame frame;
    std::array<double, 3> x{};
    switch (params.method)
    {
      case MappingMethod::Displacement:
        for (std::size_t a = 0; a < n; ++a)
        {
          const float* p = patch.positions + 3 * a;
          const auto uv = layout.uv(p[0], p[1], i, j);
          if (!displaced(chart, uv, scale * (p[2] - patch.centre_height), x, frame))
          {
            failures[tile] = outside_message(a, i, j, uv);
            return;
          }
          for (int d = 0; d < 3; ++d)
          {
            out[3 * a + std::size_t(d)] = x[std::size_t(d)];
          }
        }
        break;
      case MappingMethod::MoleculeInstancing:
        for (std::size_t m = 0; m < molecules.ids.size(); ++m)
        {
          const auto& c = molecules.centres[m];
          const auto uv = layout.uv(c[0], c[1], i, j);
          if (!displaced(chart, uv, scale * (c[2] - patch.centre_height), x, frame))
          {
            failures[tile] = outside_message(molecules.atoms[m].front(), i, j, uv);
            return;
          }
          // Rows of R: patch x -> tangent_u, y -> tangent_v, z -> normal (columns of R).
          const std::array<std::array<double, 3>, 3> axes{ frame.tangent_u, frame.tangent_v,
                                                           frame.normal };
          const std::size_t instance = tile * molecules.ids.size() + m;
          double* matrix = mapped.instance_matrices.data() + 16 * instance;
          for (int r = 0; r < 3; ++r)
          {
            double translation = x[std::size_t(r)];
            for (int col = 0; col < 3; ++col)
            {
              const double rotation = scale * axes[std::size_t(col)][std::size_t(r)];
              matrix[4 * r + col] = rotation;
              translation -= rotation * c[std::size_t(col)];
            }
            matrix[4 * r + 3] = translation;
          }
          matrix[12] = matrix[13] = matrix[14] = 0;
          matrix[15] = 1;
          mapped.instance_molecules[instance] = molecules.ids[m];
          mapped.instance_tiles[instance] = int(tile);
          for (const std::uint32_t a : map_atoms ? molecules.atoms[m] : no_atoms)
          {
            const float* p = patch.positions + 3 * a;
            for (int r = 0; r < 3; ++r)
            {
              out[3 * a + std::size_t(r)] = matrix[4 * r] * p[0] + matrix[4 * r + 1] * p[1] +
                matrix[4 * r + 2] * p[2] + matrix[4 * r + 3];
            }
          }
        }
        break;
      case MappingMethod::Polynomial: {
        std::vector<std::array<double, 3>> parameters;
        std::vector<std::array<double, 3>> targets;
        const int samples = params.samples;
        for (int layer = -1; layer <= 1; ++layer)
        {
          for (int sj = 0; sj < samples; ++sj)
          {
            for (int si = 0; si < samples; ++si)
            {
              const double s = -1 + 2.0 * si / (samples - 1);
              const double t = -1 + 2.0 * sj / (samples - 1);
              const auto q = layout.patch_point(s, t);
              const auto uv = layout.uv(q[0], q[1], i, j);
              if (!displaced(chart, uv, scale * layer * params.layer_half_thickness, x, frame))
              {
                failures[tile] = "the polynomial samples of tile (" + std::to_string(i) + ", " +
                  std::to_string(j) + ") leave the geodesic disk at (u, v) = (" +
                  std::to_string(uv[0]) + ", " + std::to_string(uv[1]) + "); grow the disk";
                return;
              }
              parameters.push_back({ s, t, double(layer) });
              targets.push_back(x);
            }
          }
        }
        const QuadraticFit fit = fit_quadratic(parameters, targets);
        std::copy(fit.warp.begin(), fit.warp.end(),
                  mapped.polynomial_coefficients.begin() + long(3 * quadratic_terms * tile));
        mapped.polynomial_rms_residual[tile] = fit.rms_residual;
        mapped.polynomial_max_residual[tile] = fit.max_residual;
        for (std::size_t a = 0; map_atoms && a < n; ++a)
        {
          const auto local =
            polynomial_coordinates(patch, params.layer_half_thickness, patch.positions + 3 * a);
          const auto y = evaluate_quadratic(fit.warp, local[0], local[1], local[2]);
          for (int d = 0; d < 3; ++d)
          {
            out[3 * a + std::size_t(d)] = y[std::size_t(d)];
          }
        }
        break;
      }
    }
  };
  run_parallel(parallel_for, tile_count, [&](std::size_t begin, std::size_t end) {
    for (std::size_t tile = begin; tile < end; ++tile)
    {
      map_tile(tile);
    }
  });
  for (const std::string& failure : failures)
  {
    if (!failure.empty())
    {
      throw InvalidInput(failure);
    }
  }
  return mapped;
}

std::vector<double> bond_length_changes(const MembranePatch& patch, const MappedMembrane& mapped,
                                        const std::vector<std::array<std::uint32_t, 2>>& bonds,
                                        double scale)
{
  const std::size_t n = patch.atom_count;
  const std::size_t tiles = n == 0 ? 0 : mapped.positions.size() / (3 * n);
  std::vector<double> changes(tiles * bonds.size());
  auto length = [](const auto* p, const auto* q) {
    return std::sqrt((double(p[0]) - q[0]) * (double(p[0]) - q[0]) +
                     (double(p[1]) - q[1]) * (double(p[1]) - q[1]) +
                     (double(p[2]) - q[2]) * (double(p[2]) - q[2]));
  };
  for (std::size_t t = 0; t < tiles; ++t)
  {
    const double* tile = mapped.positions.data() + 3 * n * t;
    for (std::size_t b = 0; b < bonds.size(); ++b)
    {
      const auto [i, j] = bonds[b];
      if (i >= n || j >= n)
      {
        throw InvalidInput("bond " + std::to_string(b) + " names an atom outside the patch");
      }
      const double original = scale * length(patch.positions + 3 * i, patch.positions + 3 * j);
      changes[t * bonds.size() + b] =
        original > 0 ? length(tile + 3 * i, tile + 3 * j) / original - 1 : 0.0;
    }
  }
  return changes;
}

} // namespace mesolens
