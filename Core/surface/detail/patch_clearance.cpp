// SPDX-License-Identifier: GPL-3.0-or-later
#include <Eigen/Dense>

#include "surface/detail/patch_clearance.h"

#include <CGAL/Distance_3/Point_3_Triangle_3.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

namespace mesolens {

namespace {
using Vec = Eigen::Vector3d;

// Evaluations allowed per test: pieces this close to tangency are rare, and an undecided one
// only costs the caller a split.
constexpr int budget_one_parameter = 96;
constexpr int budget_two_parameters = 256;

/// A torus piece with the cosines and sines of its arc-angle ends, computed once.
struct TorusFrame
{
  const TorusPatchPiece& piece;
  double cos0, sin0, cos1, sin1;

  explicit TorusFrame(const TorusPatchPiece& torus)
    : piece(torus)
    , cos0(std::cos(torus.t0))
    , sin0(std::sin(torus.t0))
    , cos1(std::cos(torus.t1))
    , sin1(std::sin(torus.t1))
  {
  }

  /// min over t in [t0, t1] of a cos t + b sin t.
  double least(double a, double b) const
  {
    return least_sinusoid(a, b, this->cos0, this->sin0, this->cos1, this->sin1);
  }
};

/// The parts of exposed arc `other` (azimuth ranges within its span) whose points lie within
/// `radius` of `x`: only they can come that near. Returns how many (at most 3) went into `ranges`.
int arc_parts_within(const SasArc& other, const Vec& x, double radius,
                     std::array<std::pair<double, double>, 3>& ranges)
{
  constexpr double two_pi = 6.28318530717958647692;
  const Vec v = x - other.centre;
  const double along = v.dot(other.axis), a1 = v.dot(other.e1), a2 = v.dot(other.e2);
  const double off_axis = std::sqrt(a1 * a1 + a2 * a2);
  // |x - C'(psi)|^2 = along^2 + off_axis^2 + radius'^2 - 2 off_axis radius' cos(psi - psi_x).
  const double base = along * along + off_axis * off_axis + other.radius * other.radius;
  const double scale = 2.0 * off_axis * other.radius;
  const double threshold = base - radius * radius; // cos(psi - psi_x) must be >= threshold/scale
  if (threshold <= -scale)
  {
    ranges[0] = { other.start, other.start + other.span };
    return 1;
  }
  if (threshold > scale)
  {
    return 0;
  }
  const double half = std::acos(std::clamp(threshold / scale, -1.0, 1.0));
  double nearest = std::atan2(a2, a1);
  nearest = other.start + std::fmod(std::fmod(nearest - other.start, two_pi) + two_pi, two_pi);
  int count = 0;
  for (int turn = -1; turn <= 1; ++turn)
  {
    const double low = std::max(other.start, nearest + turn * two_pi - half);
    const double high = std::min(other.start + other.span, nearest + turn * two_pi + half);
    if (low <= high)
    {
      ranges[std::size_t(count++)] = { low, high };
    }
  }
  return count;
}

/// Foreign probe positions C'(psi) = centre + radius (cos psi e1 + sin psi e2): an arc's, or
/// a single position (radius 0).
struct ForeignPositions
{
  Vec centre = Vec::Zero(), e1 = Vec::UnitX(), e2 = Vec::UnitY();
  double radius = 0;
};

/// An interval of azimuths with the cosines and sines of its ends, so that halving it needs no
/// trigonometry: under half a turn, the middle's direction is the normalised sum of the ends'.
struct AzimuthRange
{
  double low = 0, high = 0;
  double cos_low = 1, sin_low = 0, cos_high = 1, sin_high = 0;

  static AzimuthRange of(double low, double high)
  {
    return { low, high, std::cos(low), std::sin(low), std::cos(high), std::sin(high) };
  }
  double middle() const
  {
    return 0.5 * (this->low + this->high);
  }
  double half_width() const
  {
    return 0.5 * (this->high - this->low);
  }
  /// The cosine and sine of the middle.
  void middle_direction(double& cos_middle, double& sin_middle) const
  {
    if (this->high - this->low < 3.0)
    {
      const double x = this->cos_low + this->cos_high, y = this->sin_low + this->sin_high;
      const double length = std::sqrt(x * x + y * y);
      cos_middle = x / length;
      sin_middle = y / length;
    }
    else
    {
      cos_middle = std::cos(this->middle());
      sin_middle = std::sin(this->middle());
    }
  }
  AzimuthRange lower(double cos_middle, double sin_middle) const
  {
    return { this->low, this->middle(), this->cos_low, this->sin_low, cos_middle, sin_middle };
  }
  AzimuthRange upper(double cos_middle, double sin_middle) const
  {
    return { this->middle(), this->high, cos_middle, sin_middle, this->cos_high, this->sin_high };
  }
};

// With the torus point x = C(phi) + p n(phi, t), n = cos t a + sin t d(phi), and a foreign
// position w = C'(psi), q = C - w: the gap |x - w|^2 - p^2 = |q|^2 + 2 p (A cos t + B sin t),
// A = q . a, B = q . d, must stay >= 0. Over a box of azimuths (phi, psi) it is bounded below
// by its first-order Taylor expansion at the middle, taken at the box's worst corner (for each
// corner a sinusoid in t, whose minimum is closed-form), less a bound on the second-order
// remainder: with d' = dd/dphi and D' = the foreign circle's unit tangent at psi,
//   d|q|^2/dphi = 2 rho q . d',   dB/dphi = q . d',   dA/dphi = 0,
//   d|q|^2/dpsi = -2 rho' q . D', dA/dpsi = -rho' D' . a,   dB/dpsi = -rho' D' . d,
// and second derivatives of the gap at most 2 (rho + p)(rho + |q|) in phi, 2 rho' (rho' + |q|
// + p) in psi and 2 rho' (rho + p) across. Where |q| >= 2 p the gap is >= 0 whatever t.
bool torus_gap_range(const TorusFrame& frame, const ForeignPositions& other,
                     const AzimuthRange& phi, const AzimuthRange& psi, int& budget)
{
  if (--budget < 0)
  {
    return false;
  }
  const SasArc& arc = *frame.piece.arc;
  const double p = frame.piece.probe, rho = arc.radius, rho_other = other.radius;
  const double phi_delta = phi.half_width(), psi_delta = psi.half_width();
  double cos_phi = 1, sin_phi = 0, cos_psi = 1, sin_psi = 0;
  phi.middle_direction(cos_phi, sin_phi);
  psi.middle_direction(cos_psi, sin_psi);
  const Vec d = cos_phi * arc.e1 + sin_phi * arc.e2;
  const Vec d_turn = -sin_phi * arc.e1 + cos_phi * arc.e2;
  const Vec q =
    arc.centre + rho * d - (other.centre + rho_other * (cos_psi * other.e1 + sin_psi * other.e2));
  const double length = q.norm();
  const double reach = rho * phi_delta + rho_other * psi_delta;
  if (length - reach >= 2.0 * p)
  {
    return true;
  }
  const double squared = length * length;
  const double a = q.dot(arc.axis), b = q.dot(d);
  if (squared + 2.0 * p * frame.least(a, b) < 0)
  {
    return false; // cut at the middle
  }
  const Vec other_turn = -sin_psi * other.e1 + cos_psi * other.e2;
  const double b_phi = q.dot(d_turn);
  const double squared_phi = 2.0 * rho * b_phi, squared_psi = -2.0 * rho_other * q.dot(other_turn);
  const double a_psi = -rho_other * other_turn.dot(arc.axis);
  const double b_psi = -rho_other * other_turn.dot(d);
  double lowest = std::numeric_limits<double>::max();
  for (const double s_phi : { -phi_delta, phi_delta })
  {
    for (const double s_psi : { -psi_delta, psi_delta })
    {
      lowest =
        std::min(lowest,
                 squared + s_phi * squared_phi + s_psi * squared_psi +
                   2.0 * p * frame.least(a + s_psi * a_psi, b + s_phi * b_phi + s_psi * b_psi));
    }
  }
  const double most = length + reach;
  const double phi_phi = 2.0 * (rho + p) * (rho + most);
  const double psi_psi = 2.0 * rho_other * (rho_other + most + p);
  const double phi_psi = 2.0 * rho_other * (rho + p);
  const double remainder = 0.5 *
    (phi_phi * phi_delta * phi_delta + 2.0 * phi_psi * phi_delta * psi_delta +
     psi_psi * psi_delta * psi_delta);
  if (lowest - remainder >= 0)
  {
    return true;
  }
  // Halve the azimuth along which the patch's points move farther.
  if ((rho + p) * phi_delta >= rho_other * psi_delta)
  {
    return torus_gap_range(frame, other, phi.lower(cos_phi, sin_phi), psi, budget) &&
      torus_gap_range(frame, other, phi.upper(cos_phi, sin_phi), psi, budget);
  }
  return torus_gap_range(frame, other, phi, psi.lower(cos_psi, sin_psi), budget) &&
    torus_gap_range(frame, other, phi, psi.upper(cos_psi, sin_psi), budget);
}

// On the concave patch x = v + p u (u in the triangle), with q = v - C'(psi):
// |x - C'|^2 - p^2 = |q|^2 + 2 p q . u >= |q|^2 + 2 p |q| min(u . q/|q|). The minimum is
// 1-Lipschitz in the direction, which turns at most radius'/|q| per radian: the gap changes at
// most by 2 |q| radius' + 4 p radius' per radian.
bool concave_arc_range(const Vec& v, double p, const SphericalTriangle& triangle,
                       const SasArc& other, double low, double high, int& budget)
{
  if (--budget < 0)
  {
    return false;
  }
  const double middle = 0.5 * (low + high), delta = 0.5 * (high - low);
  const Vec q = v - other.point(middle);
  const double length = q.norm();
  const double reach = other.radius * delta;
  if (length - reach >= 2.0 * p)
  {
    return true;
  }
  const double gap =
    length > 0 ? length * length + 2.0 * p * length * triangle.dot_range(q / length).first : 0.0;
  if (gap < 0)
  {
    return false;
  }
  const double most = length + reach;
  const double slope = (2.0 * most + 4.0 * p) * other.radius;
  if (gap >= slope * delta && gap > 0)
  {
    return true;
  }
  return concave_arc_range(v, p, triangle, other, low, middle, budget) &&
    concave_arc_range(v, p, triangle, other, middle, high, budget);
}

} // namespace

bool concave_clear_of_every_position(double probe, const Vec (&directions)[3],
                                     const double (&radii)[3])
{
  // d: the distance from the origin to the flat triangle of the directions.
  using Kernel = CGAL::Simple_cartesian<double>;
  const auto point = [](const Vec& x) { return Kernel::Point_3(x[0], x[1], x[2]); };
  const double d = std::sqrt(CGAL::squared_distance(
    Kernel::Point_3(0, 0, 0),
    Kernel::Triangle_3(point(directions[0]), point(directions[1]), point(directions[2]))));
  return std::min({ radii[0], radii[1], radii[2] }) * d >= probe * (1.0 + 1e-9);
}

bool torus_clear_of_position(const TorusPatchPiece& torus, const Vec& position)
{
  ForeignPositions single;
  single.centre = position;
  const TorusFrame frame(torus);
  int budget = budget_one_parameter;
  return torus_gap_range(frame, single, AzimuthRange::of(torus.phi0, torus.phi1), AzimuthRange{},
                         budget);
}

bool torus_clear_of_arc(const TorusPatchPiece& torus, const SasArc& other)
{
  // Positions that cut lie within 2 p of a probe centre of the piece, and so within 2 p plus
  // the chord of the middle one.
  const double half = 0.5 * (torus.phi1 - torus.phi0);
  std::array<std::pair<double, double>, 3> ranges;
  const int count =
    arc_parts_within(other, torus.arc->point(torus.phi0 + half),
                     2.0 * torus.probe + 2.0 * torus.arc->radius * std::sin(half), ranges);
  const ForeignPositions positions{ other.centre, other.e1, other.e2, other.radius };
  const TorusFrame frame(torus);
  const AzimuthRange phi = AzimuthRange::of(torus.phi0, torus.phi1);
  int budget = budget_two_parameters;
  for (int k = 0; k < count; ++k)
  {
    if (!torus_gap_range(
          frame, positions, phi,
          AzimuthRange::of(ranges[std::size_t(k)].first, ranges[std::size_t(k)].second), budget))
    {
      return false;
    }
  }
  return true;
}

bool concave_clear_of_arc(const Vec& probe_centre, double probe, const SphericalTriangle& triangle,
                          const SasArc& other)
{
  std::array<std::pair<double, double>, 3> ranges;
  const int count = arc_parts_within(other, probe_centre, 2.0 * probe, ranges);
  int budget = budget_one_parameter;
  for (int k = 0; k < count; ++k)
  {
    if (!concave_arc_range(probe_centre, probe, triangle, other, ranges[std::size_t(k)].first,
                           ranges[std::size_t(k)].second, budget))
    {
      return false;
    }
  }
  return true;
}

} // namespace mesolens
