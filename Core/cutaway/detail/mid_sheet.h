// SPDX-License-Identifier: GPL-3.0-or-later
// Points on the middle sheet of a membrane's point cloud (private to MesoLensCore): the two
// leaflets are paired along the local normal, so that a bilayer of lipid centres or of head
// groups gives one sheet halfway between them.
#pragma once

#include "mesolens/common/parallel_for.h"

#include <cstddef>
#include <memory>
#include <vector>

namespace mesolens {

class PointSearch;

/// The spacing of a cloud's points as if they were spread evenly over a sheet: the median
/// distance from a point to its 10th nearest neighbour, over up to 1000 points spread through the
/// cloud, times sqrt(pi / 10) (on an even sheet with one point per s^2 that distance is
/// sqrt(10 / pi) s). Unlike the median distance to the nearest neighbour (0.5 s for points
/// placed at random), it does not shrink where points cluster. With fewer than 11 points, the
/// median distance to the nearest neighbour (median_spacing()). Throws InvalidInput as that
/// does, or when the points nearly all coincide.
double sheet_spacing(const std::vector<double>& points);

/// Settings of MidSheetFinder.
struct MidSheetParams
{
  /// How far along the normal the other leaflet is looked for (cloud units): more than the
  /// distance between the two leaflets' points (lipid centres about 20 Å apart, head groups
  /// about 40 Å). <= 0: up to 8 sheet spacings, then 1.5 times the distance found.
  double search_height = 0;
  /// The first `own_points` points are the cloud's own and are sampled; the others (periodic
  /// images, for instance) are only neighbours. 0: all points are the cloud's own.
  std::size_t own_points = 0;
  /// The own points' sheet_spacing() if known (cloud units); <= 0: measured.
  double spacing = 0;
};

/// Points on the middle sheet, from MidSheetFinder::samples().
struct MidSheet
{
  std::vector<double> points; ///< 3 coordinates each, in sample order
  std::size_t samples = 0;    ///< samples taken
  std::size_t strays = 0;     ///< samples dropped for having almost no neighbours
  std::size_t unpaired = 0;   ///< samples of a bilayer dropped for finding no other leaflet
  std::size_t outliers = 0;   ///< middle points dropped for lying off their neighbours' sheet
};

/// The middle sheet of a cloud (a membrane's lipid centres or head groups). At a point, the
/// local normal comes first from the 12 nearest points (PCA, least spread); the points in a
/// cylinder along it are split into two groups of heights (1-D two-means), and twice the normal
/// is made again from the planes of the two groups (their spreads about their own means,
/// pooled) and the points split again. Where the groups are far apart for their spread (more
/// than 4 standard deviations and one sheet spacing) they are two leaflets. After the
/// calibration the same is tried from the normal of a wider ball (max(3 spacings, 1.5 d)) and
/// the better kept: two layers before one, then the larger distance for the spread.
///
/// On construction the cloud is indexed and calibrated on up to 400 of its points spread
/// through it (cylinder radius 2 spacings, height +-8 spacings or the search height): when at
/// least 40 % see two leaflets the cloud is a bilayer, the leaflets' distance d the median over
/// them, and later cylinders have radius max(2 spacings, 0.4 d) and height +-1.5 d; otherwise it
/// is one sheet (cylinders of radius and height 2 spacings). The cloud must outlive the finder.
/// Deterministic whatever the ParallelFor.
class MidSheetFinder
{
public:
  /// `points`: 3 coordinates each, at least 4 own points, finite.
  MidSheetFinder(const std::vector<double>& points, const MidSheetParams& params = {},
                 const ParallelFor& parallel_for = {});
  ~MidSheetFinder();
  MidSheetFinder(const MidSheetFinder&) = delete;
  MidSheetFinder& operator=(const MidSheetFinder&) = delete;

  /// The own points' sheet spacing.
  double spacing() const
  {
    return this->Spacing;
  }
  /// The median distance between the two leaflets; 0 for one sheet.
  double leaflet_distance() const
  {
    return this->Distance;
  }

  /// Middle points at a Poisson-disk set of the own points `sample_spacing` apart (raised to
  /// the spacing): halfway between the two leaflets seen from each sample of a bilayer
  /// (samples that see only their own leaflet give none), or on the local plane of one sheet.
  /// Samples with fewer than a tenth of the median count of points within 3 spacings (strays
  /// far from the membrane) give none, and middle points further than max(d / 5, spacing / 2)
  /// from the plane (PCA) of the other middle points within 2.5 sample spacings (outliers: a
  /// sample paired along a wrong normal) are dropped, when samples are at most 2 spacings apart.
  MidSheet samples(double sample_spacing) const;

  /// Moves `positions` (3 coordinates each, near the middle sheet: a mesh's vertices) along
  /// `normals` (3 each, unit) onto the middle sheet: where the line meets the local plane halfway
  /// between the leaflets found along the normal refined from the given one as above (or the
  /// local plane of one sheet). Positions where no two leaflets (for a bilayer) are found stay.
  /// Returns how many moved.
  std::size_t project(std::vector<double>& positions, const std::vector<double>& normals) const;

  /// The neighbourhoods looked at, in cloud units.
  struct Shape
  {
    double count_radius = 0; ///< the ball whose points count as neighbours (strays have few)
    double lateral = 0;      ///< radius of the cylinder along the normal
    double height = 0;       ///< its half height
    double least_gap = 0;    ///< the least distance between two leaflets' groups
    double wide_radius = 0;  ///< the ball of a second first normal; 0: none
  };

private:
  void drop_outliers(MidSheet& sheet, double sample_spacing) const;

  const std::vector<double>& Points;
  std::size_t OwnPoints = 0;
  std::unique_ptr<PointSearch> Search;
  ParallelFor Parallel;
  double Spacing = 0;
  double Distance = 0;
  bool Bilayer = false;
  Shape Around; ///< the neighbourhoods looked at after the calibration
};

} // namespace mesolens
