// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/mapping/membrane_mapping.h"

#include "mesolens/common/errors.h"
#include "mesolens/molecules/molecule_groups.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
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
  const long long tile_count = static_cast<long long>(params.tiles) * params.tiles;
  const long long end = params.end_atom_tile < 0 ? tile_count : params.end_atom_tile;
  if (params.first_atom_tile < 0 || params.first_atom_tile > end || end > tile_count)
  {
    throw InvalidInput("the atom tiles [" + std::to_string(params.first_atom_tile) + ", " +
                       std::to_string(end) + ") are not within the " + std::to_string(tile_count) +
                       " tiles");
  }
  const int m = params.max_polynomial_splits;
  if (m < 1 || m > 8 || (m & (m - 1)) != 0 || std::isnan(params.max_polynomial_residual))
  {
    throw InvalidInput("max_polynomial_splits must be 1, 2, 4 or 8 and the residual bound a "
                       "number");
  }
  if (!std::isfinite(params.centre_uv[0]) || !std::isfinite(params.centre_uv[1]) ||
      !std::isfinite(patch.centre_height))
  {
    throw InvalidInput("the mapping centre is not finite");
  }
  if (patch.atom_count() > 0 && !patch.positions.data())
  {
    throw InvalidInput("the membrane patch has no positions");
  }
  for (std::size_t i = 0; i < patch.positions.value_count(); ++i)
  {
    if (!std::isfinite(patch.positions.data()[i]))
    {
      throw InvalidInput("membrane atom " + std::to_string(i / 3) + " has a non-finite coordinate");
    }
  }
}

/// The patch's molecules and their centres (of mass, when masses are given). Without molecule
/// ids every atom is its own molecule.
struct PatchMolecules
{
  MoleculeGroups groups;
  std::vector<double> centres; ///< 3 per molecule
};

PatchMolecules patch_molecules(const MembranePatch& patch)
{
  for (std::size_t i = 0; patch.molecule_ids && i < patch.atom_count(); ++i)
  {
    if (patch.molecule_ids[i] < 0)
    {
      throw InvalidInput("membrane atom " + std::to_string(i) + " has a negative molecule id");
    }
  }
  PatchMolecules molecules;
  molecules.groups = group_molecules(patch.molecule_ids, patch.atom_count());
  molecules.centres = molecule_centres(molecules.groups, patch.positions, patch.masses);
  return molecules;
}

constexpr double not_mapped = std::numeric_limits<double>::quiet_NaN();

/// Maps the tiles one at a time; every tile writes only its own slots of the output.
class TileMapper
{
public:
  TileMapper(const SurfaceChart& chart, const MembranePatch& patch, const MappingParams& params,
             MappedMembrane& out)
    : Chart(chart)
    , Patch(patch)
    , Params(params)
    , Layout(patch, params)
    , Out(out)
  {
    this->Failures.resize(std::size_t(params.tiles) * std::size_t(params.tiles));
    this->Samples.resize(this->Failures.size());
    this->TilePieces.resize(this->Failures.size());
    const bool need_molecules =
      params.method == MappingMethod::MoleculeInstancing || params.cut_to_disk;
    if (params.method == MappingMethod::MoleculeInstancing && !patch.molecule_ids)
    {
      throw InvalidInput(
        "molecule instancing needs molecule ids (the MoleculeId array of a MesoLens reader)");
    }
    if (need_molecules)
    {
      this->Molecules = patch_molecules(patch);
    }
  }

  bool MapAtoms = true;
  std::size_t FirstAtomTile = 0; ///< the atom tiles: [FirstAtomTile, EndAtomTile)
  std::size_t EndAtomTile = 0;
  std::vector<std::string> Failures;

  bool maps_atoms_of(std::size_t tile) const
  {
    return this->MapAtoms && tile >= this->FirstAtomTile && tile < this->EndAtomTile;
  }

  /// Where a tile's atoms go in the output (atom tiles only).
  double* atom_block(std::size_t tile)
  {
    return this->Out.positions.data() + 3 * this->Patch.atom_count() * (tile - this->FirstAtomTile);
  }

  /// Molecules of the patch (0 unless instancing or cutting to a disk grouped them).
  std::size_t molecule_count() const
  {
    return this->Molecules.groups.count();
  }

  void displacement(std::size_t tile)
  {
    const int i = int(tile % std::size_t(this->Params.tiles));
    const int j = int(tile / std::size_t(this->Params.tiles));
    const std::size_t n = this->Patch.atom_count();
    double* out = this->atom_block(tile);
    SurfaceFrame frame;
    std::array<double, 3> x{};
    for (std::size_t a = 0; a < n; ++a)
    {
      const float* p = this->Patch.positions[a];
      const auto uv = this->Layout.uv(p[0], p[1], i, j);
      if (!displaced(this->Chart, uv, this->Params.scale * (p[2] - this->Patch.centre_height), x,
                     frame))
      {
        if (!this->Params.cut_to_disk)
        {
          this->Failures[tile] = outside_message(a, i, j, uv);
          return;
        }
        x = { not_mapped, not_mapped, not_mapped };
      }
      std::copy(x.begin(), x.end(), out + 3 * a);
    }
    this->drop_partial_molecules(tile);
  }

  void instancing(std::size_t tile)
  {
    const int i = int(tile % std::size_t(this->Params.tiles));
    const int j = int(tile / std::size_t(this->Params.tiles));
    const std::size_t n = this->Patch.atom_count();
    const double scale = this->Params.scale;
    SurfaceFrame frame;
    std::array<double, 3> x{};
    const MoleculeGroups& groups = this->Molecules.groups;
    for (std::size_t m = 0; m < groups.count(); ++m)
    {
      const double* c = this->Molecules.centres.data() + 3 * m;
      const auto uv = this->Layout.uv(c[0], c[1], i, j);
      const std::size_t instance = tile * groups.count() + m;
      double* matrix = this->Out.instance_matrices.data() + 16 * instance;
      this->Out.instance_molecules[instance] = groups.ids[m];
      this->Out.instance_tiles[instance] = int(tile);
      const bool inside =
        displaced(this->Chart, uv, scale * (c[2] - this->Patch.centre_height), x, frame);
      if (!inside && !this->Params.cut_to_disk)
      {
        this->Failures[tile] = outside_message(groups.atoms[groups.first[m]], i, j, uv);
        return;
      }
      if (!inside)
      {
        std::fill(matrix, matrix + 16, not_mapped);
      }
      else
      {
        // Rows of R: patch x -> tangent_u, y -> tangent_v, z -> normal (columns of R).
        const std::array<std::array<double, 3>, 3> axes{ frame.tangent_u, frame.tangent_v,
                                                         frame.normal };
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
      }
      if (!this->maps_atoms_of(tile))
      {
        continue;
      }
      double* out = this->atom_block(tile);
      for (const std::uint32_t a : groups.atoms_of(m))
      {
        const float* p = this->Patch.positions[a];
        for (int r = 0; r < 3; ++r)
        {
          out[3 * a + std::size_t(r)] = matrix[4 * r] * p[0] + matrix[4 * r + 1] * p[1] +
            matrix[4 * r + 2] * p[2] + matrix[4 * r + 3];
        }
      }
    }
    this->drop_partial_molecules(tile);
  }

  /// Fits one tile's polynomial, split into 2 x 2, then 4 x 4 ... pieces while its largest
  /// residual exceeds `bound` (mesh units; <= 0: never); falls back to displacement when even
  /// the finest split does not meet it.
  void fit_tile(std::size_t tile, double bound)
  {
    for (int m = 1;; m *= 2)
    {
      this->fit_pieces(tile, m);
      const double worst = this->Out.polynomial_max_residual[tile];
      if (!this->Failures[tile].empty() || bound <= 0 || worst <= bound ||
          2 * m > this->Params.max_polynomial_splits)
      {
        this->Out.polynomial_splits[tile] = m;
        this->Out.tile_fallback[tile] = bound > 0 && worst > bound;
        return;
      }
    }
  }

  /// The tiles' pieces, in tile order, in Out.polynomial_coefficients.
  void gather_pieces()
  {
    std::size_t first = 0;
    auto& offsets = this->Out.polynomial_first_piece;
    offsets.assign(this->TilePieces.size() + 1, 0);
    for (std::size_t tile = 0; tile < this->TilePieces.size(); ++tile)
    {
      offsets[tile] = first;
      first += this->TilePieces[tile].size() / (3 * quadratic_terms);
    }
    offsets.back() = first;
    this->Out.polynomial_coefficients.clear();
    this->Out.polynomial_coefficients.reserve(3 * quadratic_terms * first);
    for (const auto& pieces : this->TilePieces)
    {
      this->Out.polynomial_coefficients.insert(this->Out.polynomial_coefficients.end(),
                                               pieces.begin(), pieces.end());
    }
  }

  /// Fits the m x m pieces of one tile; sets the tile's failure when samples leave the disk,
  /// unless the tile is cut to the disk.
  void fit_pieces(std::size_t tile, int m)
  {
    this->TilePieces[tile].assign(3 * quadratic_terms * std::size_t(m) * std::size_t(m), 0.0);
    const int samples = this->Params.samples;
    const int stride = this->Params.max_polynomial_splits / m; // on the finest sample grid
    double rms = 0, worst = 0;
    bool too_few = false;
    std::vector<std::array<double, 3>> parameters, targets;
    for (int pj = 0; pj < m; ++pj)
    {
      for (int pi = 0; pi < m; ++pi)
      {
        parameters.clear();
        targets.clear();
        for (int sj = 0; sj < samples; ++sj)
        {
          for (int si = 0; si < samples; ++si)
          {
            const TileSample* sample = this->sample(tile, (pi * (samples - 1) + si) * stride,
                                                    (pj * (samples - 1) + sj) * stride);
            if (!sample)
            {
              if (this->Params.cut_to_disk)
              {
                continue;
              }
              return;
            }
            // The piece's own (s, t) in [-1, 1]; the layers h = -1, 0, +1 along the normal.
            const double s = -1 + 2.0 * si / (samples - 1);
            const double t = -1 + 2.0 * sj / (samples - 1);
            const double offset = this->Params.scale * this->Params.layer_half_thickness;
            for (int layer = -1; layer <= 1; ++layer)
            {
              parameters.push_back({ s, t, double(layer) });
              targets.push_back({ sample->position[0] + layer * offset * sample->normal[0],
                                  sample->position[1] + layer * offset * sample->normal[1],
                                  sample->position[2] + layer * offset * sample->normal[2] });
            }
          }
        }
        const std::size_t piece = std::size_t(pj) * std::size_t(m) + std::size_t(pi);
        double* coefficients = this->TilePieces[tile].data() + 3 * quadratic_terms * piece;
        if (parameters.size() < 2 * quadratic_terms)
        {
          too_few = true; // a piece mostly outside a cut disk
          std::fill(coefficients, coefficients + 3 * quadratic_terms, not_mapped);
          continue;
        }
        const QuadraticFit fit = fit_quadratic(parameters, targets);
        std::copy(fit.warp.begin(), fit.warp.end(), coefficients);
        rms = std::max(rms, fit.rms_residual);
        worst = std::max(worst, fit.max_residual);
      }
    }
    this->Out.polynomial_rms_residual[tile] = rms;
    this->Out.polynomial_max_residual[tile] =
      too_few ? std::numeric_limits<double>::infinity() : worst;
  }

  /// The atoms of a tile from its polynomial pieces (or by displacement when it fell back).
  void polynomial_atoms(std::size_t tile)
  {
    if (this->Out.tile_fallback[tile])
    {
      this->displacement(tile);
      return;
    }
    const int i = int(tile % std::size_t(this->Params.tiles));
    const int j = int(tile / std::size_t(this->Params.tiles));
    const int m = this->Out.polynomial_splits[tile];
    const std::size_t n = this->Patch.atom_count();
    const double* coefficients = this->Out.polynomial_coefficients.data() +
      3 * quadratic_terms * this->Out.polynomial_first_piece[tile];
    double* out = this->atom_block(tile);
    SurfacePoint located;
    for (std::size_t a = 0; a < n; ++a)
    {
      const float* p = this->Patch.positions[a];
      const auto y = evaluate_tile_polynomial(this->Patch, this->Params.layer_half_thickness, m,
                                              coefficients, p);
      std::copy(y.begin(), y.end(), out + 3 * a);
      if (this->Params.cut_to_disk)
      {
        const auto uv = this->Layout.uv(p[0], p[1], i, j);
        if (!this->Chart.locate(uv[0], uv[1], located))
        {
          std::fill(out + 3 * a, out + 3 * a + 3, not_mapped);
        }
      }
    }
    this->drop_partial_molecules(tile);
  }

private:
  const SurfaceChart& Chart;
  const MembranePatch& Patch;
  const MappingParams& Params;
  TileLayout Layout;
  MappedMembrane& Out;
  PatchMolecules Molecules;

  /// The surface under one point of a tile's finest sample grid: (samples - 1) m_max + 1
  /// points a side, so the grids of every split nest in it and each point is located once.
  struct TileSample
  {
    std::array<double, 3> position{};
    std::array<double, 3> normal{};
    std::int8_t state = 0; // 0 not yet located, 1 on the disk, -1 off it
  };
  std::vector<std::vector<TileSample>> Samples; // per tile
  std::vector<std::vector<double>> TilePieces;  // per tile: its pieces' coefficients

  /// The sample at finest-grid point (a, b) of a tile, located on first use; nullptr (with the
  /// tile's failure set unless cut to the disk) when it is off the disk.
  const TileSample* sample(std::size_t tile, int a, int b)
  {
    const int side = (this->Params.samples - 1) * this->Params.max_polynomial_splits + 1;
    std::vector<TileSample>& grid = this->Samples[tile];
    if (grid.empty())
    {
      grid.resize(std::size_t(side) * std::size_t(side));
    }
    TileSample& sample = grid[std::size_t(b) * std::size_t(side) + std::size_t(a)];
    if (sample.state == 0)
    {
      const int i = int(tile % std::size_t(this->Params.tiles));
      const int j = int(tile / std::size_t(this->Params.tiles));
      const double tile_s = -1 + 2.0 * a / (side - 1);
      const double tile_t = -1 + 2.0 * b / (side - 1);
      const auto q = this->Layout.patch_point(tile_s, tile_t);
      const auto uv = this->Layout.uv(q[0], q[1], i, j);
      SurfaceFrame frame;
      sample.state = this->Chart.frame(uv[0], uv[1], frame) ? 1 : -1;
      sample.position = frame.position;
      sample.normal = frame.normal;
      if (sample.state < 0 && !this->Params.cut_to_disk)
      {
        this->Failures[tile] = "the polynomial samples of tile (" + std::to_string(i) + ", " +
          std::to_string(j) + ") leave the geodesic disk at (u, v) = (" + std::to_string(uv[0]) +
          ", " + std::to_string(uv[1]) + "); grow the disk";
      }
    }
    return sample.state > 0 ? &sample : nullptr;
  }

  /// Cut to the disk: a molecule with an atom outside is dropped whole.
  void drop_partial_molecules(std::size_t tile)
  {
    if (!this->Params.cut_to_disk || !this->maps_atoms_of(tile))
    {
      return;
    }
    const std::size_t n = this->Patch.atom_count();
    double* out = this->atom_block(tile);
    std::uint8_t* mapped = this->Out.atom_mapped.data() + n * (tile - this->FirstAtomTile);
    for (std::size_t m = 0; m < this->Molecules.groups.count(); ++m)
    {
      const auto atoms = this->Molecules.groups.atoms_of(m);
      const bool whole = std::all_of(atoms.begin(), atoms.end(),
                                     [out](std::uint32_t a) { return !std::isnan(out[3 * a]); });
      for (const std::uint32_t a : atoms)
      {
        mapped[a] = whole ? 1 : 0;
        if (!whole)
        {
          std::fill(out + 3 * a, out + 3 * a + 3, not_mapped);
        }
      }
    }
  }
};

void throw_first_failure(const std::vector<std::string>& failures)
{
  for (const std::string& failure : failures)
  {
    if (!failure.empty())
    {
      throw OutsideChart(failure);
    }
  }
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

int polynomial_piece(int splits, double& s, double& t)
{
  const double fs = (s + 1) / 2 * splits;
  const double ft = (t + 1) / 2 * splits;
  const int i = std::clamp(int(std::floor(fs)), 0, splits - 1);
  const int j = std::clamp(int(std::floor(ft)), 0, splits - 1);
  s = 2 * (fs - i) - 1;
  t = 2 * (ft - j) - 1;
  return j * splits + i;
}

std::array<double, 3> evaluate_tile_polynomial(const MembranePatch& patch,
                                               double layer_half_thickness, int splits,
                                               const double* coefficients, const float* position)
{
  auto local = polynomial_coordinates(patch, layer_half_thickness, position);
  const int piece = polynomial_piece(splits, local[0], local[1]);
  const double* warp = coefficients + 3 * quadratic_terms * std::size_t(piece);
  const auto monomials = quadratic_monomials(local[0], local[1], local[2]);
  std::array<double, 3> x{ 0, 0, 0 };
  for (std::size_t d = 0; d < 3; ++d)
  {
    for (std::size_t k = 0; k < quadratic_terms; ++k)
    {
      x[d] += warp[quadratic_terms * d + k] * monomials[k];
    }
  }
  return x;
}

double tiled_extent(const MembranePatch& patch, int tiles)
{
  // Fractional cell coordinates of the atoms; tiles shift them by whole cells.
  double low[2] = { 0, 0 }, high[2] = { 1, 1 };
  for (std::size_t a = 0; a < patch.atom_count(); ++a)
  {
    const auto local = polynomial_coordinates(patch, 1.0, patch.positions[a]);
    for (int d = 0; d < 2; ++d)
    {
      low[d] = std::min(low[d], (local[std::size_t(d)] + 1) / 2);
      high[d] = std::max(high[d], (local[std::size_t(d)] + 1) / 2);
    }
  }
  // Tile i spans fractional [i - k/2 + low, i - k/2 + high], i in [0, k).
  const double k = tiles;
  double extent = 0;
  for (const double fa : { low[0] - k / 2, high[0] + k / 2 - 1 })
  {
    for (const double fb : { low[1] - k / 2, high[1] + k / 2 - 1 })
    {
      extent = std::max(
        extent, std::hypot(fa * patch.a[0] + fb * patch.b[0], fa * patch.a[1] + fb * patch.b[1]));
    }
  }
  return extent;
}

MappedMembrane map_membrane(const SurfaceChart& chart, const MembranePatch& patch,
                            const MappingParams& params, const ParallelFor& parallel_for)
{
  check_params(patch, params);
  const std::size_t tile_count = std::size_t(params.tiles) * std::size_t(params.tiles);
  const std::size_t n = patch.atom_count();
  MappedMembrane mapped;
  TileMapper mapper(chart, patch, params, mapped);
  mapper.MapAtoms = params.map_atoms || params.method == MappingMethod::Displacement;
  mapper.FirstAtomTile = std::size_t(params.first_atom_tile);
  mapper.EndAtomTile = params.end_atom_tile < 0 ? tile_count : std::size_t(params.end_atom_tile);
  mapped.first_atom_tile = mapper.FirstAtomTile;
  const std::size_t atom_tiles = mapper.EndAtomTile - mapper.FirstAtomTile;
  if (mapper.MapAtoms)
  {
    mapped.positions.resize(3 * n * atom_tiles);
    if (params.cut_to_disk)
    {
      mapped.atom_mapped.assign(n * atom_tiles, 1);
    }
  }
  // Over tiles [first, first + count).
  auto each_tile = [&](const std::function<void(std::size_t)>& work, std::size_t first,
                       std::size_t count) {
    run_parallel(parallel_for, count, [&work, first](std::size_t begin, std::size_t end) {
      for (std::size_t tile = first + begin; tile < first + end; ++tile)
      {
        work(tile);
      }
    });
    throw_first_failure(mapper.Failures);
  };
  switch (params.method)
  {
    case MappingMethod::Displacement:
      each_tile([&mapper](std::size_t tile) { mapper.displacement(tile); }, mapper.FirstAtomTile,
                atom_tiles);
      break;
    case MappingMethod::MoleculeInstancing: {
      const std::size_t molecules = mapper.molecule_count();
      mapped.instance_matrices.resize(16 * molecules * tile_count);
      mapped.instance_molecules.resize(molecules * tile_count);
      mapped.instance_tiles.resize(molecules * tile_count);
      each_tile([&mapper](std::size_t tile) { mapper.instancing(tile); }, 0, tile_count);
      break;
    }
    case MappingMethod::Polynomial: {
      mapped.polynomial_rms_residual.resize(tile_count);
      mapped.polynomial_max_residual.resize(tile_count);
      mapped.polynomial_splits.resize(tile_count);
      mapped.tile_fallback.resize(tile_count);
      const double bound = params.max_polynomial_residual * params.scale;
      each_tile([&mapper, bound](std::size_t tile) { mapper.fit_tile(tile, bound); }, 0,
                tile_count);
      mapper.gather_pieces();
      if (mapper.MapAtoms)
      {
        each_tile([&mapper](std::size_t tile) { mapper.polynomial_atoms(tile); },
                  mapper.FirstAtomTile, atom_tiles);
      }
      break;
    }
  }
  return mapped;
}

std::vector<double> bond_length_changes(const MembranePatch& patch, const MappedMembrane& mapped,
                                        const std::vector<std::array<std::uint32_t, 2>>& bonds,
                                        double scale)
{
  const std::size_t n = patch.atom_count();
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
      const double original = scale * length(patch.positions[i], patch.positions[j]);
      changes[t * bonds.size() + b] =
        original > 0 ? length(tile + 3 * i, tile + 3 * j) / original - 1 : 0.0;
    }
  }
  return changes;
}

} // namespace mesolens
