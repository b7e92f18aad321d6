// SPDX-License-Identifier: GPL-3.0-or-later
// The quadratic warp of the membrane-mapping paper: one polynomial x(s, t, h) of total degree 2
// per tile, fitted by least squares. The renderer evaluates the same polynomial on the GPU;
// this is its reference implementation.
#pragma once

#include "mesolens/common/point_span.h"

#include <array>
#include <cstddef>
#include <vector>

namespace mesolens {

/// Number of monomials of total degree <= 2 in three variables.
constexpr std::size_t quadratic_terms = 10;

/// The monomials in the order the coefficients use: 1, s, t, h, s², st, sh, t², th, h².
std::array<double, quadratic_terms> quadratic_monomials(double s, double t, double h);

/// 30 coefficients: those of x in [0, 10), y in [10, 20), z in [20, 30), each in monomial order.
using QuadraticWarp = std::array<double, 3 * quadratic_terms>;

/// x(s, t, h) for one warp.
std::array<double, 3> evaluate_quadratic(const QuadraticWarp& warp, double s, double t, double h);

/// A least-squares fit and its residuals (distances between fitted and target points).
struct QuadraticFit
{
  QuadraticWarp warp{};
  double rms_residual = 0; ///< target units
  double max_residual = 0; ///< target units
};

/// Fits x(s, t, h) to samples: parameters[i] = (s, t, h) maps to targets[i]. The 10 x 10 normal
/// equations are solved by Cholesky decomposition (Eigen's LLT), as in the paper. Needs at
/// least 10 samples in general position (e.g. a 6 x 6 grid on 3 layers); throws InvalidInput
/// for mismatched or too few samples and SolverFailure for a singular system.
QuadraticFit fit_quadratic(PointSpan<const double> parameters, PointSpan<const double> targets);

} // namespace mesolens
