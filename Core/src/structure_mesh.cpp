// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/structure_mesh.h"

#include "mesolens/errors.h"
#include "mesolens/surface_sampling.h"

#include <CGAL/Advancing_front_surface_reconstruction.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Polygon_mesh_processing/repair.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <string>

namespace mesolens {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
namespace PMP = CGAL::Polygon_mesh_processing;

constexpr double degrees = 180.0 / 3.14159265358979323846;

double length(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                   (a[2] - b[2]) * (a[2] - b[2]));
}

/// Closes the holes whose borders have at most `largest` edges.
void close_small_holes(SurfaceMesh& mesh, std::size_t largest)
{
  std::vector<SurfaceMesh::Halfedge_index> borders;
  PMP::extract_boundary_cycles(mesh, std::back_inserter(borders));
  for (const auto start : borders)
  {
    std::size_t edges = 0;
    for (auto h : CGAL::halfedges_around_face(start, mesh))
    {
      (void)h;
      ++edges;
    }
    if (edges <= largest)
    {
      std::vector<SurfaceMesh::Face_index> faces;
      std::vector<SurfaceMesh::Vertex_index> vertices;
      PMP::triangulate_and_refine_hole(mesh, start, std::back_inserter(faces),
                                       std::back_inserter(vertices));
    }
  }
}
} // namespace

MeshQuality mesh_quality(const TriangleMesh& mesh)
{
  MeshQuality quality;
  quality.min_angle = 180;
  double sum = 0;
  double squares = 0;
  std::size_t count = 0;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
  {
    const std::array<std::array<double, 3>, 3> p{ mesh.point(mesh.triangles[3 * t]),
                                                  mesh.point(mesh.triangles[3 * t + 1]),
                                                  mesh.point(mesh.triangles[3 * t + 2]) };
    const double sides[3] = { length(p[1], p[2]), length(p[2], p[0]), length(p[0], p[1]) };
    for (int k = 0; k < 3; ++k)
    {
      const double a = sides[k];
      const double b = sides[(k + 1) % 3];
      const double c = sides[(k + 2) % 3];
      const double cosine = b > 0 && c > 0 ? (b * b + c * c - a * a) / (2 * b * c) : 1.0;
      const double angle = std::acos(std::clamp(cosine, -1.0, 1.0)) * degrees;
      quality.min_angle = std::min(quality.min_angle, angle);
      quality.max_angle = std::max(quality.max_angle, angle);
      sum += a; // each edge once per triangle side: interior edges count twice, equally
      squares += a * a;
      ++count;
    }
  }
  if (count == 0)
  {
    quality.min_angle = 0;
    return quality;
  }
  quality.mean_edge = sum / double(count);
  const double variance =
    std::max(0.0, squares / double(count) - quality.mean_edge * quality.mean_edge);
  quality.edge_spread = quality.mean_edge > 0 ? std::sqrt(variance) / quality.mean_edge : 0.0;
  quality.boundary_edges = 0;
  for (const auto& loop : boundary_loops(mesh))
  {
    quality.boundary_edges += loop.size();
  }
  return quality;
}

TriangleMesh structure_mesh(const std::vector<double>& points, const StructureMeshSize& size,
                            MeshQuality* quality, const ParallelFor& parallel_for)
{
  if (points.size() % 3 != 0 || points.size() < 12)
  {
    throw InvalidInput("a structure mesh needs at least 4 points (3 coordinates each); got " +
                       std::to_string(points.size()) + " values");
  }
  if (size.edge_length < 0 || (size.edge_length == 0 && size.vertices < 4) ||
      !std::isfinite(size.edge_length) || !std::isfinite(size.mid_surface_radius))
  {
    throw InvalidInput("a structure mesh needs a target edge length > 0 or at least 4 vertices");
  }
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    if (!std::isfinite(points[i]))
    {
      throw InvalidInput("point " + std::to_string(i / 3) + " of the structure is not finite");
    }
  }

  // One even sheet of points through the middle of the cloud, as sparse as the target edge
  // length allows: the reconstruction then meets neither two leaflets nor noise, and stays fast.
  const double radius =
    size.mid_surface_radius > 0 ? size.mid_surface_radius : 4.0 * median_spacing(points);
  double edge = size.edge_length;
  if (edge <= 0)
  {
    // The area from a Poisson-disk set at twice the radius, wider than the structure is thick
    // so that each place is sampled once (about 0.8 / spacing^2 points per unit area); two
    // triangles per vertex of area (sqrt(3) / 4) L^2 each. The final length comes from the
    // reconstructed surface's area.
    const double coarse = 2.0 * radius;
    const double area =
      double(poisson_disk_subset(points, coarse).size() / 3) * coarse * coarse / 0.8;
    edge = std::sqrt(2.0 * area / (std::sqrt(3.0) * double(size.vertices)));
  }
  const double spacing = std::max(0.5 * radius, 0.5 * edge);
  std::vector<double> sheet =
    poisson_disk_subset(mid_surface_points(points, spacing, radius, 4, parallel_for), spacing);
  if (sheet.size() < 12)
  {
    sheet = points; // too few for a sheet: reconstruct through the points themselves
  }
  std::vector<Point> cloud;
  cloud.reserve(sheet.size() / 3);
  for (std::size_t i = 0; i < sheet.size(); i += 3)
  {
    cloud.emplace_back(sheet[i], sheet[i + 1], sheet[i + 2]);
  }

  std::vector<std::array<std::size_t, 3>> facets;
  CGAL::advancing_front_surface_reconstruction(cloud.begin(), cloud.end(),
                                               std::back_inserter(facets));
  if (facets.empty())
  {
    throw TopologyError("the " + std::to_string(cloud.size()) +
                        " points describe no surface (no triangle could be reconstructed)");
  }
  // The reconstruction gives the same triangles in an order (and orientation) that changes
  // from run to run; sorted, every later step and so the mesh are the same each time.
  for (auto& facet : facets)
  {
    std::sort(facet.begin(), facet.end());
  }
  std::sort(facets.begin(), facets.end());
  std::vector<std::vector<std::size_t>> polygons(facets.size());
  for (std::size_t f = 0; f < facets.size(); ++f)
  {
    polygons[f] = { facets[f][0], facets[f][1], facets[f][2] };
  }
  PMP::orient_polygon_soup(cloud, polygons);
  SurfaceMesh mesh;
  PMP::polygon_soup_to_polygon_mesh(cloud, polygons, mesh);
  // The remeshing needs a valid 2-manifold without degenerate triangles; crumbs of a few
  // triangles (left by stray points) are no part of the structure.
  PMP::duplicate_non_manifold_vertices(mesh);
  PMP::remove_degenerate_faces(mesh);
  PMP::keep_large_connected_components(mesh,
                                       std::max<std::size_t>(4, mesh.number_of_faces() / 100));
  PMP::remove_isolated_vertices(mesh);
  mesh.collect_garbage();
  close_small_holes(mesh, std::max<std::size_t>(20, mesh.number_of_vertices() / 20));
  PMP::remove_degenerate_faces(mesh);
  mesh.collect_garbage();
  if (mesh.number_of_faces() == 0 || !CGAL::is_valid_polygon_mesh(mesh))
  {
    throw TopologyError("the surface reconstructed through the " + std::to_string(cloud.size()) +
                        " points is not a valid 2-manifold");
  }

  double target = size.edge_length;
  if (target <= 0)
  {
    // Near-equilateral triangles, about two per vertex: area = 2 N (sqrt(3) / 4) L^2.
    const double area = PMP::area(mesh);
    target = std::sqrt(2.0 * area / (std::sqrt(3.0) * double(size.vertices)));
  }
  if (!(target > 0) || !std::isfinite(target))
  {
    throw TopologyError("the reconstructed surface has no area");
  }
  PMP::isotropic_remeshing(faces(mesh), target, mesh, CGAL::parameters::number_of_iterations(5));
  mesh.collect_garbage();

  TriangleMesh result;
  std::vector<std::int64_t> index(mesh.number_of_vertices(), -1);
  for (const auto v : mesh.vertices())
  {
    index[v.idx()] = std::int64_t(result.vertex_count());
    const Point& p = mesh.point(v);
    result.points.insert(result.points.end(), { p.x(), p.y(), p.z() });
  }
  for (const auto f : mesh.faces())
  {
    for (const auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
    {
      result.triangles.push_back(index[v.idx()]);
    }
  }
  if (quality)
  {
    *quality = mesh_quality(result);
  }
  return result;
}

} // namespace mesolens
