// SPDX-License-Identifier: GPL-3.0-or-later
// The closest point of a triangle mesh to any point in space (an AABB tree of the triangles).
#pragma once

#include "mesolens/mesh/triangle_mesh.h"

#include <array>
#include <memory>

namespace mesolens {

/// Exact closest-point queries on a triangle mesh, built once (O(n log n)); queries are const
/// and may run concurrently.
class SurfaceLocator
{
public:
  /// Copies what it needs of `mesh`. Throws InvalidInput when the mesh has no triangles or a
  /// non-finite point.
  explicit SurfaceLocator(const TriangleMesh& mesh);
  ~SurfaceLocator();
  SurfaceLocator(const SurfaceLocator&) = delete;
  SurfaceLocator& operator=(const SurfaceLocator&) = delete;

  /// The surface point closest to `point` (mesh units): its triangle, barycentric coordinates
  /// and position; `distance` gets how far it is. Throws InvalidInput for a non-finite point.
  SurfacePoint closest_point(const std::array<double, 3>& point, double* distance = nullptr) const;

  /// The same, starting the search from `hint` (a surface point, e.g. the answer for a nearby
  /// query; nullptr: none): faster for queries close to each other, same answer.
  SurfacePoint closest_point(const std::array<double, 3>& point, const SurfacePoint* hint,
                             double* distance = nullptr) const;

private:
  struct Impl;
  std::unique_ptr<Impl> Internal;
};

} // namespace mesolens
