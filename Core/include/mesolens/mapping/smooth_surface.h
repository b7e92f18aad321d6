// SPDX-License-Identifier: GPL-3.0-or-later
// The smooth surface that interpolates a triangle mesh: curved point-normal triangles (Vlachos,
// Peters, Boyd and Mitchell, "Curved PN triangles", I3D 2001). Membranes are mapped onto it, so
// a patch smaller than the mesh's triangles still lies on a smooth surface through the user's
// vertices, never on a flat facet or on an approximating surface that drifts from them.
#pragma once

#include "mesolens/mesh/triangle_mesh.h"

#include <array>
#include <cstdint>
#include <vector>

namespace mesolens {

/// A point of the smooth surface with its unit normal.
struct SmoothPoint
{
  std::array<double, 3> position{};
  std::array<double, 3> normal{};
};

/// One cubic Bézier triangle per mesh triangle, built from its corners and their vertex normals.
/// It passes through every vertex with the vertex normal as its normal there, and neighbouring
/// triangles meet without gaps (an edge's curve depends only on its two ends). Where a
/// triangle's vertex normals all equal its facet normal it is the flat triangle, so on a fine,
/// smooth mesh it departs from the facets by a small fraction of an edge length. Normals come
/// from the quadratic normal field of the same paper, continuous across edges.
class SmoothSurface
{
public:
  /// `mesh` is copied; `normals` holds 3 unit components per vertex (empty: the area-weighted
  /// vertex normals of the mesh). Throws InvalidInput when the sizes disagree.
  explicit SmoothSurface(TriangleMesh mesh, std::vector<double> normals = {});

  const TriangleMesh& mesh() const
  {
    return this->Mesh;
  }
  const std::vector<double>& vertex_normals() const
  {
    return this->Normals;
  }

  /// The surface at barycentric coordinates (weights of the triangle's corners 0, 1, 2; they
  /// should sum to 1) of mesh triangle `triangle`.
  SmoothPoint evaluate(std::int64_t triangle, const std::array<double, 3>& barycentric) const;

private:
  TriangleMesh Mesh;
  std::vector<double> Normals;
};

} // namespace mesolens
