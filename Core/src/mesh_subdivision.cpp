// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh_subdivision.h"

#include "mesolens/errors.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>

namespace mesolens {
namespace detail {

namespace {
struct DoublePrecision : OpenMesh::DefaultTraits
{
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};
using OpenMeshTriangles = OpenMesh::TriMesh_ArrayKernelT<DoublePrecision>;
} // namespace

TriangleMesh loop_subdivide(const TriangleMesh& mesh, std::vector<std::int64_t>& origin)
{
  OpenMeshTriangles om;
  std::vector<OpenMeshTriangles::VertexHandle> handles;
  handles.reserve(mesh.vertex_count());
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
  {
    const auto p = mesh.point(std::int64_t(v));
    handles.push_back(om.add_vertex(OpenMeshTriangles::Point(p[0], p[1], p[2])));
  }
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
  {
    const auto face = om.add_face(handles[std::size_t(mesh.triangles[3 * t])],
                                  handles[std::size_t(mesh.triangles[3 * t + 1])],
                                  handles[std::size_t(mesh.triangles[3 * t + 2])]);
    if (!face.is_valid())
    {
      throw TopologyError("Loop subdivision: triangle " + std::to_string(t) +
                          " makes the mesh non-manifold");
    }
  }
  OpenMesh::Subdivider::Uniform::LoopT<OpenMeshTriangles, double> loop;
  loop.attach(om);
  loop(1);
  loop.detach();
  TriangleMesh out;
  out.points.reserve(3 * om.n_vertices());
  for (const auto v : om.vertices())
  {
    const auto& p = om.point(v);
    out.points.insert(out.points.end(), { p[0], p[1], p[2] });
  }
  out.triangles.reserve(3 * om.n_faces());
  for (const auto f : om.faces())
  {
    for (const auto v : om.fv_range(f))
    {
      out.triangles.push_back(v.idx());
    }
  }
  origin.resize(om.n_vertices(), -1);
  return out;
}

} // namespace detail
} // namespace mesolens
