// SPDX-License-Identifier: GPL-3.0-or-later
// Loop subdivision of triangle meshes through OpenMesh (private).
#pragma once

#include "mesolens/triangle_mesh.h"

#include <cstdint>
#include <vector>

namespace mesolens {
namespace detail {

/// One level of Loop subdivision (boundaries follow the 1-6-1 boundary rule). Vertices keep
/// their indices (and move); new vertices are appended, and `origin` (one entry per input vertex)
/// grows by -1 for each. Throws TopologyError when OpenMesh refuses a face (non-manifold input).
TriangleMesh loop_subdivide(const TriangleMesh& mesh, std::vector<std::int64_t>& origin);

} // namespace detail
} // namespace mesolens
