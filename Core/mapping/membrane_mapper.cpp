// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/mapping/membrane_mapper.h"

#include "mesolens/common/errors.h"
#include "mesolens/molecules/molecule_groups.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <sstream>
#include <vector>

namespace mesolens {

namespace {
constexpr std::size_t cached_charts = 16;
constexpr double pi = 3.14159265358979323846;

std::string format_number(double value)
{
  std::ostringstream text;
  text.precision(3);
  text << value;
  return text.str();
}

/// A disk that could not be made, kept so that a search does not grow it again.
struct ChartFailure
{
  std::string message;
  bool topology = true; ///< TopologyError (else SolverFailure)
};

/// Radius of the area one molecule of a leaflet covers, membrane units: the smallest disk
/// worth mapping.
double molecule_footprint(const MembranePatch& patch)
{
  const std::size_t molecules =
    patch.molecule_ids ? group_molecules(patch.molecule_ids, patch.atom_count()).count() : 0;
  const double area = std::abs(patch.a[0] * patch.b[1] - patch.a[1] * patch.b[0]);
  const double per_leaflet = std::max<double>(1.0, double(molecules) / 2);
  // Without molecule ids: a typical lipid's 60 Å^2 if the patch is in Å, capped by the cell.
  const double footprint = patch.molecule_ids ? area / per_leaflet : std::min(area, 60.0);
  return std::sqrt(footprint / pi);
}

/// Turns the parameterization about the disk's centre so that +u at the seed points along the
/// mesh's +x axis as seen in the tangent plane there (+y where the surface faces along x): the
/// patch's orientation then depends on where the user clicked, not on how the disk's boundary
/// happens to be numbered.
void align_u_axis(const GeodesicDisk& disk, DiskParameterization& map)
{
  const SurfaceChart chart(disk.mesh, map.uv, disk.normals);
  const std::array<double, 2> seed_uv = chart.uv_of(disk.seed);
  SurfaceFrame frame;
  if (!chart.frame(seed_uv[0], seed_uv[1], frame))
  {
    return;
  }
  const auto& n = frame.normal;
  std::array<double, 3> target =
    std::abs(n[0]) < 0.9 ? std::array<double, 3>{ 1, 0, 0 } : std::array<double, 3>{ 0, 1, 0 };
  const double along = target[0] * n[0] + target[1] * n[1] + target[2] * n[2];
  for (std::size_t d = 0; d < 3; ++d)
  {
    target[d] -= along * n[d];
  }
  auto dot = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  };
  // The target's angle from +u in the tangent plane; uv turns the other way to bring it there.
  const double angle = std::atan2(dot(target, frame.tangent_v), dot(target, frame.tangent_u));
  const double c = std::cos(angle), s = std::sin(angle);
  for (std::size_t i = 0; i < map.uv.size(); i += 2)
  {
    const double u = map.uv[i], v = map.uv[i + 1];
    map.uv[i] = c * u + s * v;
    map.uv[i + 1] = -s * u + c * v;
  }
}

/// Each triangle's linear stretch, ordered by the distance of its (u, v) centroid from the
/// seed's, as MappingChart keeps them.
void measure_stretch(MappingChart& chart)
{
  const TriangleMesh& mesh = chart.disk.mesh;
  const std::vector<double>& uv = chart.parameterization.uv;
  std::vector<std::pair<double, double>> by_radius;
  by_radius.reserve(mesh.triangle_count());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
  {
    const auto a = std::size_t(mesh.triangles[3 * t]), b = std::size_t(mesh.triangles[3 * t + 1]),
               c = std::size_t(mesh.triangles[3 * t + 2]);
    const double stretch = chart.parameterization.stretch[t];
    // The nearest the triangle comes to the seed in (u, v), near enough: its centroid's distance
    // less its corners' largest distance from the centroid.
    const double cu = (uv[2 * a] + uv[2 * b] + uv[2 * c]) / 3;
    const double cv = (uv[2 * a + 1] + uv[2 * b + 1] + uv[2 * c + 1]) / 3;
    double spread = 0;
    for (const std::size_t corner : { a, b, c })
    {
      spread = std::max(spread, std::hypot(uv[2 * corner] - cu, uv[2 * corner + 1] - cv));
    }
    const double nearest =
      std::max(0.0, std::hypot(cu - chart.seed_uv[0], cv - chart.seed_uv[1]) - spread);
    by_radius.emplace_back(nearest, stretch);
  }
  std::sort(by_radius.begin(), by_radius.end());
  double worst = 1;
  for (const auto& [radius, stretch] : by_radius)
  {
    worst = std::max(worst, stretch);
    chart.stretch_radius.push_back(radius);
    chart.stretch_prefix_max.push_back(worst);
  }
}

} // namespace

struct MembraneMapper::Impl
{
  explicit Impl(TriangleMesh mesh)
    : Surface(std::move(mesh))
  {
  }

  CellSurface Surface;

  struct Entry
  {
    std::int64_t triangle = -1;
    std::array<double, 3> barycentric{};
    double radius = 0;
    std::size_t min_triangles = 0;
    std::size_t max_triangles = 0;
    std::shared_ptr<const MappingChart> chart;
    ChartFailure failure;
    std::uint64_t used = 0;
  };
  mutable std::mutex Lock;
  mutable std::vector<Entry> Cache;
  mutable std::uint64_t Clock = 0;

  std::shared_ptr<const MappingChart> build(const SurfacePoint& seed, double radius,
                                            std::size_t min_triangles,
                                            std::size_t max_triangles) const
  {
    GeodesicDiskParams params;
    params.radius = radius;
    params.min_triangles = min_triangles;
    params.max_triangles = max_triangles;
    GeodesicDisk disk = geodesic_disk(this->Surface, seed, params);
    DiskParameterization map = harmonic_parameterization(disk.mesh, radius);
    align_u_axis(disk, map);
    SurfacePlacement placement = smooth_placement(disk, this->Surface);
    SurfaceChart chart(disk.mesh, map.uv, disk.normals, std::move(placement));
    const std::array<double, 2> seed_uv = chart.uv_of(disk.seed);
    auto result = std::make_shared<MappingChart>(
      MappingChart{ std::move(disk), std::move(map), std::move(chart), seed_uv, radius, {}, {} });
    measure_stretch(*result);
    return result;
  }
};

MembraneMapper::MembraneMapper(TriangleMesh surface)
  : Internal(std::make_unique<Impl>(std::move(surface)))
{
}

MembraneMapper::~MembraneMapper() = default;

const CellSurface& MembraneMapper::surface() const
{
  return this->Internal->Surface;
}

SurfacePoint MembraneMapper::seed_near(const std::array<double, 3>& point, double tolerance) const
{
  if (!std::isfinite(point[0]) || !std::isfinite(point[1]) || !std::isfinite(point[2]))
  {
    throw InvalidInput("the picked point is not finite");
  }
  double distance = 0;
  const SurfacePoint seed = this->Internal->Surface.closest_point(point, &distance);
  const double allowed =
    tolerance > 0 ? tolerance : 0.02 * this->Internal->Surface.bounding_diagonal();
  if (distance > allowed)
  {
    throw InvalidInput(
      "the picked point (" + format_number(point[0]) + ", " + format_number(point[1]) + ", " +
      format_number(point[2]) + ") is " + format_number(distance) +
      " away from the surface, farther than the tolerance " + format_number(allowed));
  }
  return seed;
}

std::shared_ptr<const MappingChart> MembraneMapper::chart(const SurfacePoint& seed, double radius,
                                                          std::size_t min_disk_triangles,
                                                          std::size_t max_disk_triangles) const
{
  Impl& impl = *this->Internal;
  {
    std::lock_guard<std::mutex> lock(impl.Lock);
    for (Impl::Entry& entry : impl.Cache)
    {
      if (entry.triangle == seed.triangle && entry.barycentric == seed.barycentric &&
          entry.radius == radius && entry.min_triangles == min_disk_triangles &&
          entry.max_triangles == max_disk_triangles)
      {
        entry.used = ++impl.Clock;
        if (entry.chart)
        {
          return entry.chart;
        }
        if (entry.failure.topology)
        {
          throw TopologyError(entry.failure.message);
        }
        throw SolverFailure(entry.failure.message);
      }
    }
  }
  Impl::Entry entry;
  entry.triangle = seed.triangle;
  entry.barycentric = seed.barycentric;
  entry.radius = radius;
  entry.min_triangles = min_disk_triangles;
  entry.max_triangles = max_disk_triangles;
  try
  {
    entry.chart = impl.build(seed, radius, min_disk_triangles, max_disk_triangles);
  }
  catch (const TopologyError& e)
  {
    entry.failure = { e.what(), true };
  }
  catch (const SolverFailure& e)
  {
    entry.failure = { e.what(), false };
  }
  std::lock_guard<std::mutex> lock(impl.Lock);
  entry.used = ++impl.Clock;
  if (impl.Cache.size() < cached_charts)
  {
    impl.Cache.push_back(entry);
  }
  else
  {
    *std::min_element(impl.Cache.begin(), impl.Cache.end(),
                      [](const Impl::Entry& a, const Impl::Entry& b) { return a.used < b.used; }) =
      entry;
  }
  if (!entry.chart)
  {
    if (entry.failure.topology)
    {
      throw TopologyError(entry.failure.message);
    }
    throw SolverFailure(entry.failure.message);
  }
  return entry.chart;
}

void MembraneMapper::forget_charts() const
{
  std::lock_guard<std::mutex> lock(this->Internal->Lock);
  this->Internal->Cache.clear();
}

namespace {
void check_request(const MembranePatch& patch, const MapRequest& request)
{
  const MappingParams& asked = request.mapping;
  if (asked.tiles < 1)
  {
    throw InvalidInput("the number of tiles per side must be at least 1, got " +
                       std::to_string(asked.tiles));
  }
  if (!(request.radius_factor >= 0.8 && request.radius_factor <= 10))
  {
    throw InvalidInput("the radius factor must lie in [0.8, 10], got " +
                       format_number(request.radius_factor));
  }
  if (!(asked.scale > 0) || !std::isfinite(asked.scale))
  {
    throw InvalidInput("the membrane-to-mesh scale must be positive and finite");
  }
  if (!(request.max_stretch > 1))
  {
    throw InvalidInput("the largest stretch accepted must exceed 1, got " +
                       format_number(request.max_stretch));
  }
  if (patch.atom_count() == 0)
  {
    throw InvalidInput("the membrane patch has no atoms");
  }
  if (request.pieces < 1 || request.piece < 0 || request.piece >= request.pieces)
  {
    throw InvalidInput("piece " + std::to_string(request.piece) + " of " +
                       std::to_string(request.pieces) + " does not exist");
  }
}
} // namespace

/// The search for what fits around one seed: charts come from the mapper's cache, so asking
/// twice costs nothing; nothing is mapped until the search is over.
struct MembraneMapper::FitSearch
{
  const MembraneMapper& Mapper;
  const SurfacePoint& Seed;
  const MembranePatch& Patch;
  const MapRequest& Request;

  /// The chart of radius r when k x k tiles fit in it (cut: only that it is a disk), else null
  /// with `why`.
  std::shared_ptr<const MappingChart> holds(int k, double r, bool cut, std::string& why) const
  {
    std::shared_ptr<const MappingChart> chart;
    try
    {
      chart = this->Mapper.chart(this->Seed, r, this->Request.min_disk_triangles,
                                 this->Request.max_disk_triangles);
    }
    catch (const TopologyError& e)
    {
      why = e.what();
      return nullptr;
    }
    // The uv disk has the radius r; tiles reaching beyond it, or nearly, leave the chart.
    const double reach = std::hypot(chart->seed_uv[0], chart->seed_uv[1]) +
      this->Request.mapping.scale * tiled_extent(this->Patch, k);
    if (!cut && reach > 0.98 * r)
    {
      why = "its " + std::to_string(k) + " x " + std::to_string(k) +
        " tiles reach beyond the geodesic disk of radius " + format_number(r);
      return nullptr;
    }
    const double stretch = chart->largest_stretch_within(reach);
    if (!cut && stretch > this->Request.max_stretch)
    {
      why = "the geodesic disk of radius " + format_number(r) + " would stretch the " +
        std::to_string(k) + " x " + std::to_string(k) + " tiles " + format_number(stretch) +
        "-fold (the surface there cannot be flattened that far)";
      return nullptr;
    }
    return chart;
  }

  /// The chart for k x k tiles: on the disk asked (radius factor x tiled width), else on the
  /// smallest that holds the tiles.
  std::shared_ptr<const MappingChart> fitting(int k, std::string& why) const
  {
    const double scale = this->Request.mapping.scale;
    const double asked = this->Request.radius_factor * k * patch_width(this->Patch) * scale;
    const double smallest = 1.1 * scale * tiled_extent(this->Patch, k);
    auto chart = this->holds(k, asked, false, why);
    if (!chart && smallest < asked)
    {
      // The smallest disk that could hold the tiles says best why they do not fit.
      chart = this->holds(k, smallest, false, why);
    }
    return chart;
  }

  /// The largest disk up to one tile's that is one, by bisection on its radius from a
  /// molecule's footprint; null (with `why`) when not even the footprint's is.
  std::shared_ptr<const MappingChart> cut_disk(std::string& why) const
  {
    const double scale = this->Request.mapping.scale;
    const double footprint = scale * molecule_footprint(this->Patch);
    auto best = this->holds(1, footprint, true, why);
    if (!best)
    {
      return nullptr;
    }
    double inside = footprint;
    double outside = std::max(footprint, 1.1 * scale * tiled_extent(this->Patch, 1));
    for (int step = 0; step < 8 && outside > 1.01 * inside; ++step)
    {
      const double r = 0.5 * (inside + outside);
      std::string ignored;
      if (auto chart = this->holds(1, r, true, ignored))
      {
        best = chart;
        inside = r;
      }
      else
      {
        outside = r;
      }
    }
    return best;
  }
};

MapResult MembraneMapper::map(const SurfacePoint& seed, const MembranePatch& patch,
                              const MapRequest& request, const ParallelFor& parallel_for) const
{
  check_request(patch, request);
  const int asked = request.mapping.tiles;
  const FitSearch search{ *this, seed, patch, request };
  MapResult result;
  result.tiles_asked = asked;
  auto map_on = [&](const std::shared_ptr<const MappingChart>& chart, int k, bool cut) {
    MappingParams params = request.mapping;
    params.tiles = k;
    params.centre_uv = chart->seed_uv;
    params.cut_to_disk = cut;
    const long long tile_count = static_cast<long long>(k) * k;
    params.first_atom_tile = static_cast<int>(tile_count * request.piece / request.pieces);
    params.end_atom_tile = static_cast<int>(tile_count * (request.piece + 1) / request.pieces);
    result.mapped = map_membrane(chart->chart, patch, params, parallel_for);
    result.chart = chart;
    result.tiles_mapped = k;
    result.cut_to_disk = cut;
  };
  std::string why_not_asked;
  if (auto chart = search.fitting(asked, why_not_asked))
  {
    map_on(chart, asked, false); // throws OutsideChart if the tiles still leave it
    return result;
  }
  if (!request.fit_what_fits)
  {
    throw TopologyError(why_not_asked);
  }
  // The largest k that fits, by bisection over [1, asked - 1] (fewer tiles need a smaller disk).
  int low = 1, high = asked - 1, best = 0;
  std::shared_ptr<const MappingChart> best_chart;
  while (low <= high)
  {
    const int k = (low + high) / 2;
    std::string why;
    if (auto chart = search.fitting(k, why))
    {
      best = k;
      best_chart = chart;
      low = k + 1;
    }
    else
    {
      high = k - 1;
    }
  }
  const std::string asked_tiles = std::to_string(asked) + " x " + std::to_string(asked);
  if (best > 0)
  {
    map_on(best_chart, best, false);
    result.note = "mapped " + std::to_string(best) + " x " + std::to_string(best) +
      " tiles instead of " + asked_tiles + ": " + why_not_asked;
    return result;
  }
  // Not even one tile fits: one tile cut to the largest disk that is one.
  std::string why;
  const auto cut = search.cut_disk(why);
  if (!cut)
  {
    throw TopologyError("not even one molecule's footprint (radius " +
                        format_number(request.mapping.scale * molecule_footprint(patch)) +
                        ") around the picked point is a disk of the surface: " + why);
  }
  map_on(cut, 1, true);
  result.note = "mapped one tile cut to a geodesic disk of radius " + format_number(cut->radius) +
    " instead of " + asked_tiles + " tiles: " + why_not_asked;
  return result;
}

double MappingChart::largest_stretch_within(double uv_radius) const
{
  const auto end =
    std::upper_bound(this->stretch_radius.begin(), this->stretch_radius.end(), uv_radius);
  return end == this->stretch_radius.begin()
    ? 1.0
    : this->stretch_prefix_max[std::size_t(end - this->stretch_radius.begin()) - 1];
}

double patch_width(const MembranePatch& patch)
{
  const double width =
    std::max(std::hypot(patch.a[0], patch.a[1]), std::hypot(patch.b[0], patch.b[1]));
  if (!(width > 0) || !std::isfinite(width))
  {
    throw InvalidInput("the membrane patch's cell vectors are zero or not finite");
  }
  return width;
}

} // namespace mesolens
