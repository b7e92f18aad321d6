// SPDX-License-Identifier: GPL-3.0-or-later
// Periodic simulation boxes (orthorhombic and triclinic) and the minimum-image convention.
#pragma once

#include <array>

namespace mesolens {

/// A periodic box given by its three edge vectors a, b, c (rows), in Å. GROMACS boxes are lower
/// triangular (a along x, b in the xy plane); PDB CRYST1 cells are converted to that form.
/// A default-constructed box is "not set" and every periodic operation is then the identity.
struct PeriodicBox
{
  std::array<std::array<double, 3>, 3> vectors{ { { 0, 0, 0 }, { 0, 0, 0 }, { 0, 0, 0 } } };

  /// True when the three vectors span a volume (> 1e-6 Å³).
  bool is_set() const;
  /// a·(b×c), Å³.
  double volume() const;
  /// True when the off-diagonal terms are zero (to 1e-9 Å).
  bool is_orthorhombic() const;
  /// The smallest of the box's three heights (the distances between opposite faces), Å; 0 when
  /// not set. Every nonzero box-vector combination is at least this long, so a displacement
  /// shorter than half of it is its own minimum image.
  double smallest_height() const;

  /// The shortest periodic image of the displacement d (Å): d + i·a + j·b + k·c with integer
  /// i, j, k minimising the length. Exact for any triclinic box (searches the neighbouring
  /// images after reduction in fractional coordinates).
  std::array<double, 3> minimum_image(const std::array<double, 3>& d) const;

  /// The box from unit-cell parameters (lengths Å, angles in degrees), GROMACS convention.
  static PeriodicBox from_cell(double a, double b, double c, double alpha, double beta,
                               double gamma);
};

/// PeriodicBox::minimum_image() for many displacements in one box: the inverse box matrix is
/// computed once. Identity when the box is not set.
class MinimumImage
{
public:
  explicit MinimumImage(const PeriodicBox& box);
  std::array<double, 3> operator()(const std::array<double, 3>& d) const;

private:
  PeriodicBox Box;
  bool Set = false;
  bool Orthorhombic = true;
  std::array<std::array<double, 3>, 3> Inverse{}; ///< fractional = Inverse * cartesian
};

} // namespace mesolens
