// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/io/off_file.h"

#include "io/detail/file_checks.h"
#include "mesolens/common/errors.h"

#include <CGAL/IO/OFF.h>
#include <CGAL/Simple_cartesian.h>

#include <cmath>
#include <sstream>

namespace mesolens {

PolygonSoup read_off(const std::string& path)
{
  detail::require_readable_file(path);
  using Point = CGAL::Simple_cartesian<double>::Point_3;
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  bool ok = false;
  try
  {
    ok = CGAL::IO::read_OFF(path, points, polygons);
  }
  catch (const std::exception& e)
  {
    throw FileError(path + ": not a valid OFF file (" + e.what() + ")");
  }
  if (!ok)
  {
    throw FileError(path + ": not a valid OFF file");
  }
  if (points.empty() || polygons.empty())
  {
    throw FileError(path + ": the OFF file holds no faces");
  }
  PolygonSoup soup;
  soup.points.reserve(3 * points.size());
  for (const Point& p : points)
  {
    soup.points.insert(soup.points.end(), { p.x(), p.y(), p.z() });
  }
  soup.polygons.reserve(polygons.size());
  for (const auto& polygon : polygons)
  {
    soup.polygons.emplace_back(polygon.begin(), polygon.end());
  }
  return soup;
}

} // namespace mesolens
