// SPDX-License-Identifier: GPL-3.0-or-later
#include "cutaway/detail/angle_repair.h"

#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

namespace mesolens {

namespace {
using Point = RepairKernel::Point_3;
using Vector = RepairKernel::Vector_3;
using VertexIndex = RepairMesh::Vertex_index;
using HalfedgeIndex = RepairMesh::Halfedge_index;
using FaceIndex = RepairMesh::Face_index;

constexpr double degrees = 180.0 / 3.14159265358979323846;
/// Below this cosine between two triangles' normals their edge is a crease: not flipped.
const double crease_cosine = std::cos(40.0 / degrees);
/// A move or collapse may tilt a triangle by at most 60°.
constexpr double tilt_cosine = 0.5;

using Triangle = std::array<Point, 3>;

/// The triangle's three corner angles, degrees.
std::array<double, 3> corner_angles(const Triangle& t)
{
  std::array<double, 3> angles{};
  for (int k = 0; k < 3; ++k)
  {
    const Vector u = t[(k + 1) % 3] - t[k];
    const Vector v = t[(k + 2) % 3] - t[k];
    angles[k] = std::atan2(std::sqrt(CGAL::cross_product(u, v).squared_length()), u * v) * degrees;
  }
  return angles;
}

double smallest_angle(const Triangle& t)
{
  const auto angles = corner_angles(t);
  return std::min({ angles[0], angles[1], angles[2] });
}

Vector unit_normal(const Triangle& t)
{
  const Vector n = CGAL::cross_product(t[1] - t[0], t[2] - t[0]);
  const double length = std::sqrt(n.squared_length());
  return length > 0 ? n / length : Vector(0, 0, 0);
}

/// The repair's state: the mesh, its shape before the repair, and the goal.
class AngleRepair
{
public:
  AngleRepair(RepairMesh& mesh, double goal)
    : Mesh(mesh)
    , Reference(mesh)
    , Goal(goal)
  {
    this->Surface = std::make_unique<RepairSurfaceTree>(
      faces(this->Reference).first, faces(this->Reference).second, this->Reference);
    this->Surface->accelerate_distance_queries();
    this->TrimsLeft = std::max<std::size_t>(1, mesh.number_of_faces() / 20);
  }

  Triangle corners(FaceIndex f) const
  {
    const HalfedgeIndex h = this->Mesh.halfedge(f);
    return { this->Mesh.point(this->Mesh.source(h)), this->Mesh.point(this->Mesh.target(h)),
             this->Mesh.point(this->Mesh.target(this->Mesh.next(h))) };
  }

  /// The corners of f with `moved` (and `also`, if valid) put at `position`.
  Triangle corners_with(FaceIndex f, VertexIndex moved, VertexIndex also,
                        const Point& position) const
  {
    Triangle t;
    int k = 0;
    for (const VertexIndex v : CGAL::vertices_around_face(this->Mesh.halfedge(f), this->Mesh))
    {
      t[k++] = (v == moved || v == also) ? position : this->Mesh.point(v);
    }
    return t;
  }

  std::vector<FaceIndex> bad_faces() const
  {
    std::vector<FaceIndex> bad;
    for (const FaceIndex f : this->Mesh.faces())
    {
      if (smallest_angle(this->corners(f)) < this->Goal)
      {
        bad.push_back(f);
      }
    }
    return bad;
  }

  bool flip_pass();
  bool smooth_pass(const std::vector<FaceIndex>& bad);
  bool collapse_pass(const std::vector<FaceIndex>& bad);
  bool trim_pass(const std::vector<FaceIndex>& bad);

private:
  Point project(const Point& p) const
  {
    return this->Surface->closest_point(p);
  }
  bool flip_improves(HalfedgeIndex h) const;
  /// The smallest angle around `v` with it at `position`; -1 when a triangle would tilt by
  /// more than 60°.
  double star_smallest(VertexIndex v, const Point& position) const;
  /// Where a vertex's neighbours pull it (their centroid; on the boundary the midpoint of its
  /// boundary neighbours where it is nearly straight, else where it is), and its star's normal
  /// and mean edge.
  struct Pull
  {
    Point target;
    Vector normal;
    double mean_edge = 0;
  };
  Pull pull_on(VertexIndex v) const;
  bool try_move(VertexIndex v);
  bool collapse_improves(HalfedgeIndex h, const Point& position) const;
  bool try_collapse(FaceIndex f);
  bool try_trim(FaceIndex f);

  RepairMesh& Mesh;
  RepairMesh Reference;
  std::unique_ptr<RepairSurfaceTree> Surface;
  double Goal;
  std::size_t TrimsLeft = 0; ///< at most 5 % of the triangles are trimmed off the boundary
};

bool AngleRepair::flip_improves(HalfedgeIndex h) const
{
  const RepairMesh& m = this->Mesh;
  const HalfedgeIndex o = m.opposite(h);
  const VertexIndex a = m.source(h), b = m.target(h);
  const VertexIndex c = m.target(m.next(h)), d = m.target(m.next(o));
  if (c == d || m.halfedge(c, d) != RepairMesh::null_halfedge())
  {
    return false;
  }
  // Each end keeps at least three triangles (two on the boundary).
  const auto keeps_enough = [&](VertexIndex v) { return m.degree(v) > (m.is_border(v) ? 3u : 4u); };
  if (!keeps_enough(a) || !keeps_enough(b))
  {
    return false;
  }
  const Triangle old1{ m.point(a), m.point(b), m.point(c) };
  const Triangle old2{ m.point(b), m.point(a), m.point(d) };
  const Triangle new1{ m.point(a), m.point(d), m.point(c) };
  const Triangle new2{ m.point(d), m.point(b), m.point(c) };
  const Vector n1 = unit_normal(old1), n2 = unit_normal(old2);
  if (n1 * n2 < crease_cosine)
  {
    return false;
  }
  const Vector mean = n1 + n2;
  const double length = std::sqrt(mean.squared_length());
  if (!(length > 0) || unit_normal(new1) * mean < tilt_cosine * length ||
      unit_normal(new2) * mean < tilt_cosine * length)
  {
    return false;
  }
  return std::min(smallest_angle(new1), smallest_angle(new2)) >
    std::min(smallest_angle(old1), smallest_angle(old2)) + 1e-6;
}

bool AngleRepair::flip_pass()
{
  bool any = false;
  for (int sweep = 0; sweep < 10; ++sweep)
  {
    bool changed = false;
    for (const auto e : this->Mesh.edges())
    {
      if (this->Mesh.is_border(e))
      {
        continue;
      }
      const HalfedgeIndex h = this->Mesh.halfedge(e);
      if (this->flip_improves(h))
      {
        CGAL::Euler::flip_edge(h, this->Mesh);
        changed = true;
      }
    }
    any = any || changed;
    if (!changed)
    {
      break;
    }
  }
  return any;
}

double AngleRepair::star_smallest(VertexIndex v, const Point& position) const
{
  double smallest = 180;
  for (const FaceIndex f : CGAL::faces_around_target(this->Mesh.halfedge(v), this->Mesh))
  {
    if (f == RepairMesh::null_face())
    {
      continue;
    }
    const Triangle new_corners = this->corners_with(f, v, VertexIndex(), position);
    if (unit_normal(new_corners) * unit_normal(this->corners(f)) < tilt_cosine)
    {
      return -1;
    }
    smallest = std::min(smallest, smallest_angle(new_corners));
  }
  return smallest;
}

AngleRepair::Pull AngleRepair::pull_on(VertexIndex v) const
{
  const RepairMesh& m = this->Mesh;
  const Point here = m.point(v);
  Pull pull;
  bool on_boundary = false;
  Point boundary_target = here;
  Vector sum(0, 0, 0);
  Vector normal(0, 0, 0);
  double edges = 0;
  int count = 0;
  for (const HalfedgeIndex h : CGAL::halfedges_around_target(m.halfedge(v), m))
  {
    const Point& w = m.point(m.source(h));
    sum = sum + (w - CGAL::ORIGIN);
    edges += std::sqrt(CGAL::squared_distance(here, w));
    ++count;
    if (!m.is_border(h))
    {
      normal = normal + CGAL::cross_product(m.point(m.target(m.next(h))) - here, w - here);
    }
    else
    {
      // On the boundary: to the midpoint of the boundary neighbours where it is nearly
      // straight, else nowhere.
      const Point before = m.point(m.source(h));
      const Point after = m.point(m.target(m.next(h)));
      const Vector u = before - here, t = after - here;
      const double turn =
        std::atan2(std::sqrt(CGAL::cross_product(u, t).squared_length()), u * t) * degrees;
      boundary_target = turn >= 150.0 ? CGAL::midpoint(before, after) : here;
      on_boundary = true;
    }
  }
  pull.target = on_boundary ? boundary_target : CGAL::ORIGIN + sum / double(count);
  const double length = std::sqrt(normal.squared_length());
  pull.normal = length > 0 ? normal / length : Vector(0, 0, 0);
  pull.mean_edge = edges / double(count);
  return pull;
}

bool AngleRepair::try_move(VertexIndex v)
{
  RepairMesh& m = this->Mesh;
  const Point here = m.point(v);
  const double start = this->star_smallest(v, here);
  Point best_position = here;
  double best = start;
  const auto consider = [&](const Point& candidate) {
    const Point projected = this->project(candidate);
    const double value = this->star_smallest(v, projected);
    if (value > best + 1e-9)
    {
      best = value;
      best_position = projected;
      return true;
    }
    return false;
  };
  // Where the neighbours pull, all, half and a quarter of the way.
  const Pull pull = this->pull_on(v);
  for (const double step : { 1.0, 0.5, 0.25 })
  {
    consider(here + step * (pull.target - here));
  }
  // Then a pattern search in the tangent plane: eight directions, steps from a quarter of the
  // mean edge down.
  if (pull.normal.squared_length() > 0)
  {
    const Vector seed = std::abs(pull.normal.x()) < 0.9 ? Vector(1, 0, 0) : Vector(0, 1, 0);
    Vector across = CGAL::cross_product(pull.normal, seed);
    across = across / std::sqrt(across.squared_length());
    const Vector other = CGAL::cross_product(pull.normal, across);
    for (const double scale : { 0.25, 1.0 / 12, 1.0 / 36 })
    {
      bool improved = true;
      for (int walk = 0; walk < 6 && improved; ++walk)
      {
        const Point from = best_position;
        improved = false;
        for (int k = 0; k < 8; ++k)
        {
          const double angle = k * 3.14159265358979323846 / 4;
          improved = consider(from +
                              scale * pull.mean_edge *
                                (std::cos(angle) * across + std::sin(angle) * other)) ||
            improved;
        }
      }
    }
  }
  if (best > start + 1e-6)
  {
    m.point(v) = best_position;
    return true;
  }
  return false;
}

bool AngleRepair::smooth_pass(const std::vector<FaceIndex>& bad)
{
  std::vector<VertexIndex> around;
  for (const FaceIndex f : bad)
  {
    for (const VertexIndex v : CGAL::vertices_around_face(this->Mesh.halfedge(f), this->Mesh))
    {
      around.push_back(v);
      for (const VertexIndex w : CGAL::vertices_around_target(this->Mesh.halfedge(v), this->Mesh))
      {
        around.push_back(w);
      }
    }
  }
  std::sort(around.begin(), around.end());
  around.erase(std::unique(around.begin(), around.end()), around.end());
  bool any = false;
  for (int sweep = 0; sweep < 3; ++sweep)
  {
    for (const VertexIndex v : around)
    {
      any = this->try_move(v) || any;
    }
  }
  return any;
}

bool AngleRepair::collapse_improves(HalfedgeIndex h, const Point& position) const
{
  const RepairMesh& m = this->Mesh;
  const VertexIndex u = m.source(h), v = m.target(h);
  const FaceIndex gone1 = m.face(h), gone2 = m.face(m.opposite(h));
  double before = 180;
  double after = 180;
  for (const VertexIndex end : { u, v })
  {
    for (const FaceIndex f : CGAL::faces_around_target(m.halfedge(end), m))
    {
      if (f == RepairMesh::null_face())
      {
        continue;
      }
      const Triangle old_corners = this->corners(f);
      before = std::min(before, smallest_angle(old_corners));
      if (f == gone1 || f == gone2)
      {
        continue;
      }
      const Triangle new_corners = this->corners_with(f, u, v, position);
      if (unit_normal(new_corners) * unit_normal(old_corners) < tilt_cosine)
      {
        return false;
      }
      after = std::min(after, smallest_angle(new_corners));
    }
  }
  return after > before + 1e-6 || after >= this->Goal;
}

bool AngleRepair::try_collapse(FaceIndex f)
{
  RepairMesh& m = this->Mesh;
  // Its edges from the shortest (the one opposite the smallest angle) up.
  std::vector<std::pair<double, HalfedgeIndex>> edges;
  for (const HalfedgeIndex h : CGAL::halfedges_around_face(m.halfedge(f), m))
  {
    edges.emplace_back(CGAL::squared_distance(m.point(m.source(h)), m.point(m.target(h))), h);
  }
  std::sort(edges.begin(), edges.end());
  for (const auto& [length, h] : edges)
  {
    (void)length;
    const VertexIndex u = m.source(h), v = m.target(h);
    const bool u_border = m.is_border(u), v_border = m.is_border(v);
    if (u_border && v_border && !m.is_border(m.edge(h)))
    {
      continue; // would pinch the surface at its boundary
    }
    const Point position = u_border != v_border
      ? m.point(u_border ? u : v)
      : this->project(CGAL::midpoint(m.point(u), m.point(v)));
    if (!CGAL::Euler::does_satisfy_link_condition(m.edge(h), m) ||
        !this->collapse_improves(h, position))
    {
      continue;
    }
    const VertexIndex kept = CGAL::Euler::collapse_edge(m.edge(h), m);
    m.point(kept) = position;
    return true;
  }
  return false;
}

bool AngleRepair::try_trim(FaceIndex f)
{
  RepairMesh& m = this->Mesh;
  int border_edges = 0;
  HalfedgeIndex on_border = RepairMesh::null_halfedge();
  for (const HalfedgeIndex h : CGAL::halfedges_around_face(m.halfedge(f), m))
  {
    if (m.is_border(m.opposite(h)))
    {
      ++border_edges;
      on_border = h;
    }
  }
  if (border_edges == 0 || border_edges == 3 || this->TrimsLeft == 0)
  {
    return false;
  }
  // With one boundary edge, its opposite corner joins the boundary: unless it is on it
  // already, where the sheet would be pinched. An ear's tip goes with it.
  if (border_edges == 1 && m.is_border(m.target(m.next(on_border))))
  {
    return false;
  }
  CGAL::Euler::remove_face(on_border, m);
  --this->TrimsLeft;
  return true;
}

bool AngleRepair::trim_pass(const std::vector<FaceIndex>& bad)
{
  bool any = false;
  for (const FaceIndex f : bad)
  {
    if (!this->Mesh.is_removed(f) && smallest_angle(this->corners(f)) < this->Goal)
    {
      any = this->try_trim(f) || any;
    }
  }
  return any;
}

bool AngleRepair::collapse_pass(const std::vector<FaceIndex>& bad)
{
  bool any = false;
  for (const FaceIndex f : bad)
  {
    if (this->Mesh.is_removed(f) || smallest_angle(this->corners(f)) >= this->Goal)
    {
      continue;
    }
    any = this->try_collapse(f) || any;
  }
  return any;
}
} // namespace

AngleRange angle_range(const RepairMesh& mesh)
{
  AngleRange range;
  for (const FaceIndex f : mesh.faces())
  {
    const HalfedgeIndex h = mesh.halfedge(f);
    const auto angles = corner_angles({ mesh.point(mesh.source(h)), mesh.point(mesh.target(h)),
                                        mesh.point(mesh.target(mesh.next(h))) });
    for (const double angle : angles)
    {
      range.smallest = std::min(range.smallest, angle);
      range.largest = std::max(range.largest, angle);
    }
  }
  return range;
}

AngleRange repair_angles(RepairMesh& mesh, double goal, int rounds)
{
  AngleRepair repair(mesh, goal);
  repair.flip_pass();
  // Rounds that stopped helping are not repeated: where the moves only trade one bad triangle
  // for another, five rounds in a row without fewer bad triangles than ever end the repair
  // (it used to run all its rounds there, seconds on a mesh of a few hundred triangles).
  std::size_t fewest_bad = std::numeric_limits<std::size_t>::max();
  int rounds_without_progress = 0;
  for (int round = 0; round < rounds; ++round)
  {
    const std::vector<FaceIndex> bad = repair.bad_faces();
    if (bad.empty())
    {
      break;
    }
    if (bad.size() < fewest_bad)
    {
      fewest_bad = bad.size();
      rounds_without_progress = 0;
    }
    else if (++rounds_without_progress >= 5)
    {
      break;
    }
    bool changed = repair.smooth_pass(bad);
    changed = repair.flip_pass() || changed;
    changed = repair.collapse_pass(repair.bad_faces()) || changed;
    if (!changed)
    {
      // The last resort, on an open sheet: bad triangles on its boundary go.
      if (!repair.trim_pass(repair.bad_faces()))
      {
        break;
      }
    }
    if (mesh.has_garbage())
    {
      mesh.collect_garbage();
    }
  }
  if (mesh.has_garbage())
  {
    mesh.collect_garbage();
  }
  return angle_range(mesh);
}

} // namespace mesolens
