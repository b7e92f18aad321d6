// SPDX-License-Identifier: GPL-3.0-or-later
#include <Eigen/Dense>

#include "surface/detail/power_cell.h"

#include <algorithm>
#include <functional>

namespace mesolens {

namespace {
using Vec = Eigen::Vector3d;
using Corner = PowerCellWork::Corner;
/// Corners within this of a plane go with those beyond it: what is kept stays a simple
/// polytope (three planes through each corner), and a plane touching it counts as bounding.
constexpr double margin = 1e-9;
constexpr std::int32_t cube_faces = 6;
/// A plane more than this above the highest corner found by climbing is passed by without
/// looking at every corner (far more than the dents that corners moved within the margin make).
constexpr double climb_margin = 1e-6;

/// The corner where u . axis is largest, climbing from `start` along edges (on a convex
/// polytope a corner no neighbour of which lies higher is highest).
std::int32_t highest_corner(const std::vector<Corner>& corners, const Vec& axis, std::int32_t start,
                            double& height)
{
  std::int32_t at = start;
  height = corners[std::size_t(at)].position.dot(axis);
  for (bool climbed = true; climbed;)
  {
    climbed = false;
    for (const std::int32_t next : corners[std::size_t(at)].next)
    {
      const double h = corners[std::size_t(next)].position.dot(axis);
      if (h > height)
      {
        height = h;
        at = next;
        climbed = true;
        break;
      }
    }
  }
  return at;
}

/// Points the edge of `corner` that ends at `from` to `to` instead; false when none does.
bool redirect(Corner& corner, std::int32_t from, std::int32_t to)
{
  const auto at = std::find(corner.next.begin(), corner.next.end(), from);
  if (at == corner.next.end())
  {
    return false;
  }
  *at = to;
  return true;
}

/// The cube, a simple polytope: corner k has coordinates +-1 by the bits of k; the faces
/// x = -1, x = 1, y = -1, ... are planes -1, -2, -3, ... Its edge along the x and y faces runs
/// in z (bit 4), and so on.
void start_from_cube(std::vector<Corner>& corners)
{
  corners.clear();
  for (std::int32_t k = 0; k < 8; ++k)
  {
    const std::int32_t bx = k & 1, by = (k >> 1) & 1, bz = (k >> 2) & 1;
    corners.push_back({ Vec(bx ? 1.0 : -1.0, by ? 1.0 : -1.0, bz ? 1.0 : -1.0),
                        { -1 - bx, -3 - by, -5 - bz },
                        { k ^ 4, k ^ 1, k ^ 2 } });
  }
}

/// Where the corners lie against a plane.
enum class Beyond
{
  None,    ///< every corner is kept
  Some,    ///< some corners go (listed in work.beyond)
  All,     ///< every corner goes, some of them only within the margin
  Clearly, ///< every corner goes, beyond the margin
};

/// Lists the corners beyond `plane` (within the margin) in work.beyond, with each corner's
/// signed distance from it in work.side; all of them are looked at, as a corner moved within
/// the margin may leave a dent no deeper than it that the climb cannot see past.
Beyond corners_beyond(const PowerPlane& plane, PowerCellWork& work)
{
  const std::vector<Corner>& corners = work.corners;
  work.side.resize(corners.size());
  work.beyond.clear();
  bool clearly_beyond = true;
  for (std::size_t c = 0; c < corners.size(); ++c)
  {
    work.side[c] = corners[c].position.dot(plane.axis) - plane.height;
    if (work.side[c] >= -margin)
    {
      work.beyond.push_back(static_cast<std::int32_t>(c));
      clearly_beyond = clearly_beyond && work.side[c] > margin;
    }
  }
  if (work.beyond.empty())
  {
    return Beyond::None;
  }
  if (work.beyond.size() == corners.size())
  {
    return clearly_beyond ? Beyond::Clearly : Beyond::All;
  }
  return Beyond::Some;
}

/// Joins corner `made`, new on plane `shared` (its edge `slot` runs along that plane and the
/// cut), to the other new corner on that plane's face: the first one met waits in
/// work.pending, the second closes the edge. False when a third comes or the slot is taken.
bool join_on_face(std::int32_t made, std::int32_t shared, int slot, PowerCellWork& work)
{
  std::int32_t& first = work.pending[std::size_t(shared + cube_faces)];
  if (first == -1)
  {
    first = made;
    work.pending_planes.push_back(shared);
    return true;
  }
  if (first < 0)
  {
    return false; // a third corner on one face's cut
  }
  Corner& partner = work.corners[std::size_t(first)];
  const std::size_t free_slot = partner.planes[1] == shared ? 1 : 2;
  if (partner.next[free_slot] != -1)
  {
    return false;
  }
  partner.next[free_slot] = made;
  work.corners[std::size_t(made)].next[std::size_t(slot)] = first;
  first = -2; // both met
  return true;
}

/// Gives each edge from a corner beyond plane `cut` to a kept one a new corner where the plane
/// cuts it, and joins the new corners along the cut (a face of a convex polytope meets a plane
/// at two points). False where the cut is not a simple polygon.
bool cut_edges(std::int32_t cut, PowerCellWork& work)
{
  auto& corners = work.corners;
  const auto& side = work.side;
  work.pending_planes.clear();
  const std::size_t old_count = corners.size();
  for (const std::int32_t c : work.beyond)
  {
    for (int e = 0; e < 3; ++e)
    {
      const std::int32_t other = corners[std::size_t(c)].next[std::size_t(e)];
      const double other_side = side[std::size_t(other)];
      if (other_side >= -margin)
      {
        continue;
      }
      const Corner& from = corners[std::size_t(c)];
      const std::int32_t a = from.planes[std::size_t(e)];
      const std::int32_t b = from.planes[std::size_t((e + 1) % 3)];
      // On the edge itself: a corner beyond only by the margin gives its own position.
      const double t =
        std::clamp(side[std::size_t(c)] / (side[std::size_t(c)] - other_side), 0.0, 1.0);
      const Vec position =
        from.position + t * (corners[std::size_t(other)].position - from.position);
      const std::int32_t made = static_cast<std::int32_t>(corners.size());
      corners.push_back({ position, { a, b, cut }, { other, -1, -1 } });
      if (!redirect(corners[std::size_t(other)], c, made))
      {
        return false;
      }
      // Edge 1 runs along b and the cut, edge 2 along the cut and a.
      for (int slot = 1; slot <= 2; ++slot)
      {
        if (!join_on_face(made, slot == 1 ? b : a, slot, work))
        {
          return false;
        }
      }
    }
  }
  bool closed = true;
  for (const std::int32_t shared : work.pending_planes)
  {
    closed = closed && work.pending[std::size_t(shared + cube_faces)] == -2;
    work.pending[std::size_t(shared + cube_faces)] = -1;
  }
  return closed && corners.size() != old_count; // else a face met at one point only
}

/// Removes the corners beyond, the last one moving into each hole (highest holes first, so that
/// the last one is never beyond); no corner left points to one beyond any more. False when an
/// edge back to a moved corner is missing.
bool drop_corners_beyond(PowerCellWork& work)
{
  auto& corners = work.corners;
  std::sort(work.beyond.begin(), work.beyond.end(), std::greater<>());
  for (const std::int32_t hole : work.beyond)
  {
    const std::int32_t last = static_cast<std::int32_t>(corners.size()) - 1;
    if (hole != last)
    {
      corners[std::size_t(hole)] = corners[std::size_t(last)];
      for (const std::int32_t next : corners[std::size_t(hole)].next)
      {
        if (!redirect(corners[std::size_t(next)], last, hole))
        {
          return false;
        }
      }
    }
    corners.pop_back();
  }
  return true;
}

/// Marks the planes through some corner kept as bounding.
void mark_bounding(const std::vector<Corner>& corners, std::vector<char>& bounding)
{
  for (const Corner& corner : corners)
  {
    for (const std::int32_t plane : corner.planes)
    {
      if (plane >= 0)
      {
        bounding[std::size_t(plane)] = 1;
      }
    }
  }
}
} // namespace

int power_cell_faces(const std::vector<PowerPlane>& planes, std::vector<char>& bounding,
                     PowerCellWork& work)
{
  bounding.assign(planes.size(), 0);
  // Where the clipping meets corners it cannot tell apart: every plane counts as bounding.
  const auto mark_all = [&] {
    std::fill(bounding.begin(), bounding.end(), 1);
    return 2;
  };
  start_from_cube(work.corners);
  // Per plane, the first new corner of a cut met on its face (join_on_face()).
  work.pending.assign(planes.size() + cube_faces, -1);
  std::int32_t start = 0;
  for (std::size_t k = 0; k < planes.size(); ++k)
  {
    const PowerPlane& plane = planes[k];
    double top = 0;
    start = highest_corner(work.corners, plane.axis, start, top);
    if (top - plane.height < -climb_margin)
    {
      continue; // the plane holds it all, and will as it shrinks
    }
    switch (corners_beyond(plane, work))
    {
      case Beyond::None:
        continue; // within the climb's margin, but clear of every corner
      case Beyond::Clearly:
        return 0;
      case Beyond::All:
        return mark_all();
      case Beyond::Some:
        break;
    }
    if (!cut_edges(static_cast<std::int32_t>(k), work) || !drop_corners_beyond(work))
    {
      return mark_all();
    }
    start = 0;
  }
  mark_bounding(work.corners, bounding);
  return 1;
}

} // namespace mesolens
