// SPDX-License-Identifier: GPL-3.0-or-later
// Molecular surfaces of a set of atoms (spheres): the solvent-excluded surface from its analytic
// patches, the solvent-accessible and the van der Waals surface; their exact areas and volumes,
// and watertight triangle meshes of them to a chosen chord error.
#pragma once

#include "mesolens/common/parallel_for.h"
#include "mesolens/common/point_span.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace mesolens {

/// Which surface of the atoms.
enum class SurfaceKind : std::uint8_t
{
  /// Where a probe sphere rolled over the atoms cannot reach (Richards' molecular surface,
  /// Connolly's): convex parts of the atoms, saddles (torus pieces) where the probe touches two
  /// atoms, concave spherical triangles where it touches three.
  SolventExcluded = 0,
  /// The surface the probe's centre traces: the atoms' spheres inflated by the probe radius.
  SolventAccessible = 1,
  /// The atoms' spheres themselves (the probe radius is not used).
  VanDerWaals = 2,
};

/// The kinds of analytic patch, as the `patch` of a mesh vertex.
enum class SurfacePatch : std::uint8_t
{
  Convex = 0,   ///< on an atom's sphere (every vertex of the SAS and vdW surfaces)
  Toroidal = 1, ///< swept by the probe rolling on two atoms
  Concave = 2,  ///< on the probe where it touches three atoms
};

/// Parameters of molecular_surface().
struct MolecularSurfaceParams
{
  /// Which surface. Default SolventExcluded.
  SurfaceKind kind = SurfaceKind::SolventExcluded;
  /// Radius of the solvent probe, Å (length units of the input), (0, 20]; default 1.4 (water).
  /// Not used by the van der Waals surface.
  double probe_radius = 1.4;
  /// Largest distance between a triangle and the exact surface it stands for (chord error) on
  /// smooth patches, Å, [0.005, 1]; default 0.1. Edges are split until their middles lie
  /// within three quarters of it (the triangles' centres within it). Triangles spanning creases
  /// (the SAS and vdW seams, the SES's cusps and rims where probes meet) stay as the lattice
  /// made them, within its chord error: six times the tolerance, at most 0.56 Å, the SES's
  /// lattice points at most 0.9 probe radii from any point so that every cavity holds one (see
  /// grid_spacing).
  /// 0.1 suits interaction, 0.01-0.02 figures (the mesh areas each gives: docs/performance.md).
  double tolerance = 0.1;
  /// Keep the surfaces of cavities inside the molecule (closed components whose normals face
  /// inwards); false drops them from the mesh and from the area and volume. Default true.
  bool keep_cavities = true;
  /// Build the triangle mesh; false gives the exact area and volume alone. Default true.
  bool tessellate = true;
  /// Compute the exact area and volume. For the solvent-excluded surface they take the patch
  /// integrals (a quarter to a third of the time on large proteins); false skips them, for a
  /// mesh alone (e.g. when only the tolerance changes), and leaves `area`, `volume` and
  /// `patch_area` NaN, `patch_count` and `singular_patch_count` 0. The solvent-accessible and
  /// van der Waals figures cost nothing extra and are always computed. Default true.
  bool exact_figures = true;
};

/// Exact figures of a surface and, when tessellated, its mesh. Mesh vertices lie on the exact
/// surface (to 1e-5 Å); triangles are counter-clockwise seen from outside (the solvent).
struct MolecularSurface
{
  double area = 0;   ///< exact, from the patches (Å²)
  double volume = 0; ///< enclosed, exact from the patches (Å³); cavities count negatively
  /// Exact area per patch kind (convex, toroidal, concave), Å².
  std::array<double, 3> patch_area{};
  /// Number of patches: convex (atoms with exposed surface), toroidal, concave; and how many of
  /// the toroidal and concave ones are cut by the surface's singularities (a probe passing
  /// between two atoms beyond the torus's own cut at the axis, probes overlapping). Concave
  /// patches that only overlapping probes cut come exactly from the caps those leave; the others
  /// are integrated numerically (pieces split five levels deep), about 3e-5 of the area too
  /// high on proteins (1tii, 3wip, against pieces split seven levels deep).
  std::array<std::size_t, 3> patch_count{};
  std::size_t singular_patch_count = 0;
  /// Closed components of the mesh, and how many of them are cavities (dropped when
  /// keep_cavities is false).
  std::size_t component_count = 0;
  std::size_t cavity_count = 0;
  /// Points where four or more inflated atoms meet exactly (one probe touching four atoms, as
  /// in a perfect lattice): where not 0, the exact area and volume are unreliable (the mesh is
  /// not affected). Counted once per sphere through the point.
  std::size_t degenerate_vertex_count = 0;
  /// Spacing (cubes' side) of the body-centred cubic lattice the tessellation started from
  /// (before its edges were split), Å: every point lies within sqrt(5) / 4 of it from a lattice
  /// point.
  double grid_spacing = 0;

  std::vector<double> points;          ///< 3 per vertex, Å
  std::vector<double> normals;         ///< 3 per vertex, unit, pointing into the solvent
  std::vector<std::int64_t> triangles; ///< 3 vertex indices each
  std::vector<std::int32_t> atom;      ///< per vertex: the atom it belongs to (nearest)
  std::vector<SurfacePatch> patch;     ///< per vertex: the kind of patch it lies on
};

/// Called with the fraction done, in [0, 1], from the calling thread.
using SurfaceProgress = std::function<void(double)>;

/// The surface of `centres` (Å) with `radii` (Å, > 0; e.g. the van der Waals radii of their
/// elements). The solvent-excluded surface is built from the solvent-accessible boundary: its
/// exposed spheres, arcs where two meet and points where three meet are the probe's positions;
/// each patch's area and volume term comes in closed form, and singular patches are integrated
/// numerically where they are cut. The mesh is the zero set of the exact distance to those probe
/// positions minus the probe radius, contoured on a sparse grid by marching tetrahedra with
/// every vertex found on its own grid edge (watertight, 2-manifold and free of
/// self-intersections by construction), then refined: edges whose middles stray from the
/// surface are split at the middles' projections onto it, which keeps the mesh closed and
/// 2-manifold; splits that would fold a triangle, change one at a crease or pass through one,
/// are not made (the meshes of the test data's 15 PDB proteins were checked free of
/// self-intersections at 0.02, 0.05, 0.1 and 0.3 Å, 3l5q's at 0.3 Å). Exactly degenerate inputs
/// (four atoms touching one probe position, as in a perfect lattice) may give wrong exact figures;
/// the mesh stays right. Atoms, probes and cavities smaller than the tolerance are not resolved:
/// the mesh may leave them out (the exact figures keep them).
///
/// Throws InvalidInput for lists of different lengths, a non-finite centre or radius, a centre
/// coordinate beyond largest_sphere_coordinate (1e8 Å), a radius <= 0 or > 20 Å, an option out of
/// range, a tolerance that would need more than 2e7 triangles, or atoms spread so far apart
/// (thousands of Å along each axis) that the search grid would need more than about 12 GB;
/// SolverFailure ("contour is inconsistent") should the surface's field contradict itself (a
/// defect: please report the input). No atoms give an empty surface. Deterministic whatever
/// `parallel_for`.
MolecularSurface molecular_surface(PointSpan<const double> centres,
                                   const std::vector<double>& radii,
                                   const MolecularSurfaceParams& options = {},
                                   const ParallelFor& parallel_for = {},
                                   const SurfaceProgress& progress = {});

} // namespace mesolens
