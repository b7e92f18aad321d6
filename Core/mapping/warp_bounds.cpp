// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/mapping/warp_bounds.h"

#include "mesolens/mapping/polynomial_warp.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mesolens {
namespace {

struct Interval
{
  double low = 0;
  double high = 0;
};

Interval product(const Interval& a, const Interval& b)
{
  const double p[4] = { a.low * b.low, a.low * b.high, a.high * b.low, a.high * b.high };
  return { *std::min_element(p, p + 4), *std::max_element(p, p + 4) };
}

Interval square(const Interval& a)
{
  const double low = a.low * a.low;
  const double high = a.high * a.high;
  if (a.low <= 0 && a.high >= 0)
  {
    return { 0, std::max(low, high) };
  }
  return { std::min(low, high), std::max(low, high) };
}

/// The pieces [first, last] an interval of tile coordinate u in [-1, 1] (extended beyond) falls
/// in, and for piece k its part in the piece's own coordinate (as polynomial_piece maps it).
struct PieceSpan
{
  int first = 0;
  int last = 0;
  double from = 0; // fractional piece coordinates (u + 1) / 2 * splits of the interval
  double to = 0;

  PieceSpan(const Interval& u, int splits)
    : from((u.low + 1) / 2 * splits)
    , to((u.high + 1) / 2 * splits)
  {
    this->first = std::clamp(int(std::floor(this->from)), 0, splits - 1);
    this->last = std::clamp(int(std::floor(this->to)), 0, splits - 1);
  }

  /// Piece k's part of the interval, in its local coordinate 2 (f - k) - 1; the end pieces
  /// keep what lies beyond the tile (extrapolated, as polynomial_piece clamps).
  Interval local(int k) const
  {
    const double low = k == this->first ? this->from : double(k);
    const double high = k == this->last ? this->to : double(k + 1);
    return { 2 * (low - k) - 1, 2 * (high - k) - 1 };
  }
};

} // namespace

Box warped_box(const MembranePatch& patch, double layer_half_thickness, int splits,
               const double* coefficients, const Box& patch_box)
{
  // (s, t) are linear in (x, y) (as polynomial_coordinates computes them, here in double): their
  // range over the box is the range over its 4 corners.
  const double determinant = patch.a[0] * patch.b[1] - patch.a[1] * patch.b[0];
  Interval s{ std::numeric_limits<double>::max(), std::numeric_limits<double>::lowest() };
  Interval t = s;
  for (int corner = 0; corner < 4; ++corner)
  {
    const double qx = patch_box[(corner & 1) ? 3 : 0] - patch.origin[0];
    const double qy = patch_box[(corner & 2) ? 4 : 1] - patch.origin[1];
    const double cs = 2 * (patch.b[1] * qx - patch.b[0] * qy) / determinant - 1;
    const double ct = 2 * (-patch.a[1] * qx + patch.a[0] * qy) / determinant - 1;
    s = { std::min(s.low, cs), std::max(s.high, cs) };
    t = { std::min(t.low, ct), std::max(t.high, ct) };
  }
  const Interval h{ (patch_box[2] - patch.centre_height) / layer_half_thickness,
                    (patch_box[5] - patch.centre_height) / layer_half_thickness };
  const PieceSpan along_s(s, splits);
  const PieceSpan along_t(t, splits);
  Box bounds{ std::numeric_limits<double>::max(),    std::numeric_limits<double>::max(),
              std::numeric_limits<double>::max(),    std::numeric_limits<double>::lowest(),
              std::numeric_limits<double>::lowest(), std::numeric_limits<double>::lowest() };
  for (int j = along_t.first; j <= along_t.last; ++j)
  {
    for (int i = along_s.first; i <= along_s.last; ++i)
    {
      const Interval ps = along_s.local(i);
      const Interval pt = along_t.local(j);
      // The monomials' ranges in the order of quadratic_monomials: 1, s, t, h, s², st, sh, t²,
      // th, h².
      const Interval monomials[quadratic_terms] = {
        { 1, 1 },       ps,       pt, h, square(ps), product(ps, pt), product(ps, h), square(pt),
        product(pt, h), square(h)
      };
      const double* warp = coefficients + 3 * quadratic_terms * std::size_t(j * splits + i);
      for (std::size_t d = 0; d < 3; ++d)
      {
        double low = 0;
        double high = 0;
        for (std::size_t k = 0; k < quadratic_terms; ++k)
        {
          const double c = warp[quadratic_terms * d + k];
          low += c * (c >= 0 ? monomials[k].low : monomials[k].high);
          high += c * (c >= 0 ? monomials[k].high : monomials[k].low);
        }
        bounds[d] = std::min(bounds[d], low);
        bounds[d + 3] = std::max(bounds[d + 3], high);
      }
    }
  }
  return bounds;
}

} // namespace mesolens
