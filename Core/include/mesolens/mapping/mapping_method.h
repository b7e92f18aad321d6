// SPDX-License-Identifier: GPL-3.0-or-later
// The three ways of the membrane mapping to carry atoms onto a surface (the only definition:
// vtkMesoMembraneMapping's constants and the renderer's warp take their values from it).
#pragma once

namespace mesolens {

/// How membrane atoms are carried onto the surface.
enum class MappingMethod
{
  /// Each atom at x0 + w n(x0): x0 the surface point at the atom's (u, v), n the interpolated
  /// normal, w the atom's height. Follows the surface exactly; bends molecules.
  Displacement = 0,
  /// One rigid motion per molecule: its centre of mass is mapped like an atom, and the rotation
  /// takes the patch's x, y, z axes to the surface's u tangent, v tangent and normal there.
  /// Keeps every molecule undistorted.
  MoleculeInstancing = 1,
  /// One quadratic x(s, t, h) per tile, fitted by least squares to the displacement map on
  /// 3 layers of samples. Smooth, cheap to evaluate (on the GPU, by the renderer).
  Polynomial = 2,
};

} // namespace mesolens
