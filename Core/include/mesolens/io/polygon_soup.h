// SPDX-License-Identifier: GPL-3.0-or-later
// A mesh as a file gives it: points and polygons, nothing assumed.
#pragma once

#include <cstdint>
#include <vector>

namespace mesolens {

/// A polygon soup: no orientation or manifoldness is assumed.
struct PolygonSoup
{
  std::vector<double> points;                      ///< 3 per vertex
  std::vector<std::vector<std::int64_t>> polygons; ///< vertex indices per face
};

/// What a mesh file gives: its polygons, and the vertex normals when it has them.
struct MeshFileContents
{
  PolygonSoup soup;
  std::vector<double> normals; ///< 3 per vertex (nx, ny, nz), or empty
};

} // namespace mesolens
