// SPDX-License-Identifier: GPL-3.0-or-later
// A parameterized surface patch queried by texture coordinates: where (u, v) lies on the
// surface, its normal and tangent frame. The membrane mappings are built on it.
#pragma once

#include "mesolens/mapping/harmonic_parameterization.h"
#include "mesolens/mesh/triangle_mesh.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace mesolens {

/// The surface at one (u, v): position, unit normal (interpolated vertex normals) and the
/// orthonormal frame whose first axis follows +u.
struct SurfaceFrame
{
  std::array<double, 3> position{};
  std::array<double, 3> normal{};
  std::array<double, 3> tangent_u{}; ///< unit, along d position / du, orthogonal to normal
  std::array<double, 3> tangent_v{}; ///< normal x tangent_u
};

/// Moves a point of a chart's disk mesh (a triangle of it and barycentric coordinates) onto the
/// surface the mesh approximates: sets frame.position and frame.normal (unit), which hold the
/// flat triangle's point and interpolated normal on entry. Called concurrently.
using SurfacePlacement = std::function<void(
  std::int64_t triangle, const std::array<double, 3>& barycentric, SurfaceFrame& frame)>;

/// A disk mesh with its parameterization, indexed for point location in (u, v).
class SurfaceChart
{
public:
  /// `uv` has 2 values per disk vertex (from harmonic_parameterization()); `normals` 3 unit
  /// components per vertex (empty: the mesh's area-weighted vertex normals); `placement` puts
  /// located points on the true surface (empty: they stay on the flat triangles). Throws
  /// InvalidInput when the sizes disagree or a coordinate is not finite.
  SurfaceChart(TriangleMesh disk, std::vector<double> uv, std::vector<double> normals = {},
               SurfacePlacement placement = {});

  const TriangleMesh& mesh() const
  {
    return this->Disk;
  }
  const std::vector<double>& uv() const
  {
    return this->Uv;
  }

  /// The (u, v) of a point on the disk mesh (barycentric interpolation).
  std::array<double, 2> uv_of(const SurfacePoint& point) const;

  /// The surface point at (u, v); false when (u, v) is outside every triangle (beyond the disk).
  bool locate(double u, double v, SurfacePoint& point) const;

  /// The frame at (u, v), on the true surface when the chart has a placement; false when
  /// (u, v) is outside the disk.
  bool frame(double u, double v, SurfaceFrame& frame) const;

private:
  TriangleMesh Disk;
  std::vector<double> Uv;
  std::vector<double> Normals;
  SurfacePlacement Placement;
  // Uniform grid over the uv bounding box: cell c lists triangles [Start[c], Start[c + 1]).
  std::array<double, 2> Low{};
  double Cell = 1;
  int Columns = 1;
  int Rows = 1;
  std::vector<std::size_t> Start;
  std::vector<std::uint32_t> Triangles;
};

} // namespace mesolens
