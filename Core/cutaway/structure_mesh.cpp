// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/cutaway/structure_mesh.h"

#include "mesolens/common/errors.h"
#include "mesolens/molecules/molecule_pbc.h"
#include "mesolens/cutaway/surface_sampling.h"

#include "common/detail/disjoint_sets.h"
#include "cutaway/detail/angle_repair.h"
#include "cutaway/detail/mid_sheet.h"
#include "cutaway/detail/sheet_lattice.h"

#include <CGAL/Advancing_front_surface_reconstruction.h>
#include <CGAL/Polygon_mesh_processing/angle_and_area_smoothing.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Polygon_mesh_processing/repair.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/tangential_relaxation.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <numeric>
#include <sstream>
#include <string>

namespace mesolens {

namespace {
using Point = RepairKernel::Point_3;
using Vector = RepairKernel::Vector_3;
using SurfaceMesh = RepairMesh;
namespace PMP = CGAL::Polygon_mesh_processing;

constexpr double degrees = 180.0 / 3.14159265358979323846;
/// The repair aims a degree above the bound, so that rounding never decides the check.
constexpr double repair_goal = structure_mesh_min_angle + 1.0;

double length(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                   (a[2] - b[2]) * (a[2] - b[2]));
}

std::size_t component_count(const TriangleMesh& mesh)
{
  detail::DisjointSets vertices(mesh.vertex_count());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
  {
    for (std::size_t k = 1; k < 3; ++k)
    {
      vertices.join(std::size_t(mesh.triangles[3 * t + k]), std::size_t(mesh.triangles[3 * t]));
    }
  }
  std::size_t count = 0;
  std::vector<std::uint8_t> seen(mesh.vertex_count(), 0);
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
  {
    const std::size_t r = vertices.root(std::size_t(mesh.triangles[3 * t]));
    count += seen[r] ? 0 : 1;
    seen[r] = 1;
  }
  return count;
}

void require_valid(PointSpan<const double> points, const StructureMeshParams& params)
{
  if (points.size() < 4)
  {
    throw InvalidInput("a structure mesh needs at least 4 points; got " +
                       std::to_string(points.size()));
  }
  if (params.edge_length < 0 || !std::isfinite(params.edge_length) ||
      !std::isfinite(params.mid_surface_radius) ||
      (params.edge_length == 0 && (params.vertices < 4 || params.vertices > params.vertex_limit)))
  {
    throw InvalidInput("a structure mesh needs a finite target edge length > 0 or a vertex count "
                       "in [4, " +
                       std::to_string(params.vertex_limit) + "] (the vertex limit); got " +
                       std::to_string(params.vertices) + " vertices, edge length " +
                       std::to_string(params.edge_length));
  }
  for (std::size_t i = 0; i < points.value_count(); ++i)
  {
    if (!std::isfinite(points.data()[i]))
    {
      throw InvalidInput("point " + std::to_string(i / 3) + " of the structure is not finite");
    }
  }
}

/// Throws InvalidInput when the points all coincide, TopologyError when they lie on a line: no
/// surface either way.
void require_surface_spread(const std::vector<double>& points)
{
  const std::size_t n = points.size() / 3;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i)
  {
    mean += Eigen::Vector3d(points[3 * i], points[3 * i + 1], points[3 * i + 2]) / double(n);
  }
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < n; ++i)
  {
    const Eigen::Vector3d d =
      Eigen::Vector3d(points[3 * i], points[3 * i + 1], points[3 * i + 2]) - mean;
    covariance += d * d.transpose();
  }
  const Eigen::Vector3d spread =
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance, Eigen::EigenvaluesOnly)
      .eigenvalues(); // ascending
  bool coincide = true;
  for (std::size_t i = 3; i < points.size() && coincide; ++i)
  {
    coincide = points[i] == points[i % 3];
  }
  if (coincide)
  {
    throw InvalidInput("all " + std::to_string(n) + " points of the structure coincide");
  }
  if (!(spread[1] > 1e-12 * spread[2]))
  {
    throw TopologyError("the " + std::to_string(n) +
                        " points lie on a line and describe no surface");
  }
}

/// Near-equilateral triangles, about two per vertex: area = 2 N (sqrt(3) / 4) L^2.
double edge_for_area(double area, std::size_t vertices)
{
  return std::sqrt(2.0 * area / (std::sqrt(3.0) * double(vertices)));
}

TriangleMesh to_triangle_mesh(const SurfaceMesh& mesh)
{
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
  return result;
}

SurfaceMesh to_surface_mesh(const TriangleMesh& mesh)
{
  SurfaceMesh result;
  std::vector<SurfaceMesh::Vertex_index> vertices;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
  {
    const auto p = mesh.point(std::int64_t(v));
    vertices.push_back(result.add_vertex(Point(p[0], p[1], p[2])));
  }
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
  {
    result.add_face(vertices[std::size_t(mesh.triangles[3 * t])],
                    vertices[std::size_t(mesh.triangles[3 * t + 1])],
                    vertices[std::size_t(mesh.triangles[3 * t + 2])]);
  }
  return result;
}

/// Closes the holes whose borders are shorter than the square root of the mesh's area: gaps
/// the reconstruction left, never a patch's outline (at least 3.5 times as long, as a circle's
/// is the shortest around a given area).
void close_small_holes(SurfaceMesh& mesh)
{
  const double longest = std::sqrt(PMP::area(mesh));
  std::vector<SurfaceMesh::Halfedge_index> borders;
  PMP::extract_boundary_cycles(mesh, std::back_inserter(borders));
  for (const auto start : borders)
  {
    if (PMP::face_border_length(start, mesh) < longest)
    {
      std::vector<SurfaceMesh::Face_index> faces;
      std::vector<SurfaceMesh::Vertex_index> vertices;
      PMP::triangulate_and_refine_hole(mesh, start, std::back_inserter(faces),
                                       std::back_inserter(vertices));
    }
  }
}

/// CGAL's advancing-front reconstruction through `sheet`, as one valid 2-manifold: the
/// largest component, small holes closed.
SurfaceMesh reconstructed_sheet(const std::vector<double>& sheet)
{
  std::vector<Point> cloud;
  cloud.reserve(sheet.size() / 3);
  for (std::size_t i = 0; i + 2 < sheet.size(); i += 3)
  {
    cloud.emplace_back(sheet[i], sheet[i + 1], sheet[i + 2]);
  }
  std::vector<std::array<std::size_t, 3>> facets;
  if (cloud.size() >= 3)
  {
    CGAL::advancing_front_surface_reconstruction(cloud.begin(), cloud.end(),
                                                 std::back_inserter(facets));
  }
  if (facets.empty())
  {
    throw TopologyError("the points describe no surface: no triangle could be reconstructed "
                        "through the " +
                        std::to_string(cloud.size()) + " point(s) of their middle sheet");
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
  PMP::duplicate_non_manifold_vertices(mesh);
  PMP::remove_degenerate_faces(mesh);
  PMP::keep_largest_connected_components(mesh, 1); // one sheet
  PMP::remove_isolated_vertices(mesh);
  mesh.collect_garbage();
  close_small_holes(mesh);
  PMP::remove_degenerate_faces(mesh);
  mesh.collect_garbage();
  if (mesh.number_of_faces() == 0 || !CGAL::is_valid_polygon_mesh(mesh))
  {
    throw TopologyError("the surface reconstructed through the " + std::to_string(cloud.size()) +
                        " points of the middle sheet is not a valid 2-manifold");
  }
  return mesh;
}

/// `reconstructed` remeshed isotropically to edges of `edge`, its boundary vertices sliding
/// along the boundary, then its angles evened (CGAL's angle smoothing, with Delaunay flips).
///
/// The five rounds of split, collapse, flip, relaxation and projection are CGAL's isotropic
/// remeshing, with its relaxation and projection made here: inside the remesher (CGAL 5.5), a
/// vertex whose faces all became degenerate reads past the end of its halfedge statuses
/// (CGAL issue 7345); outside it, the same relaxation has no such read.
SurfaceMesh remeshed(const SurfaceMesh& reconstructed, double edge)
{
  const RepairSurfaceTree surface(faces(reconstructed).first, faces(reconstructed).second,
                                  reconstructed);
  SurfaceMesh mesh = reconstructed;
  for (int round = 0; round < 5; ++round)
  {
    // A projection given (never called) spares the remesher a search tree of its own.
    const auto unused_projection = [&mesh](SurfaceMesh::Vertex_index v) { return mesh.point(v); };
    PMP::isotropic_remeshing(
      faces(mesh), edge, mesh,
      CGAL::parameters::number_of_relaxation_steps(0).do_project(false).projection_functor(
        unused_projection));
    mesh.collect_garbage();
    PMP::tangential_relaxation(mesh, CGAL::parameters::relax_constraints(true));
    // Back onto the reconstruction, as the remesher would: every vertex but the border's.
    for (const auto v : mesh.vertices())
    {
      if (!mesh.is_isolated(v) && !mesh.is_border(v))
      {
        mesh.point(v) = surface.closest_point(mesh.point(v));
      }
    }
  }
  PMP::angle_and_area_smoothing(
    mesh, CGAL::parameters::number_of_iterations(3).use_area_smoothing(false));
  mesh.collect_garbage();
  return mesh;
}

/// Moves every vertex of `mesh` along its normal onto the middle sheet: the reconstruction's
/// flat facets cut inside a curved sheet, and its points were thinned.
void project_onto_sheet(SurfaceMesh& mesh, const MidSheetFinder& finder)
{
  std::vector<double> positions;
  std::vector<double> normals;
  for (const auto v : mesh.vertices())
  {
    const Point& p = mesh.point(v);
    const Vector n = PMP::compute_vertex_normal(v, mesh);
    positions.insert(positions.end(), { p.x(), p.y(), p.z() });
    normals.insert(normals.end(), { n.x(), n.y(), n.z() });
  }
  finder.project(positions, normals);
  std::size_t i = 0;
  for (const auto v : mesh.vertices())
  {
    mesh.point(v) = Point(positions[i], positions[i + 1], positions[i + 2]);
    i += 3;
  }
}

/// The target edge from the asked size, given the sheet's area.
double target_edge(const StructureMeshParams& params, double area)
{
  const double edge =
    params.edge_length > 0 ? params.edge_length : edge_for_area(area, params.vertices);
  if (!(edge > 0) || !std::isfinite(edge))
  {
    throw TopologyError("the reconstructed surface has no area");
  }
  return edge;
}

/// Throws InvalidInput when edges of `edge` over `area` would make more vertices than the
/// limit: the remeshing would run for hours or exhaust the memory first.
void require_within_vertex_limit(const StructureMeshParams& params, double edge, double area)
{
  const double vertices = area / (std::sqrt(3.0) / 2 * edge * edge);
  if (!(vertices <= double(params.vertex_limit)))
  {
    std::ostringstream message;
    message.precision(4);
    message << "a structure mesh with edges of " << edge << " over the sheet's area of " << area
            << " would have about " << vertices << " vertices, more than the vertex limit of "
            << params.vertex_limit
            << "; give a longer edge length, or raise StructureMeshParams::vertex_limit";
    throw InvalidInput(message.str());
  }
}

/// The general path: reconstruction through the middle sheet, remeshing to the asked size.
SurfaceMesh reconstructed_structure(const std::vector<double>& points,
                                    const StructureMeshParams& params,
                                    const ParallelFor& parallel_for)
{
  const MidSheetFinder finder(points, { params.mid_surface_radius, 0, 0 }, parallel_for);
  const double spacing = finder.spacing();
  // A first edge from the area a coarse Poisson-disk set covers (about 0.8 / spacing^2 points
  // per unit area, its spacing wider than a bilayer so that each place counts once): the
  // samples of the middle sheet need be no denser than half of it.
  const double coarse = 8.0 * spacing;
  const double area =
    double(poisson_disk_subset(points, coarse).size() / 3) * coarse * coarse / 0.8;
  const double sample_spacing = std::max(spacing, 0.5 * target_edge(params, area));
  const MidSheet sheet = finder.samples(sample_spacing);
  // Both leaflets' samples gave points: one of each place.
  std::vector<double> thinned = poisson_disk_subset(sheet.points, sample_spacing);
  if (thinned.size() < 12)
  {
    // Too few to thin (a coarse mesh of a small cloud), or no middle sheet at all (a handful of
    // points): through the points themselves.
    thinned = sheet.points.size() >= 12 ? sheet.points : points;
  }
  const SurfaceMesh surface = reconstructed_sheet(thinned);
  const double sheet_area = PMP::area(surface);
  const double edge = target_edge(params, sheet_area);
  require_within_vertex_limit(params, edge, sheet_area);
  SurfaceMesh mesh = remeshed(surface, edge);
  if (params.edge_length <= 0)
  {
    // Once more with the edge corrected by the count it gave.
    const double ratio = double(mesh.number_of_vertices()) / double(params.vertices);
    if (std::abs(ratio - 1.0) > 0.05)
    {
      mesh = remeshed(surface, edge * std::sqrt(ratio));
    }
  }
  project_onto_sheet(mesh, finder);
  if (CGAL::is_closed(mesh) && !PMP::is_outward_oriented(mesh))
  {
    PMP::reverse_face_orientations(mesh);
  }
  return mesh;
}

/// The periodic path: a lattice over the box cell the membrane spans.
SurfaceMesh lattice_structure(const std::vector<double>& points, const SheetCell& cell,
                              const StructureMeshParams& params, const ParallelFor& parallel_for)
{
  const double spacing = sheet_spacing(points);
  if (params.edge_length > 0)
  {
    const Eigen::Vector3d a(cell.a[0], cell.a[1], cell.a[2]), b(cell.b[0], cell.b[1], cell.b[2]);
    require_within_vertex_limit(params, params.edge_length, a.cross(b).norm());
  }
  const LatticeShape shape = lattice_shape(cell, params.vertices, params.edge_length);
  const double a_length =
    std::sqrt(cell.a[0] * cell.a[0] + cell.a[1] * cell.a[1] + cell.a[2] * cell.a[2]);
  const double edge = a_length / shape.columns;
  const double sample_spacing = std::max(spacing, 0.5 * edge);
  // Neighbours across the cell's sides: as far as the middle sheet's cylinders reach (8
  // spacings up and 2 across, or 1.5 leaflet distances up), with room.
  const double reach = std::max(12.0 * spacing, 1.6 * params.mid_surface_radius);
  const std::vector<double> cloud = with_periodic_images(points, cell, reach);
  const MidSheetFinder finder(cloud, { params.mid_surface_radius, points.size() / 3, spacing },
                              parallel_for);
  const MidSheet sheet = finder.samples(sample_spacing);
  const double smoothing = std::max(sample_spacing, 0.5 * edge);
  const std::vector<double> lifted = with_periodic_images(sheet.points, cell, 3.0 * smoothing);
  return to_surface_mesh(sheet_lattice(cell, shape, lifted, smoothing));
}

/// Throws TopologyError naming the worst triangle when an angle is out of the bound.
void require_angle_bound(const TriangleMesh& mesh)
{
  double worst = 0;
  std::size_t worst_triangle = 0;
  double worst_angle = 60;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
  {
    const std::array<std::array<double, 3>, 3> p{ mesh.point(mesh.triangles[3 * t]),
                                                  mesh.point(mesh.triangles[3 * t + 1]),
                                                  mesh.point(mesh.triangles[3 * t + 2]) };
    const double sides[3] = { length(p[1], p[2]), length(p[2], p[0]), length(p[0], p[1]) };
    for (int k = 0; k < 3; ++k)
    {
      const double b = sides[(k + 1) % 3], c = sides[(k + 2) % 3];
      const double cosine =
        b > 0 && c > 0 ? (b * b + c * c - sides[k] * sides[k]) / (2 * b * c) : 1.0;
      const double angle = std::acos(std::clamp(cosine, -1.0, 1.0)) * degrees;
      const double miss =
        std::max(structure_mesh_min_angle - angle, angle - structure_mesh_max_angle);
      if (miss > worst)
      {
        worst = miss;
        worst_triangle = t;
        worst_angle = angle;
      }
    }
  }
  if (worst > 0)
  {
    std::array<double, 3> centre{ 0, 0, 0 };
    for (std::size_t k = 0; k < 3; ++k)
    {
      const auto p = mesh.point(mesh.triangles[3 * worst_triangle + k]);
      for (int d = 0; d < 3; ++d)
      {
        centre[d] += p[d] / 3;
      }
    }
    std::ostringstream message;
    message.precision(4);
    message << "the structure mesh's triangles cannot all get angles within "
            << structure_mesh_min_angle << "-" << structure_mesh_max_angle << "°: triangle "
            << worst_triangle << " near (" << centre[0] << ", " << centre[1] << ", " << centre[2]
            << ") keeps an angle of " << worst_angle
            << "°; try another vertex count or give a structure mesh";
    throw TopologyError(message.str());
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
  const auto loops = boundary_loops(mesh);
  quality.boundary_loops = loops.size();
  for (const auto& loop : loops)
  {
    quality.boundary_edges += loop.size();
  }
  quality.components = component_count(mesh);
  return quality;
}

TriangleMesh structure_mesh(PointSpan<const double> points, const StructureMeshParams& params,
                            MeshQuality* quality, const ParallelFor& parallel_for)
{
  require_valid(points, params);
  // A membrane split by the box along its normal (or a vesicle by its faces) in one piece.
  std::vector<double> whole(points.data(), points.data() + points.value_count());
  if (params.box.is_set())
  {
    const auto shifts = assembly_shifts(points, params.box);
    for (std::size_t i = 0; i < shifts.size(); ++i)
    {
      for (std::size_t k = 0; k < 3; ++k)
      {
        whole[3 * i + k] += shifts[i][k];
      }
    }
  }
  require_surface_spread(whole);
  const auto cell = periodic_sheet_cell(whole, params.box);
  SurfaceMesh mesh = cell ? lattice_structure(whole, *cell, params, parallel_for)
                          : reconstructed_structure(whole, params, parallel_for);
  repair_angles(mesh, repair_goal);
  TriangleMesh result = to_triangle_mesh(mesh);
  require_angle_bound(result);
  if (quality)
  {
    *quality = mesh_quality(result);
  }
  return result;
}

} // namespace mesolens
