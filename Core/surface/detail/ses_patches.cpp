// SPDX-License-Identifier: GPL-3.0-or-later
#include <Eigen/Dense>

#include "surface/detail/ses_patches.h"

#include "surface/detail/patch_clearance.h"
#include "surface/detail/spherical_triangle.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace mesolens {

namespace {
using Vec = Eigen::Vector3d;
constexpr double pi = 3.14159265358979323846;
constexpr int deepest_split = 6;   // singular patches: at most 4^6 pieces, near the cuts only
constexpr double ball_slack = 1.1; // concave pieces lie within their corner distance: a margin

/// Area and x . n integral of a patch piece.
struct Integral
{
  double area = 0, flux = 0;
  Integral& operator+=(const Integral& other)
  {
    this->area += other.area;
    this->flux += other.flux;
    return *this;
  }
  Integral& operator-=(const Integral& other)
  {
    this->area -= other.area;
    this->flux -= other.flux;
    return *this;
  }
};

/// An angle with its cosine and sine, computed once.
struct Angle
{
  double value = 0, cos = 1, sin = 0;
  explicit Angle(double radians)
    : value(radians)
    , cos(std::cos(radians))
    , sin(std::sin(radians))
  {
  }
};

/// The generating arc of a torus: in the plane of the axis and the radial direction d(phi),
/// points o + rho d + p (cos t a + sin t d) for t in the arc's range, where the probe touches
/// the first atom at t = first and the second at t = second.
struct Torus
{
  const SasArc* arc = nullptr;
  double probe = 0;
  double first = 0, second = 0;
  double first_radius = 0, second_radius = 0; ///< the atoms' inflated radii, |C - c|

  /// Whether no accessible position but the torus's own can cut it (see
  /// torus_clear_of_every_position()): the probe does not pass between the atoms and the
  /// generating arc is narrow enough.
  bool sheltered() const
  {
    return this->arc->radius >= this->probe &&
      torus_clear_of_every_position(this->probe, this->first_radius, this->second_radius,
                                    std::abs(this->second - this->first));
  }

  Vec point(const Angle& phi, const Angle& t) const
  {
    const Vec d = phi.cos * this->arc->e1 + phi.sin * this->arc->e2;
    return this->arc->centre + this->arc->radius * d +
      this->probe * (t.cos * this->arc->axis + t.sin * d);
  }

  /// The point in the middle of the piece over [phi0, phi1] x [t0, t1].
  Vec middle(const Angle& phi0, const Angle& phi1, const Angle& t0, const Angle& t1) const
  {
    return this->point(Angle(0.5 * (phi0.value + phi1.value)), Angle(0.5 * (t0.value + t1.value)));
  }

  /// How far the piece over [phi0, phi1] x [t0, t1] reaches from `middle`, exactly. For each t
  /// the squared distance grows with |phi - phi_m| (its coefficient in -cos(phi - phi_m) is
  /// 2 (rho + p sin t)(rho + p sin t_m), distances to the axis, >= 0), so the farthest point
  /// lies on an azimuth edge, where it is the maximum of a sinusoid in t.
  double reach(const Vec& middle, const Angle& phi0, const Angle& phi1, const Angle& t0,
               const Angle& t1) const
  {
    const SasArc& a = *this->arc;
    const double p = this->probe;
    double farthest = 0;
    for (const Angle* phi : { &phi0, &phi1 })
    {
      const Vec d = phi->cos * a.e1 + phi->sin * a.e2;
      const Vec u = a.centre + a.radius * d - middle;
      // max over [t0, t1] of x cos t + y sin t.
      const double most =
        -least_sinusoid(-u.dot(a.axis), -u.dot(d), t0.cos, t0.sin, t1.cos, t1.sin);
      farthest = std::max(farthest, u.squaredNorm() + p * p + 2.0 * p * most);
    }
    return std::sqrt(std::max(0.0, farthest));
  }

  /// The piece over azimuths [phi0, phi1] and arc angles [t0, t1] (where the distance to the
  /// axis, rho + p sin t, is >= 0): area = int p (rho + p sin t) dt dphi, and with the outward
  /// normal n = -(cos t a + sin t d), x . n = -(o.a cos t + (o.d + rho) sin t + p).
  Integral piece(const Angle& phi0, const Angle& phi1, const Angle& t0, const Angle& t1) const
  {
    const SasArc& a = *this->arc;
    const double p = this->probe, rho = a.radius, span = phi1.value - phi0.value,
                 dt = t1.value - t0.value;
    const Vec along_d = a.e1 * (phi1.sin - phi0.sin) - a.e2 * (phi1.cos - phi0.cos);
    const double c_int = t1.sin - t0.sin;
    const double s_int = -(t1.cos - t0.cos);
    const double sc_int = 0.5 * (t1.sin * t1.sin - t0.sin * t0.sin);
    const double ss_int = 0.5 * dt - 0.5 * (t1.sin * t1.cos - t0.sin * t0.cos);
    const double A = a.centre.dot(a.axis) * span;
    const double B = a.centre.dot(along_d) + rho * span;
    const double C = p * span;
    Integral result;
    result.area = span * p * (rho * dt + p * s_int);
    result.flux = -p *
      (rho * A * c_int + (rho * B + p * C) * s_int + rho * C * dt + p * A * sc_int +
       p * B * ss_int);
    return result;
  }
};

/// A spherical triangle on the probe at `centre` (corners unit vectors, counter-clockwise seen
/// from outside the probe): area p^2 E, and with n = -u, x . n = -(centre . u + p).
Integral concave_piece(const Vec& centre, double p, const Vec& a, const Vec& b, const Vec& c)
{
  const double triple = a.dot(b.cross(c));
  const double excess = 2.0 * std::atan2(std::abs(triple), 1.0 + a.dot(b) + b.dot(c) + c.dot(a));
  // The integral of u over a spherical polygon: half the sum over its edges of the edge's angle
  // times the unit normal of its great circle.
  Vec mean_direction = Vec::Zero();
  const Vec corners[3] = { a, b, c };
  for (int k = 0; k < 3; ++k)
  {
    const Vec& from = corners[k];
    const Vec& to = corners[(k + 1) % 3];
    const Vec normal = from.cross(to);
    const double length = normal.norm();
    if (length > 0)
    {
      mean_direction += 0.5 * std::atan2(length, from.dot(to)) * normal / length;
    }
  }
  Integral result;
  result.area = p * p * excess;
  result.flux = -(centre.dot(p * p * mean_direction) + p * result.area);
  return result;
}

/// The torus that probe `p` sweeps rolling along `arc` (of the atoms `centres`).
Torus torus_of(const SasArc& arc, const std::vector<Vec>& centres, double p)
{
  Torus torus;
  torus.arc = &arc;
  torus.probe = p;
  const double first_height = (centres[arc.first] - arc.centre).dot(arc.axis);
  const double second_height = (centres[arc.second] - arc.centre).dot(arc.axis);
  torus.first = std::atan2(-arc.radius, first_height);
  torus.second = std::atan2(-arc.radius, second_height);
  torus.first_radius = std::hypot(arc.radius, first_height);
  torus.second_radius = std::hypot(arc.radius, second_height);
  return torus;
}

/// Calls `visit(phi0, phi1, t0, t1)` with the pieces of the torus's patch: at most 60 degrees
/// of azimuth each, over the arc angles where it belongs to the surface. Where rho < p the
/// probe passes between the atoms: the part beyond the axis lies within p of the probe's
/// neighbouring positions on the same arc, and is cut away.
template<typename Visit>
void for_torus_pieces(const Torus& torus, Visit&& visit)
{
  const SasArc& arc = *torus.arc;
  const double rho = arc.radius, p = torus.probe;
  std::array<std::pair<double, double>, 2> ranges{};
  int range_count = 0;
  if (rho >= p)
  {
    ranges[range_count++] = { torus.first, torus.second };
  }
  else
  {
    const double beta = std::asin(rho / p);
    if (torus.first < -pi + beta)
    {
      ranges[range_count++] = { torus.first, std::min(torus.second, -pi + beta) };
    }
    if (torus.second > -beta)
    {
      ranges[range_count++] = { std::max(torus.first, -beta), torus.second };
    }
  }
  const int parts = std::max(1, static_cast<int>(std::ceil(arc.span / (pi / 3))));
  for (int part = 0; part < parts; ++part)
  {
    const Angle phi0(arc.start + arc.span * part / parts);
    const Angle phi1(arc.start + arc.span * (part + 1) / parts);
    for (int r = 0; r < range_count; ++r)
    {
      visit(phi0, phi1, Angle(ranges[std::size_t(r)].first), Angle(ranges[std::size_t(r)].second));
    }
  }
}

/// What may cut a torus: probe positions (arcs, vertices) touching neither of its atoms. Those
/// that touch one are its neighbours on the surface and meet it only at its edges; positions on
/// a single atom (faces) never reach a patch between two others.
ProbeDistance::Filter torus_cutters(const SasArc& arc)
{
  ProbeDistance::Filter foreign;
  foreign.mode = ProbeDistance::Filter::Mode::TorusCutters;
  foreign.atoms = { arc.first, arc.second, arc.second };
  return foreign;
}

/// What may cut a concave patch, besides other probes overlapping it: the arcs touching none of
/// its atoms, and those between two of them where the probe passes between that pair. The other
/// pieces are its neighbours on the surface and meet it only at its edges.
ProbeDistance::Filter concave_cutters(const SasVertex& vertex, double p)
{
  ProbeDistance::Filter foreign;
  foreign.mode = ProbeDistance::Filter::Mode::ConcaveCutters;
  foreign.atoms = vertex.spheres;
  foreign.probe = p;
  return foreign;
}

/// A concave patch: its corners' directions from the probe's centre (counter-clockwise seen
/// from outside the probe), and a ball holding it. The patch lies within the corners' cap about
/// its middle direction (under 90 degrees, so convex), whose chord is at most p times the
/// farthest corner's distance.
struct ConcavePatch
{
  Vec u[3];
  Vec middle;     ///< the ball's centre, on the patch
  double reach;   ///< the ball's radius, with a margin
  bool sheltered; ///< no accessible position but its own can cut it

  ConcavePatch(const SasVertex& vertex, const std::vector<Vec>& centres, double p)
  {
    double radii[3];
    for (int s = 0; s < 3; ++s)
    {
      const Vec offset = centres[vertex.spheres[std::size_t(s)]] - vertex.position;
      radii[s] = offset.norm();
      this->u[s] = offset / radii[s];
    }
    if (this->u[0].dot(this->u[1].cross(this->u[2])) < 0)
    {
      std::swap(this->u[1], this->u[2]);
    }
    const Vec direction = (this->u[0] + this->u[1] + this->u[2]).normalized();
    this->middle = vertex.position + p * direction;
    this->reach = ball_slack * p *
      std::max({ (direction - this->u[0]).norm(), (direction - this->u[1]).norm(),
                 (direction - this->u[2]).norm() });
    this->sheltered = concave_clear_of_every_position(p, this->u, radii);
  }
};

/// Splits a patch until each piece is certainly kept: when every position foreign to the patch
/// is farther than p plus its size. At the deepest split, a piece counts by the fraction of it
/// where the clearance (distance to foreign positions less p), interpolated linearly between
/// its corners, is positive: second-order accurate in its size. (Pieces certainly cut away, all
/// probe positions nearer than p less their size, are too rare on molecules to test for: the cut
/// regions are thin.)
struct Splitter
{
  const ProbeDistance* distance = nullptr;
  const ProbeDistance::Filter* foreign = nullptr;
  double probe = 0;
  /// The foreign pieces that may cut the patch (see gather_cutters()), with the spheres around
  /// it: queries look at these alone, so distances are those to possible cutters, exact
  /// wherever they are below p (where the clearance's sign is decided). Null: none may.
  const LocalPieces* cutters = nullptr;

  bool none() const
  {
    return !this->cutters || (this->cutters->arcs.empty() && this->cutters->vertices.empty());
  }

  /// Whether a piece around `middle` reaching `size` is certainly kept whole.
  bool kept(const Vec& middle, double size) const
  {
    const double limit = this->probe + size; // the search goes no farther than the test needs
    return this->none() ||
      this->distance->closest(*this->cutters, middle, *this->foreign, limit).distance >= limit;
  }

  /// Distance to the foreign positions less p (> 0: kept), at most p.
  double clearance(const Vec& x) const
  {
    return this->none()
      ? this->probe
      : this->distance->closest(*this->cutters, x, *this->foreign, 2.0 * this->probe).distance -
        this->probe;
  }
};

/// Appends to `arcs` those `foreign` admits with an exposed point nearer than `reach` to `x`
/// (from the index, then by their exact distance): the arcs that may cut a patch lying within
/// `reach` less the probe radius of `x`.
void foreign_arcs_near(const ProbeDistance& distance, const ProbeDistance::Filter& foreign,
                       const Vec& x, double reach, std::vector<std::uint32_t>& arcs)
{
  const std::size_t first = arcs.size();
  distance.arcs_within(x, reach, arcs, foreign);
  arcs.erase(std::remove_if(arcs.begin() + std::ptrdiff_t(first), arcs.end(),
                            [&](std::uint32_t k) {
                              double d = 0;
                              return !distance.arc_nearer(k, x, reach, d);
                            }),
             arcs.end());
}

/// Buffers of gather_cutters(), reused from patch to patch.
struct CutterSearch
{
  std::vector<std::uint32_t> arcs, vertices;
  LocalPieces cutters;
};

/// The pieces `foreign` admits that may come within p of a patch lying within `radius` of
/// `centre`: those within p of that ball (most patches have none: two index queries settle
/// them) that `clear_of_arc` or `clear_of_vertex` do not certify (see patch_clearance.h). False
/// when there are none; else `search.cutters` holds them with the spheres reaching the ball.
template<typename ClearOfArc, typename ClearOfVertex>
bool gather_cutters(const ProbeDistance& distance, const SasBoundary& boundary,
                    const ProbeDistance::Filter& foreign, double p, const Vec& centre,
                    double radius, ClearOfArc&& clear_of_arc, ClearOfVertex&& clear_of_vertex,
                    CutterSearch& search)
{
  search.arcs.clear();
  const double reach = radius + p;
  foreign_arcs_near(distance, foreign, centre, reach, search.arcs);
  search.arcs.erase(std::remove_if(search.arcs.begin(), search.arcs.end(),
                                   [&](std::uint32_t k) { return clear_of_arc(boundary.arcs[k]); }),
                    search.arcs.end());
  search.vertices.clear();
  if (foreign.admits_vertices())
  {
    distance.vertices_within(centre, reach, [&](std::uint32_t k) {
      if (foreign.admits(boundary.vertices[k]) && !clear_of_vertex(boundary.vertices[k]))
      {
        search.vertices.push_back(k);
      }
    });
  }
  if (search.arcs.empty() && search.vertices.empty())
  {
    return false;
  }
  // The rare patch something may cut: the pieces around it, less those certified clear.
  LocalPieces& cutters = search.cutters;
  distance.gather(centre, radius, p, cutters, true);
  std::sort(search.vertices.begin(), search.vertices.end());
  const auto listed = [](const std::vector<std::uint32_t>& kept) {
    return [&kept](const std::pair<double, std::uint32_t>& piece) {
      return !std::binary_search(kept.begin(), kept.end(), piece.second);
    };
  };
  cutters.arcs.erase(std::remove_if(cutters.arcs.begin(), cutters.arcs.end(), listed(search.arcs)),
                     cutters.arcs.end());
  cutters.vertices.erase(
    std::remove_if(cutters.vertices.begin(), cutters.vertices.end(), listed(search.vertices)),
    cutters.vertices.end());
  // The clearance asks up to 2 p: the pieces left are all that can bring it below p.
  cutters.limit = 2.0 * p;
  return true;
}

/// The part of a triangle where the linear interpolant of corner values is positive.
double positive_fraction(double g0, double g1, double g2)
{
  const double g[3] = { g0, g1, g2 };
  const int positive = (g0 > 0) + (g1 > 0) + (g2 > 0);
  if (positive == 0 || positive == 3)
  {
    return positive == 3 ? 1.0 : 0.0;
  }
  // The corner alone on its side cuts off a triangle t1 t2 of the whole.
  const bool lone_sign = positive == 1;
  int lone = 0;
  for (int k = 0; k < 3; ++k)
  {
    if ((g[k] > 0) == lone_sign)
    {
      lone = k;
    }
  }
  const double a = g[lone], b = g[(lone + 1) % 3], c = g[(lone + 2) % 3];
  const double corner = (a / (a - b)) * (a / (a - c));
  return lone_sign ? corner : 1.0 - corner;
}

/// Into `meeting`, the caps (parts of a probe's sphere inside neighbouring probes) that meet
/// the spherical triangle; false when one of them holds it whole.
bool caps_meeting(const SphericalTriangle& triangle, const std::vector<UnitCap>& caps,
                  std::vector<UnitCap>& meeting)
{
  meeting.clear();
  for (const UnitCap& cap : caps)
  {
    const auto range = triangle.dot_range(cap.axis);
    if (range.second > cap.height)
    {
      if (range.first > cap.height)
      {
        return false;
      }
      meeting.push_back(cap);
    }
  }
  return true;
}

/// A concave patch that only neighbouring probes cut (caps on its sphere), exactly: the part of
/// the probe's unit sphere that neither the caps meeting the triangle nor the hemispheres beyond
/// its three edges cover. False when that arrangement is degenerate (see
/// uncovered_unit_area()): the caller splits the patch instead. `unit_caps` is a buffer.
bool uncovered_concave(const Vec& centre, double p, const Vec (&u)[3],
                       const SphericalTriangle& triangle, const std::vector<UnitCap>& caps,
                       std::vector<UnitCap>& unit_caps, Integral& result)
{
  if (!caps_meeting(triangle, caps, unit_caps))
  {
    result = {}; // wholly inside a neighbour
    return true;
  }
  if (unit_caps.empty())
  {
    result = concave_piece(centre, p, u[0], u[1], u[2]);
    return true;
  }
  for (int k = 0; k < 3; ++k)
  {
    // The triangle (counter-clockwise) lies on the positive side of each edge's great circle.
    unit_caps.push_back({ -u[k].cross(u[(k + 1) % 3]).normalized(), 0.0 });
  }
  double area = 0;
  Vec direction_integral = Vec::Zero();
  if (!uncovered_unit_area(unit_caps, area, direction_integral))
  {
    // Circles through one point (as where a torus's cusp meets the patch): the uncovered part
    // is continuous in the caps, and widening cap k lowers it by 2 pi times its height's
    // change. Heights lowered by distinct amounts of 1e-7 to 2e-7 part the circles far beyond
    // the arrangement's 1e-9 test, and change the area by less than 1.3e-6 sr per cap.
    const std::size_t neighbours = unit_caps.size() - 3;
    for (std::size_t k = 0; k < neighbours; ++k)
    {
      UnitCap& cap = unit_caps[k];
      cap.height = std::max(-1.0, cap.height - 1e-7 * (1.0 + double(k) / double(neighbours)));
    }
    if (!uncovered_unit_area(unit_caps, area, direction_integral))
    {
      return false;
    }
  }
  result.area = p * p * area;
  result.flux = -(centre.dot(p * p * direction_integral) + p * result.area);
  return true;
}

/// Caps meeting the pieces of a concave patch, per depth of the split (reused).
using CapsByDepth = std::array<std::vector<UnitCap>, deepest_split + 1>;

/// What foreign positions take from the part of a concave patch (or piece) that the caps
/// `meeting` it leave, for a piece whose caps' part is known exactly (uncovered_concave()):
/// nothing from a piece no foreign position reaches; at the deepest split, the piece times the
/// fraction the caps leave less the fraction both leave, each interpolated linearly between its
/// corners (second-order accurate, as cut_concave()). One arrangement of the caps for the whole
/// patch, instead of one per piece.
Integral foreign_cut_concave(const Splitter& splitter, const std::vector<UnitCap>& meeting,
                             CapsByDepth& caps_by_depth, const Vec& centre, const Vec& a,
                             const Vec& b, const Vec& c, int depth)
{
  const double p = splitter.probe;
  const Vec middle = (a + b + c).normalized();
  const double size =
    ball_slack * p * std::max({ (middle - a).norm(), (middle - b).norm(), (middle - c).norm() });
  if (splitter.kept(centre + p * middle, size))
  {
    return {}; // out of every foreign position's reach
  }
  if (depth == deepest_split)
  {
    const auto cap_gap = [&](const Vec& u) {
      double g = p;
      for (const UnitCap& cap : meeting)
      {
        g = std::min(g, p * (cap.height - u.dot(cap.axis)));
      }
      return g;
    };
    const auto both = [&](const Vec& u) {
      return std::min(cap_gap(u), splitter.clearance(centre + p * u));
    };
    Integral piece = concave_piece(centre, p, a, b, c);
    const double taken = positive_fraction(cap_gap(a), cap_gap(b), cap_gap(c)) -
      positive_fraction(both(a), both(b), both(c));
    piece.area *= taken;
    piece.flux *= taken;
    return piece;
  }
  const Vec ab = (a + b).normalized(), bc = (b + c).normalized(), ca = (c + a).normalized();
  const Vec children[4][3] = { { a, ab, ca }, { ab, b, bc }, { ca, bc, c }, { ab, bc, ca } };
  std::vector<UnitCap>& child_meeting = caps_by_depth[std::size_t(depth) + 1];
  Integral sum;
  for (const auto& child : children)
  {
    // A child wholly inside a neighbour has nothing left to take.
    if (caps_meeting(SphericalTriangle(child[0], child[1], child[2]), meeting, child_meeting))
    {
      sum += foreign_cut_concave(splitter, child_meeting, caps_by_depth, centre, child[0], child[1],
                                 child[2], depth + 1);
    }
  }
  return sum;
}

/// A concave patch (or a piece of one) that other probes may cut, with `caps` those
/// overlapping it: where the caps' arrangement on it is not degenerate, the part they leave
/// exactly, less what foreign positions take from it (foreign_cut_concave()); else (three
/// circles crossing at one point, as at the cusp of a torus the probe passes through) split,
/// down to the deepest level, where a piece counts by the fraction of it where the clearance
/// from caps and foreign positions, interpolated linearly between its corners, is positive.
/// `unit_caps` is a buffer.
Integral cut_concave(const Splitter& splitter, const std::vector<UnitCap>& caps,
                     CapsByDepth& caps_by_depth, std::vector<UnitCap>& unit_caps, const Vec& centre,
                     const Vec& a, const Vec& b, const Vec& c, int depth)
{
  const double p = splitter.probe;
  std::vector<UnitCap>& meeting = caps_by_depth[std::size_t(depth)];
  const SphericalTriangle triangle(a, b, c);
  if (!caps_meeting(triangle, caps, meeting))
  {
    return {}; // wholly inside a neighbour
  }
  const Vec corners[3] = { a, b, c };
  Integral part;
  if (uncovered_concave(centre, p, corners, triangle, meeting, unit_caps, part))
  {
    part -= foreign_cut_concave(splitter, meeting, caps_by_depth, centre, a, b, c, depth);
    return part;
  }
  if (depth == deepest_split)
  {
    const auto clearance = [&](const Vec& u) {
      double g = splitter.clearance(centre + p * u);
      for (const UnitCap& cap : meeting)
      {
        g = std::min(g, p * (cap.height - u.dot(cap.axis)));
      }
      return g;
    };
    Integral piece = concave_piece(centre, p, a, b, c);
    const double kept = positive_fraction(clearance(a), clearance(b), clearance(c));
    piece.area *= kept;
    piece.flux *= kept;
    return piece;
  }
  const Vec ab = (a + b).normalized(), bc = (b + c).normalized(), ca = (c + a).normalized();
  Integral sum;
  sum += cut_concave(splitter, meeting, caps_by_depth, unit_caps, centre, a, ab, ca, depth + 1);
  sum += cut_concave(splitter, meeting, caps_by_depth, unit_caps, centre, ab, b, bc, depth + 1);
  sum += cut_concave(splitter, meeting, caps_by_depth, unit_caps, centre, ca, bc, c, depth + 1);
  sum += cut_concave(splitter, meeting, caps_by_depth, unit_caps, centre, ab, bc, ca, depth + 1);
  return sum;
}

Integral split_torus(const Splitter& splitter, const Torus& torus, const Angle& phi0,
                     const Angle& phi1, const Angle& t0, const Angle& t1, int depth)
{
  const Angle phi(0.5 * (phi0.value + phi1.value)), t(0.5 * (t0.value + t1.value));
  const Vec middle = torus.point(phi, t);
  if (splitter.kept(middle, torus.reach(middle, phi0, phi1, t0, t1)))
  {
    return torus.piece(phi0, phi1, t0, t1);
  }
  if (depth == deepest_split)
  {
    const double g00 = splitter.clearance(torus.point(phi0, t0));
    const double g10 = splitter.clearance(torus.point(phi1, t0));
    const double g01 = splitter.clearance(torus.point(phi0, t1));
    const double g11 = splitter.clearance(torus.point(phi1, t1));
    const double kept = 0.5 * (positive_fraction(g00, g10, g11) + positive_fraction(g00, g11, g01));
    Integral piece = torus.piece(phi0, phi1, t0, t1);
    piece.area *= kept;
    piece.flux *= kept;
    return piece;
  }
  Integral sum;
  sum += split_torus(splitter, torus, phi0, phi, t0, t, depth + 1);
  sum += split_torus(splitter, torus, phi, phi1, t0, t, depth + 1);
  sum += split_torus(splitter, torus, phi0, phi, t, t1, depth + 1);
  sum += split_torus(splitter, torus, phi, phi1, t, t1, depth + 1);
  return sum;
}
} // namespace

SesPatchIntegrals ses_patch_integrals(const std::vector<Vec>& centres,
                                      const std::vector<double>& atom_radii, double probe,
                                      const SasBoundary& boundary, const ProbeDistance& distance,
                                      const ParallelFor& parallel_for)
{
  SesPatchIntegrals out;
  const double p = probe;
  const std::size_t n = centres.size();
  out.face_area.assign(n, 0.0);
  out.face_volume.assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
  {
    // The exposed part of the inflated sphere, scaled about the centre onto the atom.
    const double r = atom_radii[i], scale = r / (r + p);
    const double area = scale * scale * boundary.area[i];
    out.face_area[i] = area;
    out.face_volume[i] =
      (scale * scale * centres[i].dot(boundary.normal_integral[i]) + r * area) / 3.0;
  }

  const auto& arcs = boundary.arcs;
  const auto& vertices = boundary.vertices;
  out.arc_area.assign(arcs.size(), 0.0);
  out.arc_volume.assign(arcs.size(), 0.0);
  std::vector<char> arc_singular(arcs.size(), 0);
  out.arc_uncut.assign(arcs.size(), 1);
  run_parallel(parallel_for, arcs.size(), [&](std::size_t begin, std::size_t end) {
    CutterSearch search; // reused by the patches of this range
    for (std::size_t k = begin; k < end; ++k)
    {
      const SasArc& arc = arcs[k];
      const Torus torus = torus_of(arc, centres, p);
      const ProbeDistance::Filter foreign = torus_cutters(arc);
      const bool sheltered = torus.sheltered();
      Splitter splitter{ &distance, &foreign, p, &search.cutters };
      Integral total;
      for_torus_pieces(
        torus, [&](const Angle& phi0, const Angle& phi1, const Angle& t0, const Angle& t1) {
          const Integral whole = torus.piece(phi0, phi1, t0, t1);
          if (sheltered)
          {
            total += whole;
            return;
          }
          // Whole when no foreign piece comes within p of the ball around the piece, else when
          // each that does is certified clear of the piece itself.
          const Vec middle = torus.middle(phi0, phi1, t0, t1);
          const double reach = torus.reach(middle, phi0, phi1, t0, t1);
          const TorusPatchPiece piece{ &arc, p, phi0.value, phi1.value, t0.value, t1.value };
          const bool may_be_cut = gather_cutters(
            distance, boundary, foreign, p, middle, reach,
            [&](const SasArc& other) { return torus_clear_of_arc(piece, other); },
            [&](const SasVertex& other) { return torus_clear_of_position(piece, other.position); },
            search);
          if (may_be_cut)
          {
            out.arc_uncut[k] = 0;
          }
          const Integral kept =
            may_be_cut ? split_torus(splitter, torus, phi0, phi1, t0, t1, 0) : whole;
          if (std::abs(kept.area - whole.area) > 1e-12 * std::max(1.0, whole.area))
          {
            arc_singular[k] = 1;
          }
          total += kept;
        });
      // No patch has a negative area: a few ulps below zero, where the torus shrinks to nothing
      // (atoms of no size), are the closed forms' rounding at the torus' scale.
      const double rounding =
        1e-12 * torus.probe * std::max(torus.first_radius, torus.second_radius);
      out.arc_area[k] = total.area < 0 && total.area >= -rounding ? 0.0 : total.area;
      out.arc_volume[k] = total.flux / 3.0;
    }
  });

  out.vertex_area.assign(vertices.size(), 0.0);
  out.vertex_volume.assign(vertices.size(), 0.0);
  std::vector<char> vertex_singular(vertices.size(), 0);
  out.vertex_uncut.assign(vertices.size(), 0);
  run_parallel(parallel_for, vertices.size(), [&](std::size_t begin, std::size_t end) {
    CutterSearch search; // reused by the patches of this range
    CapsByDepth caps_by_depth;
    std::vector<UnitCap> unit_caps;
    for (std::size_t k = begin; k < end; ++k)
    {
      const SasVertex& vertex = vertices[k];
      const Vec& v = vertex.position;
      const ConcavePatch concave(vertex, centres, p);
      const Vec(&u)[3] = concave.u;
      const Integral whole = concave_piece(v, p, u[0], u[1], u[2]);
      if (concave.sheltered)
      {
        out.vertex_uncut[k] = 1;
        out.vertex_area[k] = whole.area;
        out.vertex_volume[k] = whole.flux / 3.0;
        continue;
      }
      // What may cut the concave patch: other probes overlapping this one (at vertices within
      // 2 p), exactly as caps on its sphere; and, by distance, the arcs (see concave_cutters()).
      std::vector<UnitCap> caps;
      distance.vertices_within(v, 2.0 * p, [&](std::uint32_t other) {
        const Vec offset = vertices[other].position - v;
        const double gap = offset.norm();
        if (other != k && gap > 0)
        {
          caps.push_back({ offset / gap, gap / (2.0 * p) });
        }
      });
      const ProbeDistance::Filter foreign = concave_cutters(vertex, p);
      const SphericalTriangle triangle(u[0], u[1], u[2]);
      const bool may_be_cut = gather_cutters(
        distance, boundary, foreign, p, concave.middle, concave.reach,
        [&](const SasArc& other) { return concave_clear_of_arc(v, p, triangle, other); },
        [](const SasVertex&) { return false; }, search);
      const Splitter splitter{ &distance, &foreign, p, may_be_cut ? &search.cutters : nullptr };
      // Uncut (whole): no foreign arc may reach it and no other probe's cap meets it.
      const bool uncut =
        !may_be_cut && caps_meeting(triangle, caps, unit_caps) && unit_caps.empty();
      out.vertex_uncut[k] = uncut ? 1 : 0;
      const Integral patch = uncut
        ? whole
        : cut_concave(splitter, caps, caps_by_depth, unit_caps, v, u[0], u[1], u[2], 0);
      if (std::abs(patch.area - whole.area) > 1e-12 * std::max(1.0, whole.area))
      {
        vertex_singular[k] = 1;
      }
      out.vertex_area[k] = patch.area;
      out.vertex_volume[k] = patch.flux / 3.0;
    }
  });
  out.singular_count =
    static_cast<std::size_t>(std::count(arc_singular.begin(), arc_singular.end(), 1) +
                             std::count(vertex_singular.begin(), vertex_singular.end(), 1));
  return out;
}

namespace {
/// Sorts `items` from `first` on and drops repeats.
void sort_unique(std::vector<std::uint32_t>& items, std::size_t first)
{
  std::sort(items.begin() + std::ptrdiff_t(first), items.end());
  items.erase(std::unique(items.begin() + std::ptrdiff_t(first), items.end()), items.end());
}
} // namespace

void toroidal_patch_cutters(const std::vector<Vec>& centres, double probe,
                            const SasBoundary& boundary, const ProbeDistance& distance,
                            std::uint32_t k, std::vector<std::uint32_t>& arcs,
                            std::vector<std::uint32_t>& vertices)
{
  const SasArc& arc = boundary.arcs[k];
  const Torus torus = torus_of(arc, centres, probe);
  if (torus.sheltered())
  {
    return;
  }
  const ProbeDistance::Filter foreign = torus_cutters(arc);
  const std::size_t first_arc = arcs.size(), first_vertex = vertices.size();
  const auto visit = [&](const Angle& phi0, const Angle& phi1, const Angle& t0, const Angle& t1) {
    // A cutter comes within the probe radius of a point of the piece's ball.
    const Vec middle = torus.middle(phi0, phi1, t0, t1);
    const double reach = torus.reach(middle, phi0, phi1, t0, t1) + probe;
    foreign_arcs_near(distance, foreign, middle, reach, arcs);
    distance.vertices_within(middle, reach, [&](std::uint32_t other) {
      if (foreign.admits(boundary.vertices[other]))
      {
        vertices.push_back(other);
      }
    });
  };
  for_torus_pieces(torus, visit);
  sort_unique(arcs, first_arc);
  sort_unique(vertices, first_vertex);
}

void concave_patch_cutters(const std::vector<Vec>& centres, double probe,
                           const SasBoundary& boundary, const ProbeDistance& distance,
                           std::uint32_t k, std::vector<std::uint32_t>& arcs,
                           std::vector<std::uint32_t>& vertices)
{
  const SasVertex& vertex = boundary.vertices[k];
  const ConcavePatch concave(vertex, centres, probe);
  if (concave.sheltered)
  {
    return;
  }
  const ProbeDistance::Filter foreign = concave_cutters(vertex, probe);
  const std::size_t first_vertex = vertices.size();
  // A cutter comes within the probe radius of a point of the patch's ball.
  const double reach = concave.reach + probe;
  foreign_arcs_near(distance, foreign, concave.middle, reach, arcs);
  distance.vertices_within(vertex.position, 2.0 * probe, [&](std::uint32_t other) {
    if (other != k && (boundary.vertices[other].position - concave.middle).norm() < reach)
    {
      vertices.push_back(other);
    }
  });
  sort_unique(vertices, first_vertex);
}

} // namespace mesolens
