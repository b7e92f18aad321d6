// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/common/errors.h"
#include "mesolens/mesh/mesh_report.h"
#include "mesolens/protein/ribbon_geometry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <set>
#include <vector>

namespace {
using mesolens::RibbonMesh;
using mesolens::RibbonParams;
using mesolens::RibbonPiece;
using mesolens::RibbonResidue;
using Point = std::array<double, 3>;
using Chain = std::vector<RibbonResidue>;

constexpr double pi = 3.14159265358979323846;

Point add(const Point& a, const Point& b)
{
  return { a[0] + b[0], a[1] + b[1], a[2] + b[2] };
}
Point sub(const Point& a, const Point& b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}
Point scale(const Point& a, double s)
{
  return { s * a[0], s * a[1], s * a[2] };
}
double dot(const Point& a, const Point& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
double norm(const Point& a)
{
  return std::sqrt(dot(a, a));
}
Point cross(const Point& a, const Point& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}
Point vertex(const RibbonMesh& mesh, std::size_t v)
{
  return { mesh.points[3 * v], mesh.points[3 * v + 1], mesh.points[3 * v + 2] };
}
Point vertex_normal(const RibbonMesh& mesh, std::size_t v)
{
  return { mesh.normals[3 * v], mesh.normals[3 * v + 1], mesh.normals[3 * v + 2] };
}

/// An ideal α-helix along +z: Cα on radius 2.3 Å, 100° and 1.5 Å per residue; each carbonyl O
/// points along the axis (towards the C terminus) and a little inwards, as in real helices.
Chain ideal_helix(int count)
{
  Chain chain;
  for (int i = 0; i < count; ++i)
  {
    const double angle = i * 100.0 * pi / 180.0;
    const Point radial{ std::cos(angle), std::sin(angle), 0 };
    RibbonResidue residue;
    residue.trace = { 2.3 * radial[0], 2.3 * radial[1], 1.5 * i };
    residue.carbonyl_oxygen = add(residue.trace, add(Point{ 0, 0, 1.4 }, scale(radial, -0.4)));
    residue.secondary_structure = 'H';
    chain.push_back(residue);
  }
  return chain;
}

/// An ideal β-strand along +x: 3.3 Å per residue, Cα pleated ±0.94 Å in z (3.8 Å apart), each
/// carbonyl O in the sheet plane (±y), alternately to either side.
Chain ideal_strand(int count)
{
  Chain chain;
  for (int i = 0; i < count; ++i)
  {
    const double alternate = i % 2 == 0 ? 1.0 : -1.0;
    RibbonResidue residue;
    residue.trace = { 3.3 * i, 0, 0.94 * alternate };
    residue.carbonyl_oxygen = add(residue.trace, Point{ 1.2, 1.6 * alternate, 0 });
    residue.secondary_structure = 'E';
    chain.push_back(residue);
  }
  return chain;
}

/// A loop of Cα only, 3.8 Å apart, winding to the side.
Chain loop(int count, char code = '-')
{
  Chain chain;
  Point at{ 0, 0, 0 };
  for (int i = 0; i < count; ++i)
  {
    RibbonResidue residue;
    residue.trace = at;
    residue.secondary_structure = code;
    chain.push_back(residue);
    const Point step{ std::cos(0.7 * i), std::sin(0.7 * i), 0.4 };
    at = add(at, scale(step, 3.8 / norm(step)));
  }
  return chain;
}

/// Appends `piece` to `chain`, moved (not turned) so its first atom lies 3.8 Å from the chain's
/// last one, along the bisector of the chain's last step and the piece's first: both joints then
/// turn by less than 90°, as real chains do.
void append(Chain& chain, Chain piece)
{
  const Point last_step = sub(chain.back().trace, chain[chain.size() - 2].trace);
  const Point first_step = sub(piece[1].trace, piece[0].trace);
  Point join = add(scale(last_step, 1 / norm(last_step)), scale(first_step, 1 / norm(first_step)));
  if (norm(join) < 1e-3)
  {
    join = cross(last_step, Point{ 0.3, 0.5, 0.8 });
  }
  const Point target = add(chain.back().trace, scale(join, 3.8 / norm(join)));
  const Point shift = sub(target, piece.front().trace);
  for (RibbonResidue& residue : piece)
  {
    residue.trace = add(residue.trace, shift);
    if (residue.carbonyl_oxygen)
    {
      residue.carbonyl_oxygen = add(*residue.carbonyl_oxygen, shift);
    }
    chain.push_back(residue);
  }
}

/// Gives residues their index as id (plus `base`), so vertices can be traced back.
Chain numbered(Chain chain, std::int64_t base = 1000)
{
  for (std::size_t i = 0; i < chain.size(); ++i)
  {
    chain[i].id = base + static_cast<std::int64_t>(i);
  }
  return chain;
}

/// Helix (12) - loop (4) - strand (6) - loop (3), one chain.
Chain mixed_chain()
{
  Chain chain = ideal_helix(12);
  append(chain, loop(4));
  append(chain, ideal_strand(6));
  append(chain, loop(3));
  return numbered(chain);
}

/// Every piece is a closed, consistently oriented 2-manifold of genus 0 enclosing a positive
/// volume (so its triangles turn counter-clockwise seen from outside), and, unless the
/// tessellation is too coarse for it (a helix ribbon of 3 sides and 1 sample per residue), the
/// triangles' own normals agree with their vertices' normals.
void expect_closed_pieces(const RibbonMesh& mesh, bool check_face_normals = true)
{
  ASSERT_EQ(mesh.normals.size(), mesh.points.size());
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
  {
    ASSERT_NEAR(norm(vertex_normal(mesh, v)), 1.0, 1e-12) << "vertex " << v;
  }
  for (const RibbonPiece& piece : mesh.pieces)
  {
    std::vector<double> points(mesh.points.begin() + 3 * piece.first_vertex,
                               mesh.points.begin() + 3 * (piece.first_vertex + piece.vertex_count));
    std::vector<std::int64_t> triangles;
    double volume = 0;
    for (std::size_t t = piece.first_triangle; t < piece.first_triangle + piece.triangle_count; ++t)
    {
      Point corner[3];
      Point normal_sum{ 0, 0, 0 };
      for (int c = 0; c < 3; ++c)
      {
        const std::int64_t v = mesh.triangles[3 * t + c];
        ASSERT_GE(v, static_cast<std::int64_t>(piece.first_vertex));
        ASSERT_LT(v, static_cast<std::int64_t>(piece.first_vertex + piece.vertex_count));
        triangles.push_back(v - static_cast<std::int64_t>(piece.first_vertex));
        corner[c] = vertex(mesh, static_cast<std::size_t>(v));
        normal_sum = add(normal_sum, vertex_normal(mesh, static_cast<std::size_t>(v)));
      }
      const Point face = cross(sub(corner[1], corner[0]), sub(corner[2], corner[0]));
      if (check_face_normals)
      {
        EXPECT_GT(dot(face, normal_sum), 0) << "triangle " << t;
      }
      volume += dot(corner[0], cross(corner[1], corner[2])) / 6.0;
    }
    const mesolens::MeshReport report = mesolens::mesh_report(
      { { points.data(), piece.vertex_count }, triangles.data(), piece.triangle_count });
    EXPECT_TRUE(report.is_closed_manifold()) << report.describe_defects();
    EXPECT_EQ(report.components, 1u);
    EXPECT_EQ(report.euler_characteristic, 2);
    EXPECT_EQ(report.boundary_edges, 0u);
    EXPECT_EQ(report.unreferenced_vertices, 0u);
    EXPECT_GT(volume, 0);
  }
  const mesolens::MeshReport whole = mesolens::mesh_report(
    { { mesh.points.data(), mesh.vertex_count() }, mesh.triangles.data(), mesh.triangle_count() });
  EXPECT_EQ(whole.components, mesh.pieces.size());
}

/// The centre-line sample at `parameter` (residue index + fraction).
const mesolens::RibbonSample& sample_at(const RibbonMesh& mesh, double parameter)
{
  for (const auto& sample : mesh.centre_line)
  {
    if (std::abs(sample.parameter - parameter) < 1e-9)
    {
      return sample;
    }
  }
  throw std::runtime_error("no sample at " + std::to_string(parameter));
}

/// The largest distance of a sample's ring vertices from the sample.
double ring_extent(const RibbonMesh& mesh, const mesolens::RibbonSample& sample, int sides)
{
  double extent = 0;
  for (int j = 0; j < sides; ++j)
  {
    extent =
      std::max(extent, norm(sub(vertex(mesh, sample.first_ring_vertex + j), sample.position)));
  }
  return extent;
}
} // namespace

TEST(RibbonGeometry, StylesOfDsspCodes)
{
  using mesolens::RibbonStyle;
  for (char code : { 'H', 'G', 'I' })
    EXPECT_EQ(mesolens::ribbon_style(code), RibbonStyle::Helix);
  for (char code : { 'E', 'B' })
    EXPECT_EQ(mesolens::ribbon_style(code), RibbonStyle::Strand);
  for (char code : { 'T', 'S', ' ', '-', 'P', 'C' })
    EXPECT_EQ(mesolens::ribbon_style(code), RibbonStyle::Coil);
  EXPECT_EQ(mesolens::ribbon_style(' ', true), RibbonStyle::NucleicAcid);
}

TEST(RibbonGeometry, CentreLineInterpolatesEveryTraceAtom)
{
  const Chain chain = mixed_chain();
  RibbonParams settings;
  settings.subdivisions = 5;
  const RibbonMesh mesh = mesolens::ribbon_mesh(chain, settings);
  ASSERT_EQ(mesh.segments.size(), 1u);
  for (std::size_t i = 0; i < chain.size(); ++i)
  {
    const auto& sample = sample_at(mesh, static_cast<double>(i));
    EXPECT_LT(norm(sub(sample.position, chain[i].trace)), 1e-6) << "residue " << i;
    EXPECT_EQ(sample.residue, i);
  }
  // A smooth curve, not a polygon: halfway between two helix Cα the spline stays near the
  // 2.3 Å cylinder (the chord's middle is at 1.48 Å).
  for (int i = 2; i < 9; ++i)
  {
    const Point middle = sample_at(mesh, i + 0.4).position;
    EXPECT_NEAR(std::hypot(middle[0], middle[1]), 2.3, 0.15) << "residue " << i;
  }
}

TEST(RibbonGeometry, CentreLineIsSmoothThroughTheAtoms)
{
  // Across a Cα the second difference p(i + h) - 2 p(i) + p(i - h) of a C1 curve shrinks like
  // h², so halving h divides it by 4; at the corner of a polygon it only halves.
  const Chain chain = mixed_chain();
  RibbonParams coarse, fine;
  coarse.subdivisions = 10;
  fine.subdivisions = 20;
  const RibbonMesh a = mesolens::ribbon_mesh(chain, coarse);
  const RibbonMesh b = mesolens::ribbon_mesh(chain, fine);
  const auto second_difference = [](const RibbonMesh& mesh, double i, double h) {
    const Point before = sample_at(mesh, i - h).position;
    const Point after = sample_at(mesh, i + h).position;
    return norm(
      add(sub(before, sample_at(mesh, i).position), sub(after, sample_at(mesh, i).position)));
  };
  for (std::size_t i = 1; i + 1 < chain.size(); ++i)
  {
    // Samples at i - 0.1 lie in the interval before i: (i - 1) + 9 / 10.
    const double wide = second_difference(a, static_cast<double>(i), 0.1);
    const double narrow = second_difference(b, static_cast<double>(i), 0.05);
    EXPECT_GT(wide / narrow, 3.5) << "residue " << i;
  }
}

TEST(RibbonGeometry, StraightChainGivesAStraightCentreLine)
{
  // The natural spline reproduces a straight, evenly spaced chain exactly.
  Chain chain;
  for (int i = 0; i < 6; ++i)
  {
    RibbonResidue residue;
    residue.trace = { 3.8 * i, 1, 2 };
    chain.push_back(residue);
  }
  const RibbonMesh mesh = mesolens::ribbon_mesh(chain);
  for (const auto& sample : mesh.centre_line)
  {
    EXPECT_NEAR(sample.position[0], 3.8 * sample.parameter, 1e-9);
    EXPECT_NEAR(sample.position[1], 1.0, 1e-12);
    EXPECT_NEAR(sample.position[2], 2.0, 1e-12);
  }
}

TEST(RibbonGeometry, ChainBreaksAtGapsAndChainChanges)
{
  // Two runs of 8 residues 7 Å apart (over the 4.2 Å break distance) along x.
  Chain gapped = loop(1);
  for (int i = 1; i < 16; ++i)
  {
    RibbonResidue residue;
    residue.trace = { 3.8 * i + (i >= 8 ? 3.2 : 0.0), 0.3 * (i % 2), 0 };
    gapped.push_back(residue);
  }
  gapped = numbered(gapped, 0);
  const RibbonMesh mesh = mesolens::ribbon_mesh(gapped);
  ASSERT_EQ(mesh.segments.size(), 2u);
  EXPECT_EQ(mesh.segments[1].first_residue, 8u);
  ASSERT_EQ(mesh.pieces.size(), 2u);
  expect_closed_pieces(mesh);
  const double gap_start = 3.8 * 7 + 0.35 + 1e-6, gap_end = 3.8 * 8 + 3.2 - 0.35 - 1e-6;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
  {
    std::set<bool> side;
    for (int c = 0; c < 3; ++c)
    {
      side.insert(mesh.vertex_residue_id[mesh.triangles[3 * t + c]] >= 8);
    }
    EXPECT_EQ(side.size(), 1u) << "triangle " << t << " spans the gap";
  }
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
  {
    const double x = mesh.points[3 * v];
    EXPECT_FALSE(x > gap_start && x < gap_end) << "vertex " << v << " in the gap at x = " << x;
  }

  // Two chains whose ends are 3.8 Å apart are still not joined.
  Chain two = ideal_helix(6);
  append(two, ideal_strand(5));
  two = numbered(two, 0);
  for (std::size_t i = 6; i < two.size(); ++i)
  {
    two[i].chain = 7;
  }
  const RibbonMesh chains = mesolens::ribbon_mesh(two);
  ASSERT_EQ(chains.segments.size(), 2u);
  EXPECT_EQ(chains.segments[0].residue_count, 6u);
  expect_closed_pieces(chains);
  for (std::size_t t = 0; t < chains.triangle_count(); ++t)
  {
    std::set<bool> chain;
    for (int c = 0; c < 3; ++c)
    {
      chain.insert(chains.vertex_residue_id[chains.triangles[3 * t + c]] >= 6);
    }
    EXPECT_EQ(chain.size(), 1u) << "triangle " << t << " joins the chains";
  }
}

TEST(RibbonGeometry, StrandFrameFollowsThePeptidePlanesWithoutFlipping)
{
  const Chain strand = ideal_strand(9);
  // The carbonyls alternate, so a frame taken from them as they are would flip every residue.
  EXPECT_LT(dot(sub(*strand[3].carbonyl_oxygen, strand[3].trace),
                sub(*strand[4].carbonyl_oxygen, strand[4].trace)),
            0);
  RibbonParams settings;
  settings.subdivisions = 7;
  const RibbonMesh mesh = mesolens::ribbon_mesh(strand, settings);
  ASSERT_GT(mesh.centre_line.size(), 50u);
  for (std::size_t k = 1; k < mesh.centre_line.size(); ++k)
  {
    const auto& a = mesh.centre_line[k - 1];
    const auto& b = mesh.centre_line[k];
    EXPECT_GT(dot(a.normal, b.normal), 0.9) << "sample " << k;
    EXPECT_GT(dot(a.side, b.side), 0.9) << "sample " << k;
  }
  for (const auto& sample : mesh.centre_line)
  {
    // The ribbon lies in the sheet: its width along the carbonyls (y), thickness across (z).
    EXPECT_GT(std::abs(sample.side[1]), 0.85) << "at " << sample.parameter;
    EXPECT_NEAR(dot(sample.side, sample.tangent), 0.0, 1e-12);
    EXPECT_NEAR(norm(sample.normal), 1.0, 1e-12);
  }
  // Without carbonyls the frame comes from the pleat, and it lies in the sheet as well.
  Chain trace_only = strand;
  for (RibbonResidue& residue : trace_only)
  {
    residue.carbonyl_oxygen.reset();
  }
  const RibbonMesh from_curve = mesolens::ribbon_mesh(trace_only, settings);
  for (std::size_t k = 1; k < from_curve.centre_line.size(); ++k)
  {
    EXPECT_GT(dot(from_curve.centre_line[k - 1].side, from_curve.centre_line[k].side), 0.9);
    EXPECT_GT(std::abs(from_curve.centre_line[k].side[1]), 0.85);
  }
}

TEST(RibbonGeometry, HelixRibbonIsWideAlongTheAxis)
{
  for (bool with_oxygens : { true, false })
  {
    Chain helix = ideal_helix(14);
    if (!with_oxygens)
    {
      for (RibbonResidue& residue : helix)
        residue.carbonyl_oxygen.reset();
    }
    const RibbonMesh mesh = mesolens::ribbon_mesh(helix);
    for (int i = 1; i < 13; ++i)
    {
      const auto& sample = sample_at(mesh, i);
      const Point radial{ sample.position[0] / 2.3, sample.position[1] / 2.3, 0 };
      EXPECT_GT(std::abs(sample.side[2]), 0.8) << "residue " << i << " oxygens " << with_oxygens;
      EXPECT_GT(std::abs(dot(sample.normal, radial)), 0.8) << "residue " << i;
      EXPECT_DOUBLE_EQ(sample.half_width, 1.2);
      EXPECT_DOUBLE_EQ(sample.half_thickness, 0.25);
    }
    for (std::size_t k = 1; k < mesh.centre_line.size(); ++k)
    {
      EXPECT_GT(dot(mesh.centre_line[k - 1].side, mesh.centre_line[k].side), 0.8);
    }
    expect_closed_pieces(mesh);
  }
}

TEST(RibbonGeometry, EveryPieceIsClosed)
{
  const Chain chain = mixed_chain();
  for (bool cylinders : { false, true })
  {
    for (int sides : { 3, 4, 8, 13 })
    {
      for (int subdivisions : { 1, 2, 6, 12 })
      {
        RibbonParams settings;
        settings.helix_as_cylinder = cylinders;
        settings.tube_sides = sides;
        settings.subdivisions = subdivisions;
        SCOPED_TRACE(testing::Message() << "cylinders " << cylinders << " sides " << sides
                                        << " subdivisions " << subdivisions);
        const RibbonMesh mesh = mesolens::ribbon_mesh(chain, settings);
        EXPECT_EQ(mesh.pieces.size(), cylinders ? 2u : 1u);
        expect_closed_pieces(mesh, sides >= 6 && subdivisions >= 2);
      }
    }
  }
}

TEST(RibbonGeometry, CoilTubeNormalsPointOutward)
{
  Chain chain;
  for (int i = 0; i < 7; ++i)
  {
    RibbonResidue residue;
    residue.trace = { 3.8 * i, 0, 0 };
    chain.push_back(residue);
  }
  const RibbonParams settings;
  const RibbonMesh mesh = mesolens::ribbon_mesh(chain, settings);
  expect_closed_pieces(mesh);
  const double end = 3.8 * 6;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
  {
    const Point p = vertex(mesh, v);
    const Point axis_point{ std::min(std::max(p[0], 0.0), end), 0, 0 };
    const Point outward = sub(p, axis_point);
    EXPECT_NEAR(norm(outward), settings.coil_radius, 1e-9) << "vertex " << v;
    EXPECT_GT(dot(vertex_normal(mesh, v), outward), 0.99 * settings.coil_radius) << "vertex " << v;
  }
}

TEST(RibbonGeometry, ArrowheadAtEveryStrandEnd)
{
  Chain chain = loop(3);
  append(chain, ideal_strand(5));
  append(chain, loop(4));
  append(chain, ideal_strand(5));
  chain = numbered(chain);
  const std::size_t strand_ends[] = { 7, 16 }; // the second strand ends the chain
  RibbonParams settings;
  const RibbonMesh mesh = mesolens::ribbon_mesh(chain, settings);
  expect_closed_pieces(mesh);
  const double strand = 0.5 * settings.strand_width;
  const double arrow = settings.arrow_width_factor * strand;
  for (std::size_t end : strand_ends)
  {
    SCOPED_TRACE(testing::Message() << "strand ending at " << end);
    double widest = 0;
    for (const auto& sample : mesh.centre_line)
    {
      if (sample.parameter >= end - 1.0 && sample.parameter <= end)
      {
        widest = std::max(widest, sample.half_width);
        EXPECT_NEAR(ring_extent(mesh, sample, settings.tube_sides), sample.half_width, 1e-9);
      }
      if (sample.parameter >= end - 3.0 && sample.parameter <= end - 1.0)
      {
        EXPECT_NEAR(sample.half_width, strand, 1e-12) << "at " << sample.parameter;
      }
    }
    EXPECT_NEAR(widest, arrow, 1e-9);
    const auto& tip = sample_at(mesh, end);
    EXPECT_NEAR(tip.half_width, settings.coil_radius, 1e-12);
    EXPECT_LT(tip.half_width, 0.25 * widest);
    // The arrowhead's edge faces forward where it narrows.
    const auto& taper = sample_at(mesh, end - 0.5);
    const Point edge_normal = vertex_normal(mesh, taper.first_ring_vertex);
    EXPECT_GT(dot(edge_normal, taper.tangent), 0.1);
  }
}

TEST(RibbonGeometry, SectionsChangeSmoothlyBetweenStyles)
{
  Chain chain = ideal_helix(8);
  append(chain, loop(6));
  RibbonParams settings;
  settings.subdivisions = 10;
  const RibbonMesh mesh = mesolens::ribbon_mesh(chain, settings);
  EXPECT_DOUBLE_EQ(sample_at(mesh, 7).half_width, 0.5 * settings.helix_width);
  EXPECT_DOUBLE_EQ(sample_at(mesh, 8).half_width, settings.coil_radius);
  EXPECT_DOUBLE_EQ(sample_at(mesh, 8).half_thickness, settings.coil_radius);
  const double drop = 0.5 * settings.helix_width - settings.coil_radius;
  for (std::size_t k = 1; k < mesh.centre_line.size(); ++k)
  {
    const double change = mesh.centre_line[k].half_width - mesh.centre_line[k - 1].half_width;
    EXPECT_LE(change, 1e-12);                                       // never widens again
    EXPECT_LE(-change, 1.5 * drop / settings.subdivisions + 1e-12); // smoothstep's steepest
  }
}

TEST(RibbonGeometry, TriangleCountGrowsLinearlyWithSubdivisions)
{
  Chain chain = mixed_chain();
  append(chain, ideal_strand(4)); // a second arrowhead, at the chain's end
  std::vector<std::size_t> triangles;
  for (int subdivisions = 1; subdivisions <= 12; ++subdivisions)
  {
    RibbonParams settings;
    settings.subdivisions = subdivisions;
    const RibbonMesh mesh = mesolens::ribbon_mesh(chain, settings);
    triangles.push_back(mesh.triangle_count());
    // subdivisions samples per residue interval, plus one per arrowhead shoulder.
    EXPECT_EQ(mesh.centre_line.size(), (chain.size() - 1) * subdivisions + 1 + 2);
  }
  const std::size_t step = triangles[1] - triangles[0];
  EXPECT_EQ(step, 2u * 8u * (chain.size() - 1));
  for (std::size_t s = 1; s < triangles.size(); ++s)
  {
    EXPECT_EQ(triangles[s] - triangles[s - 1], step) << "subdivisions " << s + 1;
  }
}

TEST(RibbonGeometry, PerSegmentSubdivisionsAreHonoured)
{
  Chain chain = ideal_helix(10);
  Chain second = ideal_strand(6);
  for (RibbonResidue& residue : second)
  {
    residue.trace[1] += 30;
    residue.carbonyl_oxygen = add(*residue.carbonyl_oxygen, Point{ 0, 30, 0 });
  }
  chain.insert(chain.end(), second.begin(), second.end());
  ASSERT_EQ(mesolens::ribbon_segments(chain).size(), 2u);
  RibbonParams coarse, fine, mixed;
  coarse.subdivisions = 2;
  fine.subdivisions = 9;
  mixed.segment_subdivisions = { 2, 9 };
  const RibbonMesh a = mesolens::ribbon_mesh(chain, coarse);
  const RibbonMesh b = mesolens::ribbon_mesh(chain, fine);
  const RibbonMesh m = mesolens::ribbon_mesh(chain, mixed);
  ASSERT_EQ(m.pieces.size(), 2u);
  EXPECT_EQ(m.pieces[0].triangle_count, a.pieces[0].triangle_count);
  EXPECT_EQ(m.pieces[1].triangle_count, b.pieces[1].triangle_count);
  EXPECT_NE(a.pieces[1].triangle_count, b.pieces[1].triangle_count);
  expect_closed_pieces(m);
}

TEST(RibbonGeometry, HelixAsCylinderAlongItsAxis)
{
  Chain chain = loop(4);
  append(chain, ideal_helix(12));
  append(chain, loop(4));
  chain = numbered(chain);
  RibbonParams settings;
  settings.helix_as_cylinder = true;
  const RibbonMesh mesh = mesolens::ribbon_mesh(chain, settings);
  ASSERT_EQ(mesh.pieces.size(), 3u);
  EXPECT_EQ(mesh.pieces[0].kind, RibbonPiece::Kind::Tube);
  EXPECT_EQ(mesh.pieces[1].kind, RibbonPiece::Kind::Cylinder);
  EXPECT_EQ(mesh.pieces[2].kind, RibbonPiece::Kind::Tube);
  expect_closed_pieces(mesh);
  // The helix axis is the line through the helix's centre parallel to z.
  const Point first = chain[4].trace;
  const Point axis{ first[0] - 2.3, first[1], 0 };
  double low = 1e9, high = -1e9;
  const RibbonPiece& cylinder = mesh.pieces[1];
  for (std::size_t v = cylinder.first_vertex; v < cylinder.first_vertex + cylinder.vertex_count;
       ++v)
  {
    const Point p = vertex(mesh, v);
    const double radius = std::hypot(p[0] - axis[0], p[1] - axis[1]);
    EXPECT_LT(radius, settings.cylinder_radius + 1e-3);
    if (std::abs(vertex_normal(mesh, v)[2]) < 1e-9) // the side, not the caps
    {
      EXPECT_NEAR(radius, settings.cylinder_radius, 1e-3) << "vertex " << v;
      low = std::min(low, p[2]);
      high = std::max(high, p[2]);
    }
    const std::int64_t id = mesh.vertex_residue_id[v];
    EXPECT_TRUE(id >= 1004 && id < 1016) << id;
    EXPECT_EQ(mesh.vertex_secondary_structure[v], 'H');
  }
  EXPECT_NEAR(low, chain[4].trace[2], 1e-3);
  EXPECT_NEAR(high, chain[15].trace[2], 1e-3);
  // The tubes stop at the helix's first and last Cα.
  for (std::size_t p : { 0u, 2u })
  {
    for (std::size_t v = mesh.pieces[p].first_vertex;
         v < mesh.pieces[p].first_vertex + mesh.pieces[p].vertex_count; ++v)
    {
      const std::int64_t id = mesh.vertex_residue_id[v];
      EXPECT_TRUE(id <= 1004 || id >= 1015) << "tube inside the cylinder at " << id;
    }
  }
}

// Found by fuzz_ribbons: a coil radius of 1e-306 Å was taken and gave zero normals; lengths
// and counts now have documented ranges.
TEST(RibbonGeometry, SettingsOutsideTheirRangesAreRefused)
{
  const auto refused = [](const RibbonParams& settings, const std::string& phrase) {
    try
    {
      mesolens::ribbon_mesh(mixed_chain(), settings);
      ADD_FAILURE() << "accepted: " << phrase;
    }
    catch (const mesolens::InvalidInput& e)
    {
      EXPECT_NE(std::string(e.what()).find(phrase), std::string::npos) << e.what();
    }
  };
  RibbonParams bad;
  bad.coil_radius = 1e-306;
  refused(bad, "coil_radius must be a length in [0.001000, 1000.000000] Å");
  bad = {};
  bad.helix_width = 1e300;
  refused(bad, "helix_width must be a length in");
  bad = {};
  bad.subdivisions = 1000000000;
  refused(bad, "subdivisions must be in [1, 100]");
  bad = {};
  bad.tube_sides = 100000;
  refused(bad, "tube_sides must be in [3, 360]");
  bad = {};
  bad.arrow_width_factor = 1e200;
  refused(bad, "arrow_width_factor must be in [1, 100]");
  bad = {};
  bad.segment_subdivisions = { 101 };
  refused(bad, "segment_subdivisions[0] must be in [1, 100]");
  RibbonParams edge;
  edge.coil_radius = mesolens::shortest_ribbon_length;
  edge.subdivisions = mesolens::largest_ribbon_subdivisions;
  const RibbonMesh mesh = mesolens::ribbon_mesh(mixed_chain(), edge);
  for (std::size_t v = 0; v < mesh.normals.size(); v += 3)
  {
    ASSERT_NEAR(std::hypot(mesh.normals[v], mesh.normals[v + 1], mesh.normals[v + 2]), 1.0, 1e-9);
  }
}

// Found by fuzz_ribbons: a trace 1e300 Å out overflowed the spline to infinite points.
TEST(RibbonGeometry, TracesBeyondTheCoordinateLimitAreRefused)
{
  Chain chain = mixed_chain();
  chain[3].trace[2] = 1e300;
  try
  {
    mesolens::ribbon_mesh(chain);
    ADD_FAILURE() << "accepted";
  }
  catch (const mesolens::InvalidInput& e)
  {
    EXPECT_NE(std::string(e.what()).find("residue 3 (id 1003, chain 0) has a non-finite Cα/P "
                                         "position or one beyond 1e8 Å"),
              std::string::npos)
      << e.what();
  }
  chain = mixed_chain();
  chain[2].carbonyl_oxygen = std::array<double, 3>{ 0, -2e8, 0 };
  EXPECT_THROW(mesolens::ribbon_mesh(chain), mesolens::InvalidInput);
}

TEST(RibbonGeometry, BadInputs)
{
  RibbonMesh empty;
  EXPECT_NO_THROW(empty = mesolens::ribbon_mesh({}));
  EXPECT_EQ(empty.vertex_count(), 0u);
  EXPECT_EQ(empty.triangle_count(), 0u);
  EXPECT_TRUE(empty.pieces.empty());

  RibbonParams bad;
  bad.subdivisions = 0;
  EXPECT_THROW(mesolens::ribbon_mesh({}, bad), mesolens::InvalidInput);
  EXPECT_THROW(mesolens::ribbon_mesh(mixed_chain(), bad), mesolens::InvalidInput);
  bad = {};
  bad.tube_sides = 2;
  EXPECT_THROW(mesolens::ribbon_mesh(mixed_chain(), bad), mesolens::InvalidInput);
  bad = {};
  bad.arrow_width_factor = 0.5;
  EXPECT_THROW(mesolens::ribbon_mesh(mixed_chain(), bad), mesolens::InvalidInput);
  bad = {};
  bad.coil_radius = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(mesolens::ribbon_mesh(mixed_chain(), bad), mesolens::InvalidInput);
  bad = {};
  bad.segment_subdivisions = { 3, 3 }; // one segment only
  EXPECT_THROW(mesolens::ribbon_mesh(mixed_chain(), bad), mesolens::InvalidInput);
  bad.segment_subdivisions = { 0 };
  EXPECT_THROW(mesolens::ribbon_mesh(mixed_chain(), bad), mesolens::InvalidInput);

  Chain chain = mixed_chain();
  chain[12].trace[1] = std::numeric_limits<double>::quiet_NaN();
  try
  {
    mesolens::ribbon_mesh(chain);
    ADD_FAILURE() << "a NaN Cα was accepted";
  }
  catch (const mesolens::InvalidInput& error)
  {
    EXPECT_NE(std::string(error.what()).find("residue 12 (id 1012"), std::string::npos)
      << error.what();
  }
  chain = mixed_chain();
  chain[3].carbonyl_oxygen = Point{ 0, std::numeric_limits<double>::infinity(), 0 };
  try
  {
    mesolens::ribbon_mesh(chain);
    ADD_FAILURE() << "an infinite O was accepted";
  }
  catch (const mesolens::InvalidInput& error)
  {
    EXPECT_NE(std::string(error.what()).find("id 1003"), std::string::npos) << error.what();
  }
}

TEST(RibbonGeometry, LoneResidueIsASphere)
{
  for (char code : { 'H', 'E', '-' })
  {
    RibbonResidue residue;
    residue.trace = { 1, 2, 3 };
    residue.carbonyl_oxygen = Point{ 1, 4, 3 };
    residue.secondary_structure = code;
    residue.id = 77;
    const RibbonParams settings;
    const RibbonMesh mesh = mesolens::ribbon_mesh({ residue }, settings);
    ASSERT_EQ(mesh.pieces.size(), 1u);
    expect_closed_pieces(mesh);
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
    {
      const Point outward = sub(vertex(mesh, v), residue.trace);
      EXPECT_NEAR(norm(outward), settings.coil_radius, 1e-12);
      EXPECT_NEAR(dot(vertex_normal(mesh, v), outward), settings.coil_radius, 1e-9);
      EXPECT_EQ(mesh.vertex_residue_id[v], 77);
      EXPECT_EQ(mesh.vertex_secondary_structure[v], code);
    }
  }
}

TEST(RibbonGeometry, NucleicAcidBackboneIsAThickTubeThroughThePhosphates)
{
  Chain chain;
  for (int i = 0; i < 10; ++i)
  {
    RibbonResidue residue;
    const double angle = i * 36.0 * pi / 180.0; // a B-DNA strand: 36° and 3.4 Å per step
    residue.trace = { 8.9 * std::cos(angle), 8.9 * std::sin(angle), 3.4 * i };
    residue.nucleotide = true;
    chain.push_back(residue);
  }
  chain = numbered(chain);
  const RibbonParams settings;
  const RibbonMesh mesh = mesolens::ribbon_mesh(chain, settings);
  ASSERT_EQ(mesh.segments.size(), 1u); // P-P 6.5 Å is bonded for nucleotides
  expect_closed_pieces(mesh);
  for (const auto& sample : mesh.centre_line)
  {
    EXPECT_DOUBLE_EQ(sample.half_width, settings.nucleic_radius);
    EXPECT_NEAR(ring_extent(mesh, sample, settings.tube_sides), settings.nucleic_radius, 1e-9);
  }
  // A nucleotide without P is simply absent: the 13 Å step it leaves breaks the tube.
  Chain missing = chain;
  missing.erase(missing.begin() + 5);
  EXPECT_EQ(mesolens::ribbon_mesh(missing).segments.size(), 2u);
  // Amino acids and nucleotides are never joined, even within bonding distance.
  Chain hybrid = chain;
  RibbonResidue amino;
  amino.trace = add(chain.back().trace, Point{ 0, 0, 3.8 });
  hybrid.push_back(amino);
  EXPECT_EQ(mesolens::ribbon_segments(hybrid).size(), 2u);
}

TEST(RibbonGeometry, VerticesCarryTheirResidue)
{
  const Chain chain = mixed_chain();
  const RibbonParams settings;
  const RibbonMesh mesh = mesolens::ribbon_mesh(chain, settings);
  for (const auto& sample : mesh.centre_line)
  {
    ASSERT_GE(sample.first_ring_vertex, 0);
    for (int j = 0; j < settings.tube_sides; ++j)
    {
      const std::size_t v = static_cast<std::size_t>(sample.first_ring_vertex + j);
      EXPECT_EQ(mesh.vertex_residue_id[v], chain[sample.residue].id);
      EXPECT_EQ(mesh.vertex_secondary_structure[v], chain[sample.residue].secondary_structure);
    }
    EXPECT_LE(std::abs(sample.parameter - static_cast<double>(sample.residue)), 0.5);
  }
}

TEST(RibbonGeometry, DeterministicWhateverTheThreadSplit)
{
  Chain chain = mixed_chain();
  Chain other = ideal_helix(9);
  for (RibbonResidue& residue : other)
  {
    residue.chain = 2;
  }
  chain.insert(chain.end(), other.begin(), other.end());
  RibbonParams settings;
  settings.helix_as_cylinder = true;
  const RibbonMesh serial = mesolens::ribbon_mesh(chain, settings);
  // Ranges of one item, run last to first.
  const mesolens::ParallelFor reversed = [](std::size_t count,
                                            const mesolens::RangeKernel& kernel) {
    for (std::size_t i = count; i-- > 0;)
      kernel(i, i + 1);
  };
  const RibbonMesh split = mesolens::ribbon_mesh(chain, settings, reversed);
  EXPECT_EQ(serial.points, split.points);
  EXPECT_EQ(serial.normals, split.normals);
  EXPECT_EQ(serial.triangles, split.triangles);
  EXPECT_EQ(serial.vertex_residue_id, split.vertex_residue_id);
  ASSERT_EQ(serial.centre_line.size(), split.centre_line.size());
  for (std::size_t k = 0; k < serial.centre_line.size(); ++k)
  {
    EXPECT_EQ(serial.centre_line[k].position, split.centre_line[k].position);
    EXPECT_EQ(serial.centre_line[k].first_ring_vertex, split.centre_line[k].first_ring_vertex);
  }
}

TEST(RibbonGeometry, AReusedMeshIsTheFreshMeshAndKeepsItsMemory)
{
  // Into one mesh: fine, then coarse (smaller arrays), then fine again: each the same as a mesh
  // made afresh, nothing left over from the larger one, and the fine arrays' memory kept.
  const Chain chain = mixed_chain();
  RibbonParams fine, coarse;
  fine.subdivisions = 8;
  coarse.subdivisions = 2;
  RibbonMesh reused;
  mesolens::ribbon_mesh(chain, fine, {}, reused);
  const double* first_points = reused.points.data();
  for (const RibbonParams& settings : { coarse, fine })
  {
    mesolens::ribbon_mesh(chain, settings, {}, reused);
    const RibbonMesh fresh = mesolens::ribbon_mesh(chain, settings);
    EXPECT_EQ(reused.points, fresh.points);
    EXPECT_EQ(reused.normals, fresh.normals);
    EXPECT_EQ(reused.triangles, fresh.triangles);
    EXPECT_EQ(reused.vertex_residue_id, fresh.vertex_residue_id);
    EXPECT_EQ(reused.vertex_secondary_structure, fresh.vertex_secondary_structure);
    EXPECT_EQ(reused.pieces.size(), fresh.pieces.size());
    EXPECT_EQ(reused.segments.size(), fresh.segments.size());
    ASSERT_EQ(reused.centre_line.size(), fresh.centre_line.size());
    EXPECT_EQ(reused.centre_line.back().position, fresh.centre_line.back().position);
  }
  EXPECT_EQ(reused.points.data(), first_points);
  // A refused input leaves the mesh to be refilled, not a crash.
  Chain broken = chain;
  broken[1].trace[0] = std::nan("");
  EXPECT_THROW(mesolens::ribbon_mesh(broken, fine, {}, reused), mesolens::InvalidInput);
  mesolens::ribbon_mesh(chain, coarse, {}, reused);
  EXPECT_EQ(reused.triangles, mesolens::ribbon_mesh(chain, coarse).triangles);
}
