// SPDX-License-Identifier: GPL-3.0-or-later
// Protein and nucleic-acid ribbons (the cartoon model of BioBrowser, Halm, Offen & Fellner 2005):
// a cubic spline interpolating the Cα (or P) atoms of every continuous piece of chain, oriented
// by the peptide planes, swept with a cross-section that depends on the secondary structure:
// wide flat ribbons for helices (or straight cylinders), flat ribbons ending in arrowheads for
// strands, round tubes for coil and for nucleic-acid backbones. The result is a closed triangle
// mesh per piece with per-vertex normals and the residue each vertex belongs to.
#pragma once

#include "mesolens/common/parallel_for.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace mesolens {

/// How a residue is drawn.
enum class RibbonStyle : std::uint8_t
{
  Helix,      ///< wide flat ribbon, or part of a cylinder (RibbonParams::helix_as_cylinder)
  Strand,     ///< flat ribbon; the last residue of a strand carries the arrowhead
  Coil,       ///< thin round tube (also turns, bends, isolated bridges)
  NucleicAcid ///< thicker round tube through the phosphorus atoms
};

/// The style of a residue from its DSSP code: 'H' (α), 'G' (3-10) and 'I' (π) are Helix; 'E'
/// (strand) and 'B' (bridge) are Strand; everything else ('T', 'S', 'P' polyproline as mkdssp 4
/// and mesolens/dssp.h write it, ' ', '-', ...) is Coil. A nucleotide is NucleicAcid whatever
/// its code. ('P' is not taken to mean a nucleotide because DSSP uses it for polyproline.)
RibbonStyle ribbon_style(char secondary_structure, bool nucleotide = false);

/// One residue of the input, given in chain order. A residue without a trace atom (a nucleic
/// acid without P, a residue without Cα) is simply left out by the caller; the gap it leaves
/// breaks the ribbon there when it exceeds the break distance.
struct RibbonResidue
{
  /// The Cα atom of an amino acid or the P atom of a nucleotide, Å. Must be finite.
  std::array<double, 3> trace{};
  /// The residue's carbonyl O, Å: it orients the ribbon in the peptide plane. Absent for
  /// Cα-only models and nucleic acids: the orientation then comes from the curve. Finite when
  /// present.
  std::optional<std::array<double, 3>> carbonyl_oxygen;
  /// DSSP code (see ribbon_style()), carried to every vertex of the residue.
  char secondary_structure = ' ';
  /// A nucleotide traced through its P atom (drawn as the nucleic-acid tube, broken from
  /// amino acids) rather than an amino acid traced through its Cα.
  bool nucleotide = false;
  /// Chain the residue belongs to; the ribbon never connects residues of different chains.
  std::int64_t chain = 0;
  /// Opaque number carried to every vertex of the residue (e.g. the row of its Cα in the atom
  /// table), so a picked vertex leads back to the residue.
  std::int64_t id = 0;
};

/// The range of every length of RibbonParams, Å: shorter ones leave the sections' normals no
/// digits, longer ones are no ribbon.
constexpr double shortest_ribbon_length = 1e-3;
constexpr double longest_ribbon_length = 1e3;
/// The most samples per residue and vertices around a section RibbonParams takes (memory grows
/// as their product).
constexpr int largest_ribbon_subdivisions = 100;
constexpr int largest_ribbon_tube_sides = 360;
/// The largest magnitude of a trace or carbonyl O coordinate ribbon_mesh() takes, Å (farther
/// out the spline's arithmetic overflows).
constexpr double largest_ribbon_coordinate = 1e8;

/// Shape and level of detail of ribbon_mesh(). Lengths in Å, each in [shortest_ribbon_length,
/// longest_ribbon_length].
struct RibbonParams
{
  /// Spline samples per residue (level of detail), [1, 100]: 2 is coarse, 12 fine; default 6.
  /// The triangle count grows linearly with it.
  int subdivisions = 6;
  /// Per segment (in the order ribbon_segments() lists them), a subdivision count >= 1 that
  /// replaces `subdivisions`, e.g. chosen from each segment's size on screen. Empty: all
  /// segments use `subdivisions`; otherwise it must have one entry per segment.
  std::vector<int> segment_subdivisions;
  /// Vertices around every cross-section, [3, 360]. Default 8.
  int tube_sides = 8;
  /// Draw each helix of 4 or more residues as one straight capped cylinder along its axis
  /// instead of a wide ribbon (shorter helices are then drawn as coil). Default false.
  bool helix_as_cylinder = false;
  /// Full width of a helix ribbon, > 0. Default 2.4.
  double helix_width = 2.4;
  /// Full width of a strand ribbon, > 0. Default 2.0.
  double strand_width = 2.0;
  /// Width of an arrowhead's base as a multiple of strand_width, [1, 100]. Default 1.5.
  double arrow_width_factor = 1.5;
  /// Thickness of helix and strand ribbons, > 0. Default 0.5.
  double ribbon_thickness = 0.5;
  /// Radius of the coil tube, > 0; an arrowhead tapers to it. Default 0.35.
  double coil_radius = 0.35;
  /// Radius of the nucleic-acid backbone tube, > 0. Default 0.8.
  double nucleic_radius = 0.8;
  /// Radius of helix cylinders, > 0. Default 2.3 (the Cα radius of an α-helix).
  double cylinder_radius = 2.3;
  /// Consecutive amino acids whose Cα are farther apart than this are not bonded: the ribbon
  /// breaks there. > 0; default 4.2 (a trans peptide is 3.8).
  double protein_break_distance = 4.2;
  /// The same for consecutive nucleotides' P atoms (5.5-7.5 apart when bonded). > 0; default
  /// 8.0.
  double nucleic_break_distance = 8.0;
};

/// A continuous piece of chain: residues [first_residue, first_residue + residue_count) of the
/// input, all of one chain and one kind (amino acids or nucleotides), each within the break
/// distance of the next.
struct RibbonSegment
{
  std::size_t first_residue = 0;
  std::size_t residue_count = 0;
};

/// One sample of the centre line: a point of the spline with its frame and cross-section.
struct RibbonSample
{
  std::size_t segment = 0; ///< index into RibbonMesh::segments
  /// Position along the chain in residues of the input: residue index + fraction (12.5 lies
  /// halfway between residues 12 and 13). At whole numbers the sample is the residue's atom.
  double parameter = 0;
  std::size_t residue = 0;             ///< the input residue nearest along the curve
  std::array<double, 3> position{};    ///< on the spline, Å
  std::array<double, 3> tangent{};     ///< unit, towards the next residue
  std::array<double, 3> side{};        ///< unit, perpendicular to the tangent: the width direction
  std::array<double, 3> normal{};      ///< unit, tangent × side: the thickness direction
  double half_width = 0;               ///< cross-section semi-axis along `side`, Å
  double half_thickness = 0;           ///< cross-section semi-axis along `normal`, Å
  std::int64_t first_ring_vertex = -1; ///< first of the tube_sides vertices of its cross-section
                                       ///< in the mesh; -1 when not meshed (inside a cylinder)
};

/// A closed, connected part of the mesh: the tube or ribbon of a segment (or of the part of a
/// segment between two helix cylinders), or a helix cylinder.
struct RibbonPiece
{
  enum class Kind : std::uint8_t
  {
    Tube,    ///< swept along the spline, round end caps
    Cylinder ///< a straight helix cylinder
  };
  Kind kind = Kind::Tube;
  std::size_t segment = 0;        ///< index into RibbonMesh::segments
  std::size_t first_vertex = 0;   ///< its vertices are [first_vertex, + vertex_count)
  std::size_t vertex_count = 0;   ///< tube_sides per ring (caps' rings included) + 2 poles
  std::size_t first_triangle = 0; ///< its triangles are [first_triangle, + triangle_count)
  std::size_t triangle_count = 0; ///< 2 × tube_sides per ring; they use only its own vertices
};

/// The ribbon geometry: a triangle mesh whose every piece is a closed, consistently oriented
/// 2-manifold of genus 0, plus the centre line it was swept along.
struct RibbonMesh
{
  std::vector<double> points;          ///< 3 per vertex, Å
  std::vector<double> normals;         ///< 3 per vertex, unit, pointing out of the surface
  std::vector<std::int64_t> triangles; ///< 3 vertex indices each, counter-clockwise from outside
  std::vector<std::int64_t> vertex_residue_id;  ///< per vertex, RibbonResidue::id of its residue
  std::vector<char> vertex_secondary_structure; ///< per vertex, its residue's DSSP code
  std::vector<RibbonSegment> segments;          ///< as ribbon_segments() returns them
  std::vector<RibbonPiece> pieces;              ///< by segment, then along the chain
  std::vector<RibbonSample> centre_line;        ///< by segment, then along the chain

  std::size_t vertex_count() const
  {
    return this->points.size() / 3;
  }
  std::size_t triangle_count() const
  {
    return this->triangles.size() / 3;
  }
};

/// The continuous segments of `residues`: a new segment starts where the chain changes, where
/// amino acids change to nucleotides or back, and where consecutive trace atoms are farther
/// apart than the break distance. Throws InvalidInput for a non-finite trace
/// position or a non-positive break distance.
std::vector<RibbonSegment> ribbon_segments(const std::vector<RibbonResidue>& residues,
                                           const RibbonParams& settings = {});

/// Sweeps the ribbon of every segment.
///
/// Centre line: the natural cubic spline (C2; the same curve as an interpolating cubic B-spline
/// with natural ends) through the segment's trace atoms, uniform in the residue number, sampled
/// `subdivisions` times per residue plus once at each arrowhead's shoulder.
///
/// Orientation: at each residue the side direction is the residue's carbonyl O minus its trace
/// atom, made perpendicular to the tangent; without an O it is tangent × (previous + next − 2 ×
/// this atom), the curve's binormal, which lies along a helix's axis and in a strand's sheet as
/// the peptide planes do; where the chain is straight it is carried over from the neighbours. A
/// side direction opposite to the previous residue's is negated, so strands do not twist, and
/// the sides are splined like the positions.
///
/// Cross-sections are ellipses (a flat one is a ribbon): helix helix_width × ribbon_thickness,
/// strand strand_width × ribbon_thickness, coil and nucleic acid round; one family, so that
/// every ring has the same vertices and a change of style is a change of two semi-axes.
/// Between residues of two styles the section changes smoothly (a smoothstep) over the one
/// residue interval between them. A strand of two or more residues ends in an arrowhead over
/// its last residue interval: the width widens to arrow_width_factor × strand_width over a
/// tenth of the interval (half a sample step above 5 subdivisions), then tapers linearly to the
/// coil radius at the last Cα. A strand of one residue (an isolated bridge) is drawn as coil.
/// Every piece is closed by half-ellipsoid caps as deep as its end section is thin (a
/// hemisphere on a tube); a segment of one residue is a sphere of the coil (or nucleic) radius
/// whatever its code. Normals are the analytic normals of the swept ellipse, tapering included
/// (the frame's own turning is neglected).
///
/// With helix_as_cylinder, a helix of 4 or more residues is one straight cylinder of
/// cylinder_radius with shallow rounded caps (a fifth of the radius deep), along the
/// least-squares line through local axis points (the centres of the circles through three
/// consecutive Cα seen along the axis: exact for an ideal helix, where a line fit of the Cα of a
/// short helix tilts), spanning the projections of its first and last Cα; the tube of the rest
/// of the segment stops at those two Cα.
///
/// Where the curve bends across the section's width more tightly than the half-width, the sweep
/// overlaps itself there, as every swept ribbon does (the spline's radius of curvature at a
/// lone 90° Cα angle between straight stretches is about 0.8 Å: below a helix ribbon's
/// half-width, above the coil radius; the coil tube overlaps below about 65°). The mesh stays
/// closed and consistently oriented.
///
/// Empty input gives an empty mesh (no exception; the settings are still checked). Throws
/// InvalidInput, naming the residue (index, id and chain), for a non-finite trace or O
/// position or one beyond largest_ribbon_coordinate, and for settings out of range or a
/// segment_subdivisions list whose length is not the number of segments. Deterministic whatever
/// `parallel_for` (which runs the segments, then the pieces); time and memory O(residues ×
/// subdivisions × tube_sides).
RibbonMesh ribbon_mesh(const std::vector<RibbonResidue>& residues,
                       const RibbonParams& settings = {}, const ParallelFor& parallel_for = {});

/// ribbon_mesh() into `mesh`, whose arrays' memory is reused (cleared, not freed): a filter that
/// redraws the ribbons of every frame keeps its pages instead of faulting fresh ones in, which
/// is most of the time of a large mesh. Throws as ribbon_mesh() does (`mesh` then holds
/// nothing valid).
void ribbon_mesh(const std::vector<RibbonResidue>& residues, const RibbonParams& settings,
                 const ParallelFor& parallel_for, RibbonMesh& mesh);

} // namespace mesolens
