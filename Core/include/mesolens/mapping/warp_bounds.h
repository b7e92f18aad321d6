// SPDX-License-Identifier: GPL-3.0-or-later
// Conservative bounds of a box of patch atoms carried by a tile's polynomial warp: what
// occlusion culling needs to skip warped atoms without warping each of them.
#pragma once

#include "mesolens/mapping/membrane_mapping.h"

#include <array>

namespace mesolens {

/// An axis-aligned box: x, y, z minima, then maxima.
using Box = std::array<double, 6>;

/// The axis-aligned box (mesh units) that holds every point of `patch_box` (patch coordinates,
/// membrane units: a culling cell of patch atoms) after the warp of one tile: `splits` x
/// `splits` pieces of 30 coefficients each (MappedMembrane::polynomial_coefficients from the
/// tile's first piece), evaluated as evaluate_tile_polynomial does, extrapolated beyond the
/// tile. Each piece the box reaches is bounded by interval arithmetic over the quadratic's
/// monomials on its part of the box, and the pieces' bounds are joined: never smaller than the
/// true extent, and exact for a warp of degree 1 in each variable. `layer_half_thickness` > 0.
Box warped_box(const MembranePatch& patch, double layer_half_thickness, int splits,
               const double* coefficients, const Box& patch_box);

} // namespace mesolens
