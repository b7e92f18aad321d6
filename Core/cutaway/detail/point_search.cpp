// SPDX-License-Identifier: GPL-3.0-or-later
#include "cutaway/detail/point_search.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Fuzzy_sphere.h>
#include <CGAL/Kd_tree.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/property_map.h>

#include <boost/iterator/counting_iterator.hpp>

#include <algorithm>
#include <iterator>

namespace mesolens {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using PointMap = CGAL::Pointer_property_map<Point>::type;
using Traits = CGAL::Search_traits_adapter<std::size_t, PointMap, CGAL::Search_traits_3<Kernel>>;
using KdTree = CGAL::Kd_tree<Traits>;
using Sphere = CGAL::Fuzzy_sphere<Traits>;
using Distance = CGAL::Distance_adapter<std::size_t, PointMap,
                                        CGAL::Euclidean_distance<CGAL::Search_traits_3<Kernel>>>;
using NeighbourSearch = CGAL::Orthogonal_k_neighbor_search<Traits, Distance>;
} // namespace

struct PointSearch::Tree
{
  std::vector<Point> Points;
  std::unique_ptr<KdTree> Index;
};

PointSearch::PointSearch(const std::vector<double>& points)
  : Index(std::make_unique<Tree>())
{
  auto& tree = *this->Index;
  tree.Points.reserve(points.size() / 3);
  for (std::size_t i = 0; i + 2 < points.size(); i += 3)
  {
    tree.Points.emplace_back(points[i], points[i + 1], points[i + 2]);
  }
  tree.Index =
    std::make_unique<KdTree>(boost::counting_iterator<std::size_t>(0),
                             boost::counting_iterator<std::size_t>(tree.Points.size()),
                             KdTree::Splitter(), Traits(CGAL::make_property_map(tree.Points)));
  tree.Index->build(); // before any query: concurrent queries need a built tree
}

PointSearch::~PointSearch() = default;

void PointSearch::within(const std::array<double, 3>& centre, double radius,
                         std::vector<std::size_t>& found) const
{
  found.clear();
  const Sphere sphere(Point(centre[0], centre[1], centre[2]), radius, 0.0,
                      Traits(CGAL::make_property_map(this->Index->Points)));
  this->Index->Index->search(std::back_inserter(found), sphere);
}

void PointSearch::nearest(const std::array<double, 3>& centre, std::size_t count,
                          std::vector<std::size_t>& found) const
{
  found.clear();
  const PointMap map = CGAL::make_property_map(this->Index->Points);
  NeighbourSearch search(*this->Index->Index, Point(centre[0], centre[1], centre[2]),
                         static_cast<unsigned int>(count), 0.0, true, Distance(map));
  for (const auto& neighbour : search)
  {
    found.push_back(neighbour.first);
  }
}

} // namespace mesolens
