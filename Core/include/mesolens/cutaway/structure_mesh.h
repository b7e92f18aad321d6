// SPDX-License-Identifier: GPL-3.0-or-later
// A structure's triangle mesh made from the centres of its molecules (the cutaway's wireframe,
// SirTom thesis): one sheet through the middle of a membrane, its triangles near-equilateral.
#pragma once

#include "mesolens/common/parallel_for.h"
#include "mesolens/common/point_span.h"
#include "mesolens/molecules/periodic_box.h"
#include "mesolens/mesh/triangle_mesh.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace mesolens {

/// How even a mesh's triangles are, and its shape.
struct MeshQuality
{
  double min_angle = 0;   ///< degrees, over all triangles
  double max_angle = 0;   ///< degrees
  double mean_edge = 0;   ///< mesh units
  double edge_spread = 0; ///< standard deviation of the edge lengths over their mean
  std::size_t boundary_edges = 0;
  std::size_t boundary_loops = 0; ///< 0 for a closed mesh (needs a manifold mesh)
  std::size_t components = 0;     ///< connected components of the triangles
};

/// The quality of a triangle mesh.
MeshQuality mesh_quality(const TriangleMesh& mesh);

/// Every triangle of a structure mesh has its angles within this range (degrees). A smallest
/// angle of at least 30° alone bounds the largest by 180 - 2 x 30 = 120°.
constexpr double structure_mesh_min_angle = 30.0;
constexpr double structure_mesh_max_angle = 120.0;

/// Settings of structure_mesh().
struct StructureMeshParams
{
  /// About how many vertices the mesh has, [4, vertex_limit]; default 500 (used when
  /// edge_length <= 0; expect within about 15 %, and for a handful of vertices the nearest
  /// count the shape allows).
  std::size_t vertices = 500;
  /// The target edge length in mesh units; <= 0 (default): from `vertices`. An edge that
  /// would give more than vertex_limit vertices over the sheet is refused.
  double edge_length = 0;
  /// How far along the local normal the other leaflet of a bilayer is looked for, in mesh
  /// units: more than the distance between the two leaflets' points (lipid centres about 20 Å
  /// apart, head groups about 40 Å). <= 0 (default): up to 8 median spacings of the points.
  double mid_surface_radius = 0;
  /// The periodic box of the points (Å); not set (default): none. A flat membrane that spans
  /// two of its vectors is meshed over that cell.
  PeriodicBox box;
  /// The most vertices a structure mesh may be asked for, by `vertices` or by `edge_length`;
  /// default 1e6 (the remeshing needs about 1 kB per vertex and minutes per million). Raise it
  /// for finer meshes of larger sheets.
  std::size_t vertex_limit = 1000000;
};

/// A sheet through the middle of `points` (the centres of a membrane's
/// lipids, both leaflets, or their head groups alone; no water or ions, see
/// structure_molecules()).
///
/// 1. The middle sheet: at Poisson-disk samples of the points, the local normal by PCA and the
///    points along it split in two height groups; when most samples see two groups far apart
///    for their spread, the cloud is a bilayer and each sample gives the point halfway between
///    its two leaflets (samples that see only their own leaflet, and strays far from the rest,
///    give none). Otherwise the points are one sheet and are moved onto their local planes.
/// 2. The mesh: when `params.box` is set and the points spread over two of its vectors (a flat
///    periodic patch), a lattice of near-equilateral triangles over that cell, lifted to the
///    middle sheet: an open sheet spanning the patch (one boundary loop). Otherwise CGAL's
///    advancing-front reconstruction through the middle points, its largest component kept and
///    holes with fewer than max(20, 5 % of the vertices) edges closed (a vesicle closes; a
///    patch keeps its border), then CGAL's isotropic remeshing to the target edge (corrected
///    once towards the asked vertex count) and angle smoothing.
/// 3. A last pass of edge flips, vertex moves and short-edge collapses (each kept only if it
///    raises the smallest angle around it) until every triangle's angles lie within
///    structure_mesh_min_angle and structure_mesh_max_angle.
///
/// The mesh is one connected 2-manifold; a closed one is oriented outwards, a lattice towards
/// a x b. Deterministic whatever `parallel_for`. Throws InvalidInput for fewer than 4 points,
/// non-finite points, N outside [4, vertex_limit] (when edge_length <= 0), a negative or
/// non-finite length, an edge length that would give more than vertex_limit vertices, or
/// points that all coincide; TopologyError when the points describe no surface (all
/// on a line, for instance) or when the angle bound cannot be met everywhere (the message says
/// where).
TriangleMesh structure_mesh(PointSpan<const double> points, const StructureMeshParams& params,
                            MeshQuality* quality = nullptr, const ParallelFor& parallel_for = {});

/// True for the residue names of water and of monatomic ions in common force fields and in the
/// PDB, compared without case: waters SOL, WAT, HOH, H2O, DOD, TIP3, TIP4, TIP5, T3P, T4P, T4E,
/// SPC, SPCE, OPC, OPC3, and the coarse-grained W, WF, PW, BMW, TW, SW; ions such as NA, CL, K,
/// CA, MG, ZN, LI, RB, CS, BA, SR, F, BR, I, with or without a charge sign (NA+, CL-, Na+,
/// CA2+), CHARMM's SOD, POT, CLA, CAL, CES, LIT, RUB, BAR, ZN2, CD2, Martini's ION and
/// NA+/CL-, and PDB ions (MN, FE, FE2, CU, CU1, CO, NI, CD, HG, IOD).
bool is_solvent_residue(const std::string& residue_name);

/// Which molecules a structure mesh is made from, 1 per molecule that counts: not water or ions
/// (is_solvent_residue() of their type's name), not proteins or nucleic acids (their type's
/// name an amino acid or nucleotide, see molecule_assignment.h) unless fewer than 4 molecules
/// would be left, and not molecules of fewer than 4 atoms (waters and ions of any other name)
/// when the largest molecule has 4 or more (a head-group-only cloud, one bead per lipid, keeps
/// them all). Stray molecules far from the membrane are left to structure_mesh(). `types` (per
/// molecule, an index into `type_names`; empty: no names) and `atom_counts` (per molecule)
/// have the molecule count as size when not empty.
std::vector<std::uint8_t> structure_molecules(const std::vector<int>& types,
                                              const std::vector<std::string>& type_names,
                                              const std::vector<std::size_t>& atom_counts);

} // namespace mesolens
