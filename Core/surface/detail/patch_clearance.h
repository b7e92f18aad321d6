// SPDX-License-Identifier: GPL-3.0-or-later
// Whether a probe position foreign to a solvent-excluded patch comes within the probe radius
// of it (private to MesoLensCore): certificates that let a patch be integrated in closed form
// instead of being split to find where it is cut.
#pragma once

#include "surface/detail/sas_boundary.h"
#include "surface/detail/spherical_triangle.h"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>

namespace mesolens {

/// A piece of the toroidal patch that probe `probe` (Å, > 0) sweeps rolling along `arc`: the
/// points C(phi) + probe (cos t axis + sin t d(phi)) for azimuths phi in [phi0, phi1] and arc
/// angles t in [t0, t1], where d(phi) = cos phi e1 + sin phi e2 and C(phi) = centre + radius
/// d(phi) is the probe's centre (phi1 - phi0 and t1 - t0 at most pi).
struct TorusPatchPiece
{
  const SasArc* arc = nullptr;
  double probe = 0;
  double phi0 = 0, phi1 = 0, t0 = 0, t1 = 0;
};

/// The least of a cos t + b sin t over arc angles t in [t0, t1] (at most half a turn), given
/// the ends' cosines and sines: -sqrt(a^2 + b^2) where the direction (-a, -b) lies within the
/// range, else at an end. (The greatest is -least_sinusoid(-a, -b, ...).)
inline double least_sinusoid(double a, double b, double cos0, double sin0, double cos1, double sin1)
{
  if (cos0 * -b - sin0 * -a >= 0 && -a * sin1 - -b * cos1 >= 0)
  {
    return -std::sqrt(a * a + b * b);
  }
  return std::min(a * cos0 + b * sin0, a * cos1 + b * sin1);
}

// Patches no probe position can cut, whatever lies around them. A toroidal or concave patch
// lies on the sphere of radius p about a probe position v, in the cone of the directions u_a
// from v to the atoms it touches (centres c_a = v + R_a u_a, R_a the inflated radii). An
// accessible position w (|w - c_a| >= R_a for each a) has, with y = w - v,
// y . u_a <= |y|^2 / (2 R_a). A patch point v + p u with u = sum l_a u_a / N (l_a >= 0,
// N = |sum l_a u_a| >= sum l_a d, d the distance from the origin to the flat polygon of the u_a)
// then has p u . y <= |y|^2 p / (2 R d), R the least R_a; and it lies inside w's ball only when
// 2 p u . y > |y|^2. So where R d >= p no position cuts the patch.

/// Whether no accessible probe position comes nearer than `probe` (Å, > 0) to a toroidal patch
/// (or a piece of one) between the contact circles of atoms with inflated radii `first_radius`
/// and `second_radius` (Å), whose generating arc spans `span` (radians, < pi) at the probe's
/// centre: d = cos(span / 2) above. (For equal radii this says that the probe does not pass
/// between the atoms: R cos(span / 2) is the distance from the probe's centre to the axis.)
inline bool torus_clear_of_every_position(double probe, double first_radius, double second_radius,
                                          double span)
{
  return std::cos(0.5 * span) * std::min(first_radius, second_radius) >= probe * (1.0 + 1e-9);
}

/// The same for a concave patch: the spherical triangle of unit `directions` from the probe's
/// centre to its three atoms, of inflated radii `radii` (Å).
bool concave_clear_of_every_position(double probe, const Eigen::Vector3d (&directions)[3],
                                     const double (&radii)[3]);

// Each test answers true only when certain that every point of the patch lies at least the
// probe radius from every position of the foreign piece (bounds on the squared distance less
// p^2, bisected where the bound is loose, within a fixed budget). False means the piece cuts
// the patch or could not be ruled out within the budget: the caller then splits the patch.

/// Whether the probe position `position` (Å) stays clear of the torus piece.
bool torus_clear_of_position(const TorusPatchPiece& torus, const Eigen::Vector3d& position);

/// Whether every probe position on exposed arc `other` (its ends included) stays clear of the
/// torus piece.
bool torus_clear_of_arc(const TorusPatchPiece& torus, const SasArc& other);

/// Whether every probe position on exposed arc `other` stays clear of the concave patch
/// `triangle` (unit directions) on the probe sphere of radius `probe` at `probe_centre`.
bool concave_clear_of_arc(const Eigen::Vector3d& probe_centre, double probe,
                          const SphericalTriangle& triangle, const SasArc& other);

} // namespace mesolens
