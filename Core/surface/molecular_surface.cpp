// SPDX-License-Identifier: GPL-3.0-or-later
#include <Eigen/Dense>

#include "mesolens/surface/molecular_surface.h"

#include "mesolens/common/errors.h"

#include "surface/detail/chord_refinement.h"
#include "surface/detail/contour_tetrahedra.h"
#include "surface/detail/probe_distance.h"
#include "surface/detail/sas_boundary.h"
#include "surface/detail/ses_patches.h"
#include "surface/detail/ses_piece_projection.h"
#include "surface/detail/surface_contour_fields.h"
#include "surface/detail/surface_projections.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <initializer_list>
#include <limits>
#include <memory>
#include <sstream>
#include <string>

namespace mesolens {

namespace {
using Vec = Eigen::Vector3d;
constexpr double largest_radius = 20.0;        // Å: no atom, bead or probe is larger
constexpr double largest_triangle_count = 2e7; // about 2 GB: a finer tolerance is refused
/// The most blocks the lattice's box may hold. Only blocks near atoms cost memory and time, so
/// this bounds the box rather than the work: a box of more blocks means atoms kilometres apart
/// at a fine tolerance, far likelier an input in the wrong unit than a molecule. (A compact
/// molecule reaches the triangle limit first.)
constexpr double largest_lattice_block_count = 2e7;
/// The lattice's resolution, the farthest any point lies from a lattice point (its reach), is
/// that of a cubic grid whose cells' diagonals have a chord error of the tolerance's times
/// grid_tolerance_ratio, at most coarse_grid_tolerance (Å); the splits bring the mesh to the
/// tolerance. Finer lattices cost more than the splits that refine a coarse mesh as far; and
/// triangles at creases, which splits leave as the lattice made them, must shrink with the
/// tolerance for the mesh's area to converge to the exact one. At the coarsest, a 1.4 Å probe's
/// surface on atoms of 1.4 Å and more meets the cavity limit below. (Walls between cavities
/// thinner than the lattice's spacing may be missed and their cavities merged: in 3wip cubic
/// grids of 1.3 Å to 0.47 Å find 56 to 67 cavities, body-centred lattices of 1.6, 2.0, 2.24
/// and 2.5 Å find 57, 48, 55 and 51.)
constexpr double coarse_grid_tolerance = 0.56;
constexpr double grid_tolerance_ratio = 6.0;
/// The solvent-excluded surface's lattice reaches every point from at most this many probe
/// radii, so each cavity and neck, which holds a probe's ball, holds a lattice point outside
/// the surface.
constexpr double cavity_reach_ratio = 0.9;
/// A body-centred cubic lattice reaches every point from sqrt(5) / 4 of its spacing (the cubes'
/// side): its spacing per Å of reach.
constexpr double spacing_per_reach = 4.0 / 2.23606797749979;
/// How far beyond the probe radius the solvent-excluded field labels lattice points with their
/// nearest boundary piece, in spacings: the inner ends of most edges the surface crosses then
/// carry the piece that places the vertex. (Labelling farther costs more than the searches it
/// saves: on 3wip 0.5, 0.6, 0.7, 0.87 and 1.0 spacings took 6.17, 6.14, 6.15, 6.22 and 6.29
/// billion instructions.)
constexpr double hint_reach = 0.6;

void check_input(PointSpan<const double> centres, const std::vector<double>& radii,
                 const MolecularSurfaceParams& options)
{
  if (radii.size() != centres.size())
  {
    throw InvalidInput(
      "molecular_surface needs one radius per atom: " + std::to_string(centres.size()) +
      " atoms, " + std::to_string(radii.size()) + " radii");
  }
  for (std::size_t i = 0; i < centres.size(); ++i)
  {
    if (!std::isfinite(centres[i][0]) || !std::isfinite(centres[i][1]) ||
        !std::isfinite(centres[i][2]))
    {
      throw InvalidInput("atom " + std::to_string(i) + " has a non-finite position");
    }
    if (!(radii[i] > 0) || !(radii[i] <= largest_radius))
    {
      throw InvalidInput("atom " + std::to_string(i) + " has radius " + std::to_string(radii[i]) +
                         " Å; radii must lie in (0, 20] Å");
    }
  }
  if (options.kind != SurfaceKind::VanDerWaals &&
      (!(options.probe_radius > 0) || !(options.probe_radius <= largest_radius)))
  {
    throw InvalidInput("probe radius " + std::to_string(options.probe_radius) +
                       " Å is outside (0, 20] Å");
  }
  if (!(options.tolerance >= 0.005) || !(options.tolerance <= 1.0))
  {
    throw InvalidInput("surface tolerance " + std::to_string(options.tolerance) +
                       " Å is outside [0.005, 1] Å");
  }
}

/// Per vertex, its mesh component (triangles joined by vertices), numbered in the order of their
/// lowest vertices; `count` gets their number. Concurrent union-find: a root is only ever linked
/// to a lower root, so each component's root ends as its lowest vertex whatever the threads.
std::vector<std::size_t> component_labels(const std::vector<std::int64_t>& triangles,
                                          std::size_t vertex_count, std::size_t& count,
                                          const ParallelFor& parallel_for)
{
  std::vector<std::atomic<std::size_t>> parent(vertex_count);
  run_parallel(parallel_for, vertex_count, [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v)
    {
      parent[v].store(v, std::memory_order_relaxed);
    }
  });
  const auto find = [&](std::size_t x) {
    for (;;)
    {
      std::size_t up = parent[x].load(std::memory_order_relaxed);
      if (up == x)
      {
        return x;
      }
      const std::size_t next = parent[up].load(std::memory_order_relaxed);
      if (next != up)
      {
        // Path halving: `next` is an ancestor of x too.
        parent[x].compare_exchange_weak(up, next, std::memory_order_relaxed);
      }
      x = next;
    }
  };
  const auto unite = [&](std::size_t a, std::size_t b) {
    for (;;)
    {
      a = find(a);
      b = find(b);
      if (a == b)
      {
        return;
      }
      std::size_t higher = std::max(a, b);
      if (parent[higher].compare_exchange_strong(higher, std::min(a, b), std::memory_order_relaxed))
      {
        return;
      }
    }
  };
  run_parallel(parallel_for, triangles.size() / 3, [&](std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t)
    {
      unite(std::size_t(triangles[3 * t]), std::size_t(triangles[3 * t + 1]));
      unite(std::size_t(triangles[3 * t]), std::size_t(triangles[3 * t + 2]));
    }
  });
  // Each root is its component's lowest vertex: numbered on meeting it.
  std::vector<std::size_t> label(vertex_count, 0);
  count = 0;
  for (std::size_t v = 0; v < vertex_count; ++v)
  {
    const std::size_t root = parent[v].load(std::memory_order_relaxed);
    label[v] = root == v ? count++ : label[find(root)];
  }
  return label;
}

/// What the stages read: the atoms as spheres, inflated by the probe but for the van der Waals
/// surface (the spheres whose union is traced), and the options.
struct SurfaceInput
{
  const MolecularSurfaceParams& options;
  const std::vector<double>& atom_radii;
  std::vector<Vec> centres;
  std::vector<double> radii; ///< of the spheres whose union is traced
  double smallest_atom = largest_radius;
  double largest_sphere = 0;
  bool excluded = false; ///< the solvent-excluded surface
  /// Whether the exact figures are computed: always but for the SES without exact_figures.
  bool figures = false;
  double probe = 0;
};

SurfaceInput surface_input(PointSpan<const double> centre_list,
                           const std::vector<double>& atom_radii,
                           const MolecularSurfaceParams& options)
{
  SurfaceInput input{ options, atom_radii };
  input.excluded = options.kind == SurfaceKind::SolventExcluded;
  input.figures = !input.excluded || options.exact_figures;
  // The van der Waals surface has no probe: whatever the option holds (unchecked, NaN too).
  input.probe = options.kind == SurfaceKind::VanDerWaals ? 0.0 : options.probe_radius;
  const std::size_t n = centre_list.size();
  input.centres.resize(n);
  input.radii.resize(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    input.centres[i] = Vec(centre_list[i][0], centre_list[i][1], centre_list[i][2]);
    input.radii[i] = atom_radii[i] + input.probe;
    input.smallest_atom = std::min(input.smallest_atom, atom_radii[i]);
    input.largest_sphere = std::max(input.largest_sphere, input.radii[i]);
  }
  return input;
}

/// The body-centred cubic lattice the tessellation starts from (its tetrahedra's longest edges
/// one spacing long), before edges are split where they stray from the surface. An edge gives a
/// chord error of its length squared over eight radii of curvature on the most curved patches
/// (the probe's or the smallest atom's); the lattice's is coarser than the tolerance (see
/// grid_tolerance_ratio), and the splits bring each edge's midpoint within three quarters of
/// the tolerance (so the triangles' centres within it).
struct Lattice
{
  double curvature_radius = 0; ///< of the most curved patches
  double spacing = 0;          ///< the cubes' side
  double tolerance = 0;        ///< the chord error of its edges on the most curved patches
};

/// The spacing of a cubic grid whose cells' diagonals have a chord error of `tolerance` on a
/// sphere of `curvature_radius`.
double cubic_spacing_for(double tolerance, double curvature_radius)
{
  return std::sqrt(8.0 * tolerance * curvature_radius) / std::sqrt(3.0);
}

Lattice choose_lattice(const SurfaceInput& input)
{
  const MolecularSurfaceParams& options = input.options;
  const double p = input.probe;
  Lattice lattice;
  // Atoms, probes and cavities smaller than the tolerance cannot be drawn within it, so the
  // lattice does not resolve them: without this floor its cost grew without bound as a radius
  // went to 0 (an atom of 1e-4 Å took 0.8 s, one of 1e-6 Å minutes).
  lattice.curvature_radius =
    std::max(options.tolerance,
             input.excluded
               ? std::min(p, input.smallest_atom)
               : input.smallest_atom + (options.kind == SurfaceKind::SolventAccessible ? p : 0.0));
  double reach = 0.5 * std::sqrt(3.0) *
    cubic_spacing_for(std::max(
                        options.tolerance,
                        std::min(coarse_grid_tolerance, grid_tolerance_ratio * options.tolerance)),
                      lattice.curvature_radius);
  if (input.excluded)
  {
    reach = std::min(reach, cavity_reach_ratio * std::max(p, options.tolerance));
  }
  lattice.spacing = spacing_per_reach * reach;
  lattice.tolerance = lattice.spacing * lattice.spacing / (8.0 * lattice.curvature_radius);
  return lattice;
}

/// Throws InvalidInput, before any work, when the tolerance would need too many triangles: the
/// SES is rarely larger than 1.2 times the SAS, and a mesh refined to a tolerance has fewer
/// triangles than a grid as fine would give.
void refuse_too_fine(const SurfaceInput& input, const SasBoundary& boundary, const Lattice& lattice)
{
  const double tolerance = input.options.tolerance;
  double estimate = 0;
  for (const double a : boundary.area)
  {
    estimate += a;
  }
  estimate *= input.excluded ? 1.2 : 1.0;
  const double fine_spacing = cubic_spacing_for(tolerance, lattice.curvature_radius);
  const double expected_triangles = 5.0 * estimate / (fine_spacing * fine_spacing);
  if (expected_triangles > largest_triangle_count)
  {
    throw InvalidInput("a surface of about " + std::to_string(estimate) + " Å² at tolerance " +
                       std::to_string(tolerance) + " Å would need about " +
                       std::to_string(expected_triangles / 1e6) +
                       " million triangles; choose a larger tolerance");
  }
}

/// One index of the boundary's pieces for the exact figures and the tessellation, with the
/// larger reach either asks for (a larger one only coarsens its cells); none when neither
/// needs one.
std::unique_ptr<const ProbeDistance> piece_index(const SurfaceInput& input,
                                                 const SasBoundary& boundary,
                                                 const Lattice& lattice,
                                                 const ParallelFor& parallel_for)
{
  const double p = input.probe;
  const double patch_reach =
    input.excluded && input.figures ? 2.0 * p + 0.6 * input.largest_sphere : 0.0;
  const double mesh_reach =
    input.options.tessellate ? (input.excluded ? p : 0.0) + 3.0 * lattice.spacing : 0.0;
  if (patch_reach > 0 || mesh_reach > 0)
  {
    return std::make_unique<const ProbeDistance>(input.centres, input.radii, boundary,
                                                 std::max(patch_reach, mesh_reach), parallel_for);
  }
  return nullptr;
}

/// The exact area and volume per patch: the SES's patch integrals, or the union's exposed
/// spheres (a volume term of (R area + centre . normal integral) / 3 each, the divergence
/// theorem's). Empty without the figures.
SesPatchIntegrals exact_patches(const SurfaceInput& input, const SasBoundary& boundary,
                                const ProbeDistance* distance, const ParallelFor& parallel_for)
{
  SesPatchIntegrals patches;
  if (input.excluded && input.figures)
  {
    patches = ses_patch_integrals(input.centres, input.atom_radii, input.probe, boundary, *distance,
                                  parallel_for);
  }
  else if (input.figures)
  {
    const std::size_t n = input.centres.size();
    patches.face_area = boundary.area;
    patches.face_volume.resize(n);
    for (std::size_t i = 0; i < n; ++i)
    {
      patches.face_volume[i] =
        (input.radii[i] * boundary.area[i] + input.centres[i].dot(boundary.normal_integral[i])) /
        3.0;
    }
  }
  return patches;
}

/// The field whose zero set is the surface: for the SES the distance to the nearest probe
/// position less the probe radius, labelling lattice points near the surface with their nearest
/// piece; for the others the spheres' union.
std::unique_ptr<ContourField> surface_field(const SurfaceInput& input, const SasBoundary& boundary,
                                            const ProbeDistance& distance,
                                            const SesPieceProjection& pieces,
                                            const Lattice& lattice)
{
  const double p = input.probe;
  return input.excluded
    ? excluded_surface_field(distance, pieces, boundary, input.centres, input.radii,
                             input.atom_radii, p, p + hint_reach * lattice.spacing)
    : union_surface_field(input.centres, input.radii);
}

/// The field's zero set contoured on the lattice, over the spheres' box with two cells to
/// spare, shifted off any symmetry of the input.
ContourMesh contour_lattice(ContourField& field, const SurfaceInput& input, const Lattice& lattice,
                            const ParallelFor& parallel_for,
                            const std::function<void(double)>& progress)
{
  const double spacing = lattice.spacing;
  Vec low = Vec::Constant(1e300), high = -low;
  for (std::size_t i = 0; i < input.centres.size(); ++i)
  {
    low = low.cwiseMin(input.centres[i] - Vec::Constant(input.radii[i]));
    high = high.cwiseMax(input.centres[i] + Vec::Constant(input.radii[i]));
  }
  low -= Vec(2.0 + 0.318309886, 2.0 + 0.271828183, 2.0 + 0.141421356) * spacing;
  high += Vec::Constant(3.0 * spacing);
  const ContourGrid grid(low, high, spacing);
  const double blocks = double(grid.blocks[0]) * double(grid.blocks[1]) * double(grid.blocks[2]);
  if (!(blocks <= largest_lattice_block_count))
  {
    std::ostringstream message;
    message.precision(3);
    message << "the surface's lattice would span " << (high - low).x() << " x " << (high - low).y()
            << " x " << (high - low).z() << " Å at a spacing of " << spacing << " Å, about "
            << blocks << " blocks of " << ContourGrid::block_cells << "^3 cells, more than "
            << "the limit of " << largest_lattice_block_count
            << ": atoms far apart make the box large; give them separately, or choose a larger "
               "tolerance";
    throw InvalidInput(message.str());
  }
  return contour_tetrahedra(field, low, high, spacing, parallel_for, progress);
}

/// Splits the mesh's edges until their midpoints lie within three quarters of the tolerance.
/// Each round of splits divides an edge's deviation by about four: enough rounds to go from the
/// lattice's chord error to the tolerance, and two for edges the lattice left longer.
void refine_to_tolerance(ContourMesh& mesh, const SurfaceInput& input, const SasBoundary& boundary,
                         const ProbeDistance& distance, const SesPieceProjection& pieces,
                         const Lattice& lattice, const ParallelFor& parallel_for)
{
  const double tolerance = input.options.tolerance;
  const double spacing = lattice.spacing;
  const double split_tolerance = 0.75 * tolerance;
  const int rounds =
    std::min(8,
             2 +
               static_cast<int>(std::ceil(std::log(std::max(1.0, lattice.tolerance / tolerance)) /
                                          std::log(4.0))));
  SurfaceProjection projection;
  if (input.excluded)
  {
    // Midpoints of edges up to a spacing long stray less than three quarters of one.
    const double projection_limit = input.probe + 0.75 * spacing;
    projection = [&, projection_limit] {
      return excluded_surface_projection(distance, pieces, boundary, input.centres,
                                         input.atom_radii, input.probe, projection_limit);
    };
  }
  else
  {
    projection = [&] {
      return union_surface_projection(distance, input.centres, input.radii, 1.5 * spacing);
    };
  }
  refine_chords(mesh, projection, split_tolerance, 1.5 * spacing, rounds, parallel_for);
}

/// The triangle mesh: the lattice's contour, refined to the tolerance.
ContourMesh tessellate(const SurfaceInput& input, const SasBoundary& boundary,
                       const ProbeDistance& distance, const SesPatchIntegrals& patches,
                       const Lattice& lattice, const ParallelFor& parallel_for,
                       const std::function<void(double)>& progress)
{
  SesPieceProjection pieces(input.centres, input.atom_radii, input.probe, boundary, distance);
  // Patches the exact figures certified uncut need no further certificate (none without the
  // figures).
  pieces.take_uncut_patches(patches.arc_uncut, patches.vertex_uncut);
  const std::unique_ptr<ContourField> field =
    surface_field(input, boundary, distance, pieces, lattice);
  ContourMesh mesh = contour_lattice(*field, input, lattice, parallel_for, progress);
  refine_to_tolerance(mesh, input, boundary, distance, pieces, lattice, parallel_for);
  return mesh;
}

/// The mesh's components (triangles joined by vertices); cavities are those enclosing negative
/// volume (their normals face inwards).
struct Components
{
  std::vector<std::size_t> of_vertex;
  std::vector<char> cavity; ///< per component
  std::size_t count = 0, cavities = 0;

  bool in_cavity(std::size_t vertex) const
  {
    return this->cavity[this->of_vertex[vertex]] != 0;
  }
};

Components find_components(const ContourMesh& mesh, const ParallelFor& parallel_for)
{
  const std::vector<ContourVertex>& vertices = mesh.vertices;
  const std::vector<std::int64_t>& triangles = mesh.triangles;
  Components components;
  components.of_vertex =
    component_labels(triangles, vertices.size(), components.count, parallel_for);
  std::vector<double> component_volume(components.count, 0.0);
  for (std::size_t t = 0; t < triangles.size(); t += 3)
  {
    const Vec& a = vertices[std::size_t(triangles[t])].position;
    const Vec& b = vertices[std::size_t(triangles[t + 1])].position;
    const Vec& c = vertices[std::size_t(triangles[t + 2])].position;
    component_volume[components.of_vertex[std::size_t(triangles[t])]] += a.dot(b.cross(c)) / 6.0;
  }
  components.cavity.assign(components.count, 0);
  for (std::size_t k = 0; k < components.count; ++k)
  {
    components.cavity[k] = component_volume[k] < 0 ? 1 : 0;
  }
  components.cavities =
    static_cast<std::size_t>(std::count(components.cavity.begin(), components.cavity.end(), 1));
  return components;
}

/// Whether the mesh vertex nearest a point, among the vertices of some atoms, lies in a cavity.
class NearestVertex
{
public:
  NearestVertex(const std::vector<ContourVertex>& vertices, const Components& components,
                std::size_t atom_count)
    : vertices_(vertices)
    , components_(components)
    , on_atom_(atom_count)
  {
    for (std::size_t v = 0; v < vertices.size(); ++v)
    {
      this->on_atom_[std::size_t(vertices[v].atom)].push_back(static_cast<std::uint32_t>(v));
    }
  }

  bool in_cavity(const Vec& x, std::initializer_list<std::uint32_t> atoms) const
  {
    double best = 1e300;
    bool in_cavity = false;
    for (const std::uint32_t atom : atoms)
    {
      for (const std::uint32_t v : this->on_atom_[atom])
      {
        const double d = (this->vertices_[v].position - x).squaredNorm();
        if (d < best)
        {
          best = d;
          in_cavity = this->components_.in_cavity(v);
        }
      }
    }
    return in_cavity;
  }

private:
  const std::vector<ContourVertex>& vertices_;
  const Components& components_;
  std::vector<std::vector<std::uint32_t>> on_atom_; ///< per atom, its vertices
};

/// Zeroes the figures of the tori and concave patches in cavities: by vote of their mesh
/// vertices, or for those without any, the component of the nearest vertex of their atoms.
void drop_cavity_toroidal_and_concave(const std::vector<ContourVertex>& vertices,
                                      const Components& components, const NearestVertex& nearest,
                                      const SasBoundary& boundary, SesPatchIntegrals& patches)
{
  std::vector<int> arc_votes(boundary.arcs.size(), 0), vertex_votes(boundary.vertices.size(), 0);
  std::vector<int> arc_seen(boundary.arcs.size(), 0), vertex_seen(boundary.vertices.size(), 0);
  for (std::size_t v = 0; v < vertices.size(); ++v)
  {
    const int vote = components.in_cavity(v) ? 1 : -1;
    if (vertices[v].patch == static_cast<std::uint8_t>(SurfacePatch::Toroidal))
    {
      arc_votes[vertices[v].piece] += vote;
      arc_seen[vertices[v].piece] = 1;
    }
    else if (vertices[v].patch == static_cast<std::uint8_t>(SurfacePatch::Concave))
    {
      vertex_votes[vertices[v].piece] += vote;
      vertex_seen[vertices[v].piece] = 1;
    }
  }
  for (std::size_t k = 0; k < boundary.arcs.size(); ++k)
  {
    const SasArc& arc = boundary.arcs[k];
    const bool gone = arc_seen[k]
      ? arc_votes[k] > 0
      : nearest.in_cavity(arc.point(arc.start + 0.5 * arc.span), { arc.first, arc.second });
    if (gone)
    {
      patches.arc_area[k] = patches.arc_volume[k] = 0;
    }
  }
  for (std::size_t k = 0; k < boundary.vertices.size(); ++k)
  {
    const auto& s3 = boundary.vertices[k].spheres;
    const bool gone = vertex_seen[k]
      ? vertex_votes[k] > 0
      : nearest.in_cavity(boundary.vertices[k].position, { s3[0], s3[1], s3[2] });
    if (gone)
    {
      patches.vertex_area[k] = patches.vertex_volume[k] = 0;
    }
  }
}

/// Takes the parts in cavities off the spheres' convex patches: per sphere, its boundary loops
/// each placed by the nearest vertex on that atom, the part bounded by its cavity loops taken
/// as one region (Gauss-Bonnet per region).
void drop_cavity_convex_parts(const SurfaceInput& input, const NearestVertex& nearest,
                              const SasBoundary& boundary, SesPatchIntegrals& patches)
{
  constexpr double two_pi = 6.28318530717958647692;
  std::vector<double>& face_area = patches.face_area;
  std::vector<double>& face_volume = patches.face_volume;
  const std::vector<Vec>& centres = input.centres;
  std::size_t first_loop = 0;
  for (std::size_t i = 0; i < centres.size(); ++i)
  {
    std::size_t end_loop = first_loop;
    while (end_loop < boundary.loops.size() && boundary.loops[end_loop].sphere == i)
    {
      ++end_loop;
    }
    const double atom_scale = input.atom_radii[i] / input.radii[i]; // the SAS sphere onto the atom
    const double scale = input.excluded ? atom_scale : 1.0;
    const double surface_radius = input.excluded ? input.atom_radii[i] : input.radii[i];
    const std::uint32_t atom = static_cast<std::uint32_t>(i);
    std::size_t cavity_loops = 0;
    double turning = 0;
    Vec normal_integral = Vec::Zero();
    for (std::size_t l = first_loop; l < end_loop; ++l)
    {
      const SasLoop& loop = boundary.loops[l];
      const Vec on_surface = centres[i] + scale * (loop.sample - centres[i]);
      if (nearest.in_cavity(on_surface, { atom }))
      {
        ++cavity_loops;
        turning += loop.turning;
        normal_integral += loop.normal_integral;
      }
    }
    const std::size_t loop_count = end_loop - first_loop;
    first_loop = end_loop;
    if (face_area[i] <= 0)
    {
      continue;
    }
    if (loop_count == 0)
    {
      // Wholly exposed: a sphere of its own.
      const Vec pole = centres[i] + Vec(surface_radius, 0, 0);
      if (nearest.in_cavity(pole, { atom }))
      {
        face_area[i] = face_volume[i] = 0;
      }
      continue;
    }
    if (cavity_loops == 0)
    {
      continue;
    }
    if (cavity_loops == loop_count)
    {
      face_area[i] = face_volume[i] = 0;
      continue;
    }
    const double unit = std::max(0.0, two_pi * (2.0 - double(cavity_loops)) - turning);
    const double area = surface_radius * surface_radius * unit;
    const Vec normals = scale * scale * normal_integral;
    face_area[i] = std::max(0.0, face_area[i] - area);
    face_volume[i] -= (surface_radius * area + centres[i].dot(normals)) / 3.0;
  }
}

/// The exact figures summed per patch kind (NaN without them).
void sum_figures(const SesPatchIntegrals& patches, bool figures, MolecularSurface& surface)
{
  if (!figures)
  {
    surface.area = surface.volume = std::numeric_limits<double>::quiet_NaN();
    surface.patch_area.fill(std::numeric_limits<double>::quiet_NaN());
    return;
  }
  const auto add = [&](const std::vector<double>& area, const std::vector<double>& volume,
                       SurfacePatch kind) {
    const int slot = static_cast<int>(kind);
    for (std::size_t k = 0; k < area.size(); ++k)
    {
      surface.patch_area[slot] += area[k];
      surface.volume += volume[k];
      surface.patch_count[slot] += area[k] > 0 ? 1 : 0;
    }
  };
  add(patches.face_area, patches.face_volume, SurfacePatch::Convex);
  add(patches.arc_area, patches.arc_volume, SurfacePatch::Toroidal);
  add(patches.vertex_area, patches.vertex_volume, SurfacePatch::Concave);
  surface.area = surface.patch_area[0] + surface.patch_area[1] + surface.patch_area[2];
}

/// The mesh into `surface`, less the cavities unless `keep_all` (arrays sized first, then
/// filled in place; when every vertex stays, the triangles keep their indices).
void copy_mesh(ContourMesh& mesh, const Components& components, bool keep_all,
               const ParallelFor& parallel_for, MolecularSurface& surface)
{
  const std::vector<ContourVertex>& vertices = mesh.vertices;
  std::vector<std::int64_t> new_index(keep_all ? 0 : vertices.size(), -1);
  std::size_t kept = keep_all ? vertices.size() : 0;
  for (std::size_t v = 0; v < new_index.size(); ++v)
  {
    if (!components.in_cavity(v))
    {
      new_index[v] = static_cast<std::int64_t>(kept++);
    }
  }
  surface.points.resize(3 * kept);
  surface.normals.resize(3 * kept);
  surface.atom.resize(kept);
  surface.patch.resize(kept);
  run_parallel(parallel_for, vertices.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v)
    {
      const std::int64_t k = keep_all ? static_cast<std::int64_t>(v) : new_index[v];
      if (k < 0)
      {
        continue;
      }
      const std::size_t at = static_cast<std::size_t>(k);
      const ContourVertex& vertex = vertices[v];
      for (int a = 0; a < 3; ++a)
      {
        surface.points[3 * at + std::size_t(a)] = vertex.position[a];
        surface.normals[3 * at + std::size_t(a)] = vertex.normal[a];
      }
      surface.atom[at] = vertex.atom;
      surface.patch[at] = static_cast<SurfacePatch>(vertex.patch);
    }
  });
  if (keep_all)
  {
    surface.triangles = std::move(mesh.triangles);
  }
  else
  {
    for (const std::int64_t v : mesh.triangles)
    {
      if (new_index[std::size_t(v)] >= 0)
      {
        surface.triangles.push_back(new_index[std::size_t(v)]);
      }
    }
  }
}
} // namespace

MolecularSurface molecular_surface(PointSpan<const double> centre_list,
                                   const std::vector<double>& atom_radii,
                                   const MolecularSurfaceParams& options,
                                   const ParallelFor& parallel_for, const SurfaceProgress& progress)
{
  check_input(centre_list, atom_radii, options);
  MolecularSurface surface;
  if (centre_list.empty())
  {
    return surface;
  }
  const auto report = [&](double fraction) {
    if (progress)
    {
      progress(fraction);
    }
  };
  const SurfaceInput input = surface_input(centre_list, atom_radii, options);
  const SasBoundary boundary = sas_boundary(centre_list, input.radii, input.excluded, parallel_for);
  surface.degenerate_vertex_count = boundary.degenerate_vertices;
  report(0.1);

  const Lattice lattice = choose_lattice(input);
  surface.grid_spacing = lattice.spacing;
  if (options.tessellate)
  {
    refuse_too_fine(input, boundary, lattice);
  }
  const std::unique_ptr<const ProbeDistance> distance =
    piece_index(input, boundary, lattice, parallel_for);
  SesPatchIntegrals patches = exact_patches(input, boundary, distance.get(), parallel_for);
  surface.singular_patch_count = patches.singular_count;
  report(0.2);

  ContourMesh mesh;
  if (options.tessellate)
  {
    mesh = tessellate(input, boundary, *distance, patches, lattice, parallel_for,
                      [&](double f) { report(0.2 + 0.7 * f); });
    report(0.95);
  }

  const Components components = find_components(mesh, parallel_for);
  surface.component_count = components.count;
  surface.cavity_count = components.cavities;
  // The exact figures less those of dropped cavities (in place: the patch integrals are not
  // needed afterwards). Tori and concave patches go whole, convex ones by their boundary loops.
  if (input.figures && !options.keep_cavities && components.cavities > 0)
  {
    const NearestVertex nearest(mesh.vertices, components, centre_list.size());
    drop_cavity_toroidal_and_concave(mesh.vertices, components, nearest, boundary, patches);
    drop_cavity_convex_parts(input, nearest, boundary, patches);
  }
  sum_figures(patches, input.figures, surface);
  copy_mesh(mesh, components, options.keep_cavities || components.cavities == 0, parallel_for,
            surface);
  if (!options.keep_cavities)
  {
    surface.component_count -= surface.cavity_count;
  }
  report(1.0);
  return surface;
}

} // namespace mesolens
