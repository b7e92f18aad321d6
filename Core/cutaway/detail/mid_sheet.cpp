// SPDX-License-Identifier: GPL-3.0-or-later
#include "cutaway/detail/mid_sheet.h"

#include "mesolens/common/errors.h"
#include "mesolens/cutaway/surface_sampling.h"

#include "cutaway/detail/point_search.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>

namespace mesolens {

namespace {
using Vector = std::array<double, 3>;
using Shape = MidSheetFinder::Shape;
using Cylinder = std::vector<std::pair<double, std::size_t>>;

/// The heights of the points near a sample, split in two groups.
struct HeightGroups
{
  bool two_layers = false;
  double middle = 0;     ///< mean height of the points, or halfway between the two groups
  double distance = 0;   ///< between the groups' means (0 for one layer)
  double spread = 0;     ///< standard deviation of the heights (the larger group's for two)
  std::size_t split = 0; ///< where the higher group starts among the sorted heights
};

/// What the neighbourhood of a point gave.
struct Look
{
  std::size_t neighbours = 0;
  Eigen::Vector3d normal{ 0, 0, 1 };
  HeightGroups groups;
};

/// Reused memory of one thread's looks.
struct LookBuffers
{
  std::vector<std::size_t> found;
  Cylinder cylinder;
  std::vector<double> heights;
};

Vector point_at(const std::vector<double>& points, std::size_t i)
{
  return { points[3 * i], points[3 * i + 1], points[3 * i + 2] };
}

Eigen::Vector3d position(const std::vector<double>& points, std::size_t i)
{
  return { points[3 * i], points[3 * i + 1], points[3 * i + 2] };
}

double median(std::vector<double> values)
{
  if (values.empty())
  {
    return 0;
  }
  std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(values.size() / 2),
                   values.end());
  return values[values.size() / 2];
}

/// Splits sorted heights in the two groups of least total squared deviation (1-D two-means,
/// exact through prefix sums) and says whether they are two layers.
HeightGroups split_heights(const std::vector<double>& heights, double least_gap)
{
  HeightGroups groups;
  const std::size_t m = heights.size();
  if (m == 0)
  {
    return groups;
  }
  std::vector<double> sums(m + 1, 0.0), squares(m + 1, 0.0);
  for (std::size_t i = 0; i < m; ++i)
  {
    sums[i + 1] = sums[i] + heights[i];
    squares[i + 1] = squares[i] + heights[i] * heights[i];
  }
  groups.middle = sums[m] / double(m);
  groups.spread = std::sqrt(std::max(0.0, squares[m] / double(m) - groups.middle * groups.middle));
  if (m < 6)
  {
    return groups;
  }
  const auto deviation = [&](std::size_t begin, std::size_t end) {
    const double count = double(end - begin);
    const double sum = sums[end] - sums[begin];
    return std::max(0.0, squares[end] - squares[begin] - sum * sum / count);
  };
  std::size_t best = 3;
  double least = deviation(0, 3) + deviation(3, m);
  for (std::size_t k = 4; k + 3 <= m; ++k)
  {
    const double total = deviation(0, k) + deviation(k, m);
    if (total < least)
    {
      least = total;
      best = k;
    }
  }
  const double low = sums[best] / double(best);
  const double high = (sums[m] - sums[best]) / double(m - best);
  const double spread =
    std::sqrt(std::max(deviation(0, best) / double(best), deviation(best, m) / double(m - best)));
  groups.distance = high - low;
  groups.split = best;
  groups.two_layers = groups.distance > std::max(4.0 * spread, least_gap);
  if (groups.two_layers)
  {
    groups.middle = 0.5 * (low + high);
    groups.spread = spread;
  }
  return groups;
}

/// The direction of least spread of a covariance matrix (PCA).
Eigen::Vector3d least_spread(const Eigen::Matrix3d& covariance)
{
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvectors().col(0);
}

/// The spread (scatter matrix) of the points `cylinder[k].second`, k in [begin, end), about
/// their mean.
Eigen::Matrix3d spread_of(const std::vector<double>& points, const Cylinder& cylinder,
                          std::size_t begin, std::size_t end)
{
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  if (end <= begin)
  {
    return covariance;
  }
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (std::size_t k = begin; k < end; ++k)
  {
    mean += position(points, cylinder[k].second);
  }
  mean /= double(end - begin);
  for (std::size_t k = begin; k < end; ++k)
  {
    const Eigen::Vector3d d = position(points, cylinder[k].second) - mean;
    covariance += d * d.transpose();
  }
  return covariance;
}

/// The heights along `normal` of the points of `found` in the cylinder about it through
/// `centre`, with their indices, sorted by height.
void heights_in_cylinder(const std::vector<double>& points, const std::vector<std::size_t>& found,
                         const Eigen::Vector3d& centre, const Eigen::Vector3d& normal,
                         const Shape& shape, Cylinder& cylinder)
{
  cylinder.clear();
  for (const std::size_t i : found)
  {
    const Eigen::Vector3d d = position(points, i) - centre;
    const double t = d.dot(normal);
    if (std::abs(t) <= shape.height && d.squaredNorm() - t * t <= shape.lateral * shape.lateral)
    {
      cylinder.emplace_back(t, i);
    }
  }
  std::sort(cylinder.begin(), cylinder.end());
}

/// The height groups along a first normal, then twice along the normal of the planes of its
/// groups (their spreads about their own means, pooled): the leaflets' distance does not tilt
/// it.
Look refined_look(const std::vector<double>& points, const Eigen::Vector3d& centre,
                  const Eigen::Vector3d& first, const Shape& shape, LookBuffers& buffers)
{
  Look look;
  look.normal = first;
  Cylinder& cylinder = buffers.cylinder;
  for (int pass = 0; pass < 3; ++pass)
  {
    heights_in_cylinder(points, buffers.found, centre, look.normal, shape, cylinder);
    buffers.heights.resize(cylinder.size());
    for (std::size_t k = 0; k < cylinder.size(); ++k)
    {
      buffers.heights[k] = cylinder[k].first;
    }
    look.groups = split_heights(buffers.heights, shape.least_gap);
    if (pass < 2 && cylinder.size() >= 3)
    {
      const std::size_t split = look.groups.two_layers ? look.groups.split : 0;
      const Eigen::Vector3d refined =
        least_spread(spread_of(points, cylinder, 0, split) +
                     spread_of(points, cylinder, split, cylinder.size()));
      look.normal = refined.dot(look.normal) < 0 ? Eigen::Vector3d(-refined) : refined;
    }
  }
  return look;
}

/// How well a look's normal crosses the sheet: two layers beat one; two layers far apart for
/// their spread, one layer thin.
double look_score(const Look& look, double spacing)
{
  const double spread = look.groups.spread + 1e-6 * spacing;
  return look.groups.two_layers ? 1e6 + look.groups.distance / spread : spacing / spread;
}

/// The normal and height groups at `centre` (`buffers.found`: the points in the ball around
/// the cylinder). The first normal is `initial`, or without one the better (look_score) of the
/// least spread of the 12 nearest points, which lie in a sample's own leaflet, and, where the
/// shape asks, of the points in a wide ball, which hold both leaflets: on uneven clouds either
/// may lie along the sheet.
Look look_around(const std::vector<double>& points, const Eigen::Vector3d& centre,
                 const Eigen::Vector3d* initial, const Shape& shape, LookBuffers& buffers)
{
  Cylinder& cylinder = buffers.cylinder;
  cylinder.clear(); // first the squared distances, for the count and the nearest points
  std::size_t neighbours = 0;
  for (const std::size_t i : buffers.found)
  {
    const double d2 = (position(points, i) - centre).squaredNorm();
    cylinder.emplace_back(d2, i);
    neighbours += d2 <= shape.count_radius * shape.count_radius ? 1 : 0;
  }
  if (!initial && cylinder.size() < 3)
  {
    Look none;
    none.neighbours = neighbours;
    return none;
  }
  std::vector<Eigen::Vector3d> firsts;
  if (initial)
  {
    firsts.push_back(*initial);
  }
  else
  {
    const std::size_t nearest = std::min<std::size_t>(12, cylinder.size());
    std::nth_element(cylinder.begin(), cylinder.begin() + std::ptrdiff_t(nearest - 1),
                     cylinder.end());
    firsts.push_back(least_spread(spread_of(points, cylinder, 0, nearest)));
    if (shape.wide_radius > 0)
    {
      const auto wide = std::partition(cylinder.begin(), cylinder.end(), [&](const auto& entry) {
        return entry.first <= shape.wide_radius * shape.wide_radius;
      });
      firsts.push_back(
        least_spread(spread_of(points, cylinder, 0, std::size_t(wide - cylinder.begin()))));
    }
  }
  Look best;
  for (const Eigen::Vector3d& first : firsts)
  {
    const Look look = refined_look(points, centre, first, shape, buffers);
    if (&first == &firsts.front() ||
        look_score(look, shape.least_gap) > look_score(best, shape.least_gap))
    {
      best = look;
    }
  }
  best.neighbours = neighbours;
  return best;
}

/// look_around() at every point of `centres` (3 coordinates each), in parallel, in order.
std::vector<Look> look_around_all(const std::vector<double>& points, const PointSearch& search,
                                  const std::vector<double>& centres,
                                  const std::vector<double>* normals, const Shape& shape,
                                  const ParallelFor& parallel_for)
{
  std::vector<Look> looks(centres.size() / 3);
  const double reach =
    std::max({ shape.count_radius, shape.wide_radius, std::hypot(shape.lateral, shape.height) });
  run_parallel(parallel_for, looks.size(), [&](std::size_t begin, std::size_t end) {
    LookBuffers buffers;
    for (std::size_t s = begin; s < end; ++s)
    {
      search.within(point_at(centres, s), reach, buffers.found);
      const Eigen::Vector3d initial = normals ? position(*normals, s) : Eigen::Vector3d(0, 0, 1);
      looks[s] =
        look_around(points, position(centres, s), normals ? &initial : nullptr, shape, buffers);
    }
  });
  return looks;
}
} // namespace

double sheet_spacing(const std::vector<double>& points)
{
  const std::size_t n = points.size() / 3;
  if (n < 11)
  {
    return median_spacing(points); // too few for a 10th neighbour
  }
  const PointSearch search(points);
  const std::size_t step = std::max<std::size_t>(1, n / 1000);
  std::vector<double> distances;
  std::vector<std::size_t> found;
  for (std::size_t i = 0; i < n; i += step)
  {
    search.nearest(point_at(points, i), 11, found); // the point itself and 10 others
    distances.push_back((position(points, found.back()) - position(points, i)).norm());
  }
  const double spacing = median(distances) * std::sqrt(3.14159265358979323846 / 10.0);
  if (!(spacing > 0))
  {
    throw InvalidInput("the " + std::to_string(n) + " points of the cloud nearly all coincide");
  }
  return spacing;
}

MidSheetFinder::MidSheetFinder(const std::vector<double>& points, const MidSheetParams& params,
                               const ParallelFor& parallel_for)
  : Points(points)
  , OwnPoints(params.own_points > 0 ? params.own_points : points.size() / 3)
  , Parallel(parallel_for)
{
  if (points.size() % 3 != 0 || this->OwnPoints < 4 || this->OwnPoints > points.size() / 3)
  {
    throw InvalidInput("a middle sheet needs at least 4 points of 3 coordinates");
  }
  this->Search = std::make_unique<PointSearch>(points);
  const double h = params.spacing > 0
    ? params.spacing
    : sheet_spacing(
        std::vector<double>(points.begin(), points.begin() + std::ptrdiff_t(3 * this->OwnPoints)));
  this->Spacing = h;

  // Calibration on up to 400 own points spread through the cloud: one sheet or two leaflets,
  // and how far apart.
  std::vector<double> calibration;
  const std::size_t step = std::max<std::size_t>(1, this->OwnPoints / 400);
  for (std::size_t i = 0; i < this->OwnPoints; i += step)
  {
    calibration.insert(calibration.end(), points.begin() + std::ptrdiff_t(3 * i),
                       points.begin() + std::ptrdiff_t(3 * i + 3));
  }
  const double height = params.search_height > 0 ? params.search_height : 8.0 * h;
  const auto looks = look_around_all(points, *this->Search, calibration, nullptr,
                                     { 3.0 * h, 2.0 * h, height, h, 0.0 }, parallel_for);
  std::vector<double> distances;
  for (const Look& look : looks)
  {
    if (look.groups.two_layers)
    {
      distances.push_back(look.groups.distance);
    }
  }
  this->Bilayer = double(distances.size()) >= 0.4 * double(looks.size());
  this->Distance = this->Bilayer ? median(distances) : 0.0;
  const double d = this->Distance;
  this->Around = this->Bilayer
    ? Shape{ 3.0 * h, std::max(2.0 * h, 0.4 * d), 1.5 * d, h, std::max(3.0 * h, 1.5 * d) }
    : Shape{ 3.0 * h, 2.0 * h, 2.0 * h, h, 3.0 * h };
}

MidSheetFinder::~MidSheetFinder() = default;

MidSheet MidSheetFinder::samples(double sample_spacing) const
{
  MidSheet sheet;
  const std::vector<double> own(this->Points.begin(),
                                this->Points.begin() + std::ptrdiff_t(3 * this->OwnPoints));
  const std::vector<double> samples =
    poisson_disk_subset(own, std::max(this->Spacing, sample_spacing));
  sheet.samples = samples.size() / 3;
  const auto looks =
    look_around_all(this->Points, *this->Search, samples, nullptr, this->Around, this->Parallel);
  // Strays (a lipid that left the membrane) have almost no neighbours.
  std::vector<double> counts;
  for (const Look& look : looks)
  {
    counts.push_back(double(look.neighbours));
  }
  const double fewest = std::max(3.0, 0.1 * median(counts));
  for (std::size_t s = 0; s < looks.size(); ++s)
  {
    const Look& look = looks[s];
    if (double(look.neighbours) < fewest)
    {
      ++sheet.strays;
      continue;
    }
    if (this->Bilayer && (!look.groups.two_layers || look.groups.distance < 0.5 * this->Distance))
    {
      ++sheet.unpaired;
      continue;
    }
    // Halfway between the leaflets, or onto the local plane of one sheet.
    const Eigen::Vector3d moved = position(samples, s) + look.groups.middle * look.normal;
    sheet.points.insert(sheet.points.end(), { moved[0], moved[1], moved[2] });
  }
  this->drop_outliers(sheet, std::max(this->Spacing, sample_spacing));
  return sheet;
}

void MidSheetFinder::drop_outliers(MidSheet& sheet, double sample_spacing) const
{
  const std::size_t count = sheet.points.size() / 3;
  if (count < 4 || sample_spacing > 2.0 * this->Spacing)
  {
    return; // the plane of a few neighbours far apart is no test on a curved sheet
  }
  const PointSearch search(sheet.points);
  const double radius = 2.5 * sample_spacing;
  const double tolerance = std::max(0.2 * this->Distance, 0.5 * this->Spacing);
  std::vector<std::uint8_t> keep(count, 1);
  run_parallel(this->Parallel, count, [&](std::size_t begin, std::size_t end) {
    std::vector<std::size_t> near;
    Cylinder others; // the neighbours, as spread_of() takes them
    for (std::size_t i = begin; i < end; ++i)
    {
      search.within(point_at(sheet.points, i), radius, near);
      others.clear();
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      for (const std::size_t j : near)
      {
        if (j != i)
        {
          others.emplace_back(0.0, j);
          mean += position(sheet.points, j);
        }
      }
      if (others.size() < 5)
      {
        continue;
      }
      // A point off the plane of its neighbours (a sample paired along a wrong normal): its own
      // normal may be the wrong one, theirs is not.
      mean /= double(others.size());
      const Eigen::Vector3d normal =
        least_spread(spread_of(sheet.points, others, 0, others.size()));
      keep[i] = std::abs((position(sheet.points, i) - mean).dot(normal)) <= tolerance;
    }
  });
  std::vector<double> kept;
  for (std::size_t i = 0; i < count; ++i)
  {
    if (keep[i])
    {
      kept.insert(kept.end(), sheet.points.begin() + std::ptrdiff_t(3 * i),
                  sheet.points.begin() + std::ptrdiff_t(3 * i + 3));
    }
    else
    {
      ++sheet.outliers;
    }
  }
  sheet.points = std::move(kept);
}

std::size_t MidSheetFinder::project(std::vector<double>& positions,
                                    const std::vector<double>& normals) const
{
  const auto looks =
    look_around_all(this->Points, *this->Search, positions, &normals, this->Around, this->Parallel);
  std::size_t moved = 0;
  for (std::size_t v = 0; v < looks.size(); ++v)
  {
    const Look& look = looks[v];
    if (this->Bilayer && (!look.groups.two_layers || look.groups.distance < 0.5 * this->Distance))
    {
      continue;
    }
    // Along the given normal only (to where it meets the sheet's local plane): the positions
    // keep their spacing across it.
    const Eigen::Vector3d given = position(normals, v);
    const double along = look.groups.middle / std::max(0.5, std::abs(look.normal.dot(given)));
    for (std::size_t k = 0; k < 3; ++k)
    {
      positions[3 * v + k] += along * given[Eigen::Index(k)];
    }
    ++moved;
  }
  return moved;
}

} // namespace mesolens
