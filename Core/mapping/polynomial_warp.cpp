// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/mapping/polynomial_warp.h"

#include "mesolens/common/errors.h"

#include <Eigen/Cholesky>
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace mesolens {

std::array<double, quadratic_terms> quadratic_monomials(double s, double t, double h)
{
  return { 1.0, s, t, h, s * s, s * t, s * h, t * t, t * h, h * h };
}

std::array<double, 3> evaluate_quadratic(const QuadraticWarp& warp, double s, double t, double h)
{
  const auto m = quadratic_monomials(s, t, h);
  std::array<double, 3> x{ 0, 0, 0 };
  for (std::size_t d = 0; d < 3; ++d)
  {
    for (std::size_t k = 0; k < quadratic_terms; ++k)
    {
      x[d] += warp[d * quadratic_terms + k] * m[k];
    }
  }
  return x;
}

QuadraticFit fit_quadratic(PointSpan<const double> parameters, PointSpan<const double> targets)
{
  if (parameters.size() != targets.size() || parameters.size() < quadratic_terms)
  {
    throw InvalidInput("a quadratic warp needs at least 10 samples, each with a target");
  }
  Eigen::Matrix<double, quadratic_terms, quadratic_terms> normal =
    Eigen::Matrix<double, quadratic_terms, quadratic_terms>::Zero();
  Eigen::Matrix<double, quadratic_terms, 3> right =
    Eigen::Matrix<double, quadratic_terms, 3>::Zero();
  for (std::size_t i = 0; i < parameters.size(); ++i)
  {
    const auto m = quadratic_monomials(parameters[i][0], parameters[i][1], parameters[i][2]);
    const Eigen::Map<const Eigen::Matrix<double, quadratic_terms, 1>> row(m.data());
    normal.noalias() += row * row.transpose();
    for (int d = 0; d < 3; ++d)
    {
      right.col(d) += row * targets[i][std::size_t(d)];
    }
  }
  const Eigen::LLT<Eigen::Matrix<double, quadratic_terms, quadratic_terms>> cholesky(normal);
  if (cholesky.info() != Eigen::Success)
  {
    throw SolverFailure("the normal equations of the quadratic fit are singular: the samples "
                        "do not determine a quadratic");
  }
  const Eigen::Matrix<double, quadratic_terms, 3> solution = cholesky.solve(right);
  QuadraticFit fit;
  for (std::size_t d = 0; d < 3; ++d)
  {
    for (std::size_t k = 0; k < quadratic_terms; ++k)
    {
      fit.warp[d * quadratic_terms + k] = solution(Eigen::Index(k), Eigen::Index(d));
    }
  }
  double sum = 0;
  for (std::size_t i = 0; i < parameters.size(); ++i)
  {
    const auto x =
      evaluate_quadratic(fit.warp, parameters[i][0], parameters[i][1], parameters[i][2]);
    const double error =
      std::sqrt(std::pow(x[0] - targets[i][0], 2) + std::pow(x[1] - targets[i][1], 2) +
                std::pow(x[2] - targets[i][2], 2));
    sum += error * error;
    fit.max_residual = std::max(fit.max_residual, error);
  }
  fit.rms_residual = std::sqrt(sum / double(parameters.size()));
  return fit;
}

} // namespace mesolens
