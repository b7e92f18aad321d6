// SPDX-License-Identifier: GPL-3.0-or-later
#include "cutaway/detail/sheet_lattice.h"

#include "mesolens/common/errors.h"

#include "cutaway/detail/point_search.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>

namespace mesolens {

namespace {
using Vector = std::array<double, 3>;

double dot(const Vector& p, const Vector& q)
{
  return p[0] * q[0] + p[1] * q[1] + p[2] * q[2];
}

Vector cross(const Vector& p, const Vector& q)
{
  return { p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0] };
}

double norm(const Vector& p)
{
  return std::sqrt(dot(p, p));
}

/// The cell's plane coordinates: x along a, y across it in the plane, and the height along the
/// normal (absolute: the origin has no normal component).
struct PlaneFrame
{
  Vector e1{}, e2{}, normal{}, origin{};
  double a_length = 0, b_along = 0, b_across = 0;

  explicit PlaneFrame(const SheetCell& cell)
    : normal(cell.normal)
    , origin(cell.origin)
  {
    this->a_length = norm(cell.a);
    for (int k = 0; k < 3; ++k)
    {
      this->e1[k] = cell.a[k] / this->a_length;
    }
    this->e2 = cross(this->normal, this->e1);
    this->b_along = dot(cell.b, this->e1);
    this->b_across = dot(cell.b, this->e2);
  }

  /// x, y in the plane and the height.
  Vector coordinates(const double* p) const
  {
    const Vector d{ p[0] - this->origin[0], p[1] - this->origin[1], p[2] - this->origin[2] };
    return { dot(d, this->e1), dot(d, this->e2),
             p[0] * this->normal[0] + p[1] * this->normal[1] + p[2] * this->normal[2] };
  }

  /// Fractional coordinates u (along a) and v (along b) of plane coordinates x, y.
  std::array<double, 2> fractions(double x, double y) const
  {
    const double v = y / this->b_across;
    return { (x - v * this->b_along) / this->a_length, v };
  }

  Vector point(double x, double y, double height) const
  {
    Vector p{};
    for (int k = 0; k < 3; ++k)
    {
      p[k] = this->origin[k] + x * this->e1[k] + y * this->e2[k] + height * this->normal[k];
    }
    return p;
  }
};

/// One row of the lattice: its first vertex's plane coordinates and its vertex count.
struct Row
{
  double x = 0, y = 0;
  int count = 0;
};

/// The rows of a lattice shape: row j lies at v = j / rows; its vertices are an edge apart,
/// from the cell's slanted side, shifted so that consecutive rows are offset by half an edge.
std::vector<Row> row_layout(const PlaneFrame& frame, const LatticeShape& shape)
{
  const double edge = frame.a_length / shape.columns;
  const double slant = frame.b_along / shape.rows; // how far each row's side moves along a
  const double shift = 0.5 - slant / edge;         // of each row's first vertex, in edges
  std::vector<Row> rows(std::size_t(shape.rows) + 1);
  for (int j = 0; j <= shape.rows; ++j)
  {
    double phase = j * shift - std::floor(j * shift);
    if (phase > 1.0 - 1e-9)
    {
      phase = 0.0;
    }
    Row& row = rows[std::size_t(j)];
    row.x = j * slant + phase * edge;
    row.y = j * frame.b_across / shape.rows;
    row.count = int(std::floor(shape.columns - phase + 1e-9)) + 1;
  }
  return rows;
}

std::size_t vertex_count(const std::vector<Row>& rows)
{
  std::size_t count = 0;
  for (const Row& row : rows)
  {
    count += std::size_t(row.count);
  }
  return count;
}

/// Triangles between two rows (vertex ids `low` and `high` onwards, plane x of each), zipped
/// from left to right: counter-clockwise about the normal.
void zip_rows(const Row& lower, std::int64_t low, const Row& upper, std::int64_t high, double edge,
              std::vector<std::int64_t>& triangles)
{
  int i = 0;
  int k = 0;
  while (i + 1 < lower.count || k + 1 < upper.count)
  {
    const bool advance_lower = k + 1 >= upper.count ||
      (i + 1 < lower.count && lower.x + (i + 1) * edge <= upper.x + (k + 1) * edge);
    if (advance_lower)
    {
      triangles.insert(triangles.end(), { low + i, low + i + 1, high + k });
      ++i;
    }
    else
    {
      triangles.insert(triangles.end(), { low + i, high + k + 1, high + k });
      ++k;
    }
  }
}

/// The Gaussian-weighted mean height of the sheet near plane position (x, y).
double height_at(const PointSearch& search, const std::vector<double>& flat,
                 const std::vector<double>& heights, double x, double y, double smoothing,
                 std::vector<std::size_t>& found)
{
  search.within({ x, y, 0 }, 2.5 * smoothing, found);
  if (found.size() < 3)
  {
    search.nearest({ x, y, 0 }, 8, found);
  }
  double nearest = std::numeric_limits<double>::infinity();
  for (const std::size_t i : found)
  {
    nearest = std::min(nearest, std::hypot(flat[3 * i] - x, flat[3 * i + 1] - y));
  }
  double sum = 0;
  double weights = 0;
  for (const std::size_t i : found)
  {
    const double r = std::hypot(flat[3 * i] - x, flat[3 * i + 1] - y);
    // Relative to the nearest point: far from every point the weights do not all vanish.
    const double w = std::exp(-(r * r - nearest * nearest) / (2 * smoothing * smoothing));
    sum += w * heights[i];
    weights += w;
  }
  return sum / weights;
}
} // namespace

std::optional<SheetCell> periodic_sheet_cell(const std::vector<double>& points,
                                             const PeriodicBox& box)
{
  if (!box.is_set() || points.size() < 3 * 16)
  {
    return std::nullopt;
  }
  Eigen::Matrix3d vectors; // columns a, b, c
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      vectors(c, r) = box.vectors[std::size_t(r)][std::size_t(c)];
    }
  }
  const Eigen::Matrix3d inverse = vectors.inverse();
  const std::size_t n = points.size() / 3;
  std::vector<int> spread;
  for (int axis = 0; axis < 3; ++axis)
  {
    std::vector<double> fractions(n);
    for (std::size_t i = 0; i < n; ++i)
    {
      const double f =
        inverse.row(axis).dot(Eigen::Vector3d(points[3 * i], points[3 * i + 1], points[3 * i + 2]));
      fractions[i] = f - std::floor(f);
    }
    std::sort(fractions.begin(), fractions.end());
    double gap = 1.0 - (fractions.back() - fractions.front());
    for (std::size_t i = 1; i < n; ++i)
    {
      gap = std::max(gap, fractions[i] - fractions[i - 1]);
    }
    if (gap < 0.125)
    {
      spread.push_back(axis);
    }
  }
  if (spread.size() != 2)
  {
    return std::nullopt;
  }
  SheetCell cell;
  for (int k = 0; k < 3; ++k)
  {
    cell.a[k] = box.vectors[std::size_t(spread[0])][std::size_t(k)];
    cell.b[k] = box.vectors[std::size_t(spread[1])][std::size_t(k)];
  }
  const Vector normal = cross(cell.a, cell.b);
  const double length = norm(normal);
  for (int k = 0; k < 3; ++k)
  {
    cell.normal[k] = normal[k] / length;
  }
  Vector mean{ 0, 0, 0 };
  for (std::size_t i = 0; i < n; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      mean[k] += points[3 * i + std::size_t(k)] / double(n);
    }
  }
  const double along_normal = dot(mean, cell.normal);
  for (int k = 0; k < 3; ++k)
  {
    cell.origin[k] = mean[k] - 0.5 * (cell.a[k] + cell.b[k]) - along_normal * cell.normal[k];
  }
  return cell;
}

std::vector<double> with_periodic_images(const std::vector<double>& points, const SheetCell& cell,
                                         double margin)
{
  const PlaneFrame frame(cell);
  const double area = frame.a_length * frame.b_across;
  const double margin_u = margin * norm(cell.b) / area;
  const double margin_v = margin * frame.a_length / area;
  std::vector<double> all = points;
  for (std::size_t i = 0; i + 2 < points.size(); i += 3)
  {
    const Vector plane = frame.coordinates(&points[i]);
    const auto [u, v] = frame.fractions(plane[0], plane[1]);
    for (int du = -1; du <= 1; ++du)
    {
      for (int dv = -1; dv <= 1; ++dv)
      {
        if ((du == 0 && dv == 0) || u + du < -margin_u || u + du > 1 + margin_u ||
            v + dv < -margin_v || v + dv > 1 + margin_v)
        {
          continue;
        }
        for (int k = 0; k < 3; ++k)
        {
          all.push_back(points[i + std::size_t(k)] + du * cell.a[k] + dv * cell.b[k]);
        }
      }
    }
  }
  return all;
}

LatticeShape lattice_shape(const SheetCell& cell, std::size_t vertices, double edge)
{
  const PlaneFrame frame(cell);
  const double row_height = std::sqrt(3.0) / 2;
  const double area = frame.a_length * frame.b_across;
  const double target =
    edge > 0 ? edge : std::sqrt(area / (row_height * double(std::max<std::size_t>(vertices, 4))));
  const int columns = std::max(2, int(std::lround(frame.a_length / target)));
  const int rows = std::max(1, int(std::lround(frame.b_across / (row_height * target))));
  LatticeShape best{ columns, rows };
  if (edge > 0)
  {
    return best;
  }
  double best_score = std::numeric_limits<double>::infinity();
  for (int c = std::max(2, columns - 3); c <= columns + 3; ++c)
  {
    for (int r = std::max(1, rows - 3); r <= rows + 3; ++r)
    {
      const double shape = (frame.b_across / r) / (row_height * frame.a_length / c);
      if (shape < 0.75 || shape > 1.0 / 0.75)
      {
        continue;
      }
      const double count = double(vertex_count(row_layout(frame, { c, r })));
      // A count 5 % off weighs as much as rows 10 % too far apart or too close.
      const double score =
        std::abs(count - double(vertices)) / double(vertices) + 0.5 * std::abs(std::log(shape));
      if (score < best_score)
      {
        best_score = score;
        best = { c, r };
      }
    }
  }
  return best;
}

TriangleMesh sheet_lattice(const SheetCell& cell, const LatticeShape& shape,
                           const std::vector<double>& sheet, double smoothing)
{
  if (sheet.size() < 3)
  {
    throw TopologyError("the membrane's middle sheet has no points to lift the lattice to");
  }
  const PlaneFrame frame(cell);
  std::vector<double> flat;
  std::vector<double> heights;
  for (std::size_t i = 0; i + 2 < sheet.size(); i += 3)
  {
    const Vector plane = frame.coordinates(&sheet[i]);
    flat.insert(flat.end(), { plane[0], plane[1], 0.0 });
    heights.push_back(plane[2]);
  }
  const PointSearch search(flat);
  const std::vector<Row> rows = row_layout(frame, shape);
  const double edge = frame.a_length / shape.columns;
  TriangleMesh mesh;
  std::vector<std::int64_t> first;
  std::vector<std::size_t> found;
  for (const Row& row : rows)
  {
    first.push_back(std::int64_t(mesh.vertex_count()));
    for (int k = 0; k < row.count; ++k)
    {
      const double x = row.x + k * edge;
      const Vector p =
        frame.point(x, row.y, height_at(search, flat, heights, x, row.y, smoothing, found));
      mesh.points.insert(mesh.points.end(), p.begin(), p.end());
    }
  }
  for (std::size_t j = 0; j + 1 < rows.size(); ++j)
  {
    zip_rows(rows[j], first[j], rows[j + 1], first[j + 1], edge, mesh.triangles);
  }
  return mesh;
}

} // namespace mesolens
