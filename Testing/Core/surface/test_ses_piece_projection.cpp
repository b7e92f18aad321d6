// SPDX-License-Identifier: GPL-3.0-or-later
// Projections onto single solvent-excluded patches with their cheap certificates (a private part
// of MesoLensCore), against the general search: every certified point must lie on the surface,
// points inside a patch's ball must get their nearest surface point, and most points near the
// surface must be certified (else the speed-up is gone). The contour's field, sampled a block
// at a time from the same pieces, against the same search.
#include "surface/detail/contour_tetrahedra.h"
#include "surface/detail/excluded_surface.h"
#include "surface/detail/probe_distance.h"
#include "surface/detail/sas_boundary.h"
#include "surface/detail/ses_patches.h"
#include "surface/detail/ses_piece_projection.h"
#include "surface/detail/surface_contour_fields.h"

#include "mesolens/molecules/elements.h"
#include "mesolens/io/structure_file.h"
#include "mesolens_test_data.h"
#include "mesolens_test_threads.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace {
using Vec = Eigen::Vector3d;
using mesolens::ClosestPiece;
using mesolens::PieceKind;
constexpr double probe = 1.4;

/// Atoms, their boundary with the probe, a general search and the projections under test.
struct Surface
{
  std::vector<std::array<double, 3>> centre_list;
  std::vector<Vec> centres;
  std::vector<double> atom_radii, inflated;
  mesolens::SasBoundary boundary;
  std::unique_ptr<mesolens::ProbeDistance> distance;
  std::unique_ptr<mesolens::SesPieceProjection> pieces;

  Surface(const std::vector<Vec>& atoms, const std::vector<double>& radii,
          const mesolens::ParallelFor& parallel_for)
    : centres(atoms)
    , atom_radii(radii)
  {
    for (std::size_t i = 0; i < atoms.size(); ++i)
    {
      this->centre_list.push_back({ atoms[i][0], atoms[i][1], atoms[i][2] });
      this->inflated.push_back(radii[i] + probe);
    }
    this->boundary = mesolens::sas_boundary(this->centre_list, this->inflated, true, parallel_for);
    this->distance = std::make_unique<mesolens::ProbeDistance>(this->centres, this->inflated,
                                                               this->boundary, 3.0 * probe);
    this->pieces = std::make_unique<mesolens::SesPieceProjection>(
      this->centres, this->atom_radii, probe, this->boundary, *this->distance);
  }

  /// The patch integrals' word on which patches nothing cuts, handed to the projections.
  mesolens::SesPatchIntegrals take_uncut_patches()
  {
    double largest = 0;
    for (const double r : this->inflated)
    {
      largest = std::max(largest, r);
    }
    const mesolens::ProbeDistance patch_distance(this->centres, this->inflated, this->boundary,
                                                 2.0 * probe + largest);
    mesolens::SesPatchIntegrals patches = mesolens::ses_patch_integrals(
      this->centres, this->atom_radii, probe, this->boundary, patch_distance, {});
    this->pieces->take_uncut_patches(patches.arc_uncut, patches.vertex_uncut);
    return patches;
  }

  /// Whether `y` lies on the surface by the general search (its nearest probe position the
  /// probe radius away, to 1e-7 Å).
  bool on_surface(const Vec& y) const
  {
    return std::abs(this->distance->closest(y).distance - probe) <= 1e-7;
  }
};

std::vector<Vec> protein_atoms(const std::string& file, std::vector<double>& radii)
{
  const auto table = mesolens::read_structure(mesolens_test::data_file(file)).models.at(0);
  std::vector<Vec> atoms;
  for (std::size_t i = 0; i < table.atomic_numbers.size(); ++i)
  {
    const int z = table.atomic_numbers[i];
    if (z == 1)
    {
      continue;
    }
    atoms.emplace_back(table.positions[3 * i], table.positions[3 * i + 1],
                       table.positions[3 * i + 2]);
    radii.push_back(z > 0 ? mesolens::van_der_waals_radius(z) : 2.0);
  }
  return atoms;
}

/// Points near the surface: around each atom, from inside its sphere to a probe diameter out.
std::vector<Vec> points_near(const Surface& surface, int per_atom, unsigned seed)
{
  std::mt19937 random(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> depth(-0.5, 2.0 * probe);
  std::vector<Vec> points;
  for (std::size_t i = 0; i < surface.centres.size(); ++i)
  {
    for (int k = 0; k < per_atom; ++k)
    {
      const Vec u = Vec(normal(random), normal(random), normal(random)).normalized();
      points.push_back(surface.centres[i] + (surface.atom_radii[i] + depth(random)) * u);
    }
  }
  return points;
}

/// The general answer: the nearest surface point of `x` from its nearest probe position,
/// when `x` lies within the probe radius of one (between the surface and the solvent).
bool general_nearest(const Surface& surface, const Vec& x, Vec& y, ClosestPiece& piece)
{
  piece = surface.distance->closest(x);
  const Vec away = x - piece.point;
  if (piece.kind == PieceKind::None || !(piece.distance > 0) || !(away.norm() > 0))
  {
    return false;
  }
  y = piece.point + probe / away.norm() * away;
  return surface.on_surface(y);
}

/// Checks the projections of points near `surface` against the general search; returns the
/// fraction of the points inside their nearest probe's ball that were certified.
double check_against_search(const Surface& surface, const std::vector<Vec>& points)
{
  std::size_t inside = 0, certified = 0, checked = 0;
  for (const Vec& x : points)
  {
    Vec exact;
    ClosestPiece piece;
    if (!general_nearest(surface, x, exact, piece))
    {
      continue;
    }
    // Inside the probe's ball (or the atom's, for a convex point): the certified projection
    // onto that piece's patch is the nearest surface point.
    Vec y;
    ClosestPiece nearest;
    const bool inside_ball = piece.kind == PieceKind::Face
      ? (x - surface.centres[piece.index]).norm() < surface.atom_radii[piece.index]
      : (x - piece.point).norm() < probe;
    if (inside_ball)
    {
      ++inside;
      if (surface.pieces->nearest(x, piece.kind, piece.index, y, nearest))
      {
        ++certified;
        EXPECT_LT((y - exact).norm(), 1e-9) << "x " << x.transpose();
        EXPECT_NEAR((nearest.point - y).norm(), probe, 1e-9);
      }
    }
    // Whatever the piece tried, a certified point lies on the surface.
    for (const PieceKind kind : { PieceKind::Face, PieceKind::Arc, PieceKind::Vertex })
    {
      const std::size_t count = kind == PieceKind::Face
        ? surface.centres.size()
        : (kind == PieceKind::Arc ? surface.boundary.arcs.size()
                                  : surface.boundary.vertices.size());
      if (count == 0)
      {
        continue;
      }
      const auto index = static_cast<std::uint32_t>((checked * 7919) % count);
      if (surface.pieces->nearest(x, kind, index, y, nearest))
      {
        EXPECT_TRUE(surface.on_surface(y)) << "piece " << int(kind) << " " << index;
      }
    }
    if (surface.pieces->nearest_near(x, { piece.kind, piece.index }, { piece.kind, piece.index }, y,
                                     nearest))
    {
      EXPECT_TRUE(surface.on_surface(y));
    }
    ++checked;
  }
  EXPECT_GT(inside, points.size() / 10);
  return inside > 0 ? double(certified) / double(inside) : 0.0;
}

/// Atoms packed so that the probe passes between pairs (self-intersecting tori) and probes
/// between triples overlap: the singular cases.
std::vector<Vec> packed_atoms(std::vector<double>& radii)
{
  std::vector<Vec> atoms;
  std::mt19937 random(11);
  std::uniform_real_distribution<double> coordinate(-4.0, 4.0), radius(1.2, 1.9);
  while (atoms.size() < 40)
  {
    const Vec c(coordinate(random), coordinate(random), coordinate(random));
    bool apart = true;
    for (const Vec& other : atoms)
    {
      apart = apart && (other - c).norm() > 2.0;
    }
    if (apart)
    {
      atoms.push_back(c);
      radii.push_back(radius(random));
    }
  }
  return atoms;
}

TEST(SesPieceProjection, CertifiedPointsOfCrambinLieOnItsSurface)
{
  std::vector<double> radii;
  const std::vector<Vec> atoms = protein_atoms("proteins/1crn.pdb", radii);
  const Surface surface(atoms, radii, mesolens_test::two_threads());
  ASSERT_GT(surface.boundary.vertices.size(), 100u);
  const double certified = check_against_search(surface, points_near(surface, 12, 7));
  // Most points are certified: the cheap path does the work.
  EXPECT_GT(certified, 0.8);
}

TEST(SesPieceProjection, PinchedToriAndOverlappingProbesAreCut)
{
  std::vector<double> radii;
  const std::vector<Vec> atoms = packed_atoms(radii);
  const Surface surface(atoms, radii, {});
  std::size_t pinched = 0;
  for (const auto& arc : surface.boundary.arcs)
  {
    pinched += arc.radius < probe ? 1 : 0;
  }
  EXPECT_GT(pinched, 0u);
  const double certified = check_against_search(surface, points_near(surface, 60, 3));
  EXPECT_GT(certified, 0.5);
}

/// How many pieces' answers differ between projections given the integrals' uncut patches
/// (`flagged`) and projections that list every patch's cutters (`listed`), over `points` and the
/// arcs or vertices (`kind`) within reach of each; certified answers are checked on the surface
/// and counted into `certified`.
std::size_t differences(const Surface& flagged, const Surface& listed,
                        const std::vector<Vec>& points, PieceKind kind, std::size_t& certified)
{
  std::size_t differ = 0;
  const std::size_t pieces =
    kind == PieceKind::Arc ? flagged.boundary.arcs.size() : flagged.boundary.vertices.size();
  for (const Vec& x : points)
  {
    for (std::uint32_t k = 0; k < pieces; ++k)
    {
      const Vec& at = kind == PieceKind::Arc ? flagged.boundary.arcs[k].centre
                                             : flagged.boundary.vertices[k].position;
      if ((x - at).norm() > 3.0 * probe + 2.0)
      {
        continue; // far from this patch: not a test of it
      }
      Vec a, b;
      ClosestPiece near_a, near_b;
      const bool by_flags = flagged.pieces->nearest(x, kind, k, a, near_a);
      const bool by_lists = listed.pieces->nearest(x, kind, k, b, near_b);
      differ += by_flags != by_lists || (by_flags && (a - b).norm() > 0) ? 1 : 0;
      if (by_flags)
      {
        ++certified;
        EXPECT_TRUE(flagged.on_surface(a)) << "piece " << int(kind) << " " << k;
      }
    }
  }
  return differ;
}

std::size_t count_set(const std::vector<char>& flags)
{
  return std::size_t(std::count(flags.begin(), flags.end(), 1));
}

TEST(SesPieceProjection, PatchesTheIntegralsFindUncutNeedNoList)
{
  // With the integrals' uncut patches taken (no list of cutters made for them), every answer is
  // the one the lists give, on crambin and on the packed singular set, where concave patches
  // come cut and uncut (tori are almost never cut by a foreign probe: see the next test).
  for (const bool packed : { false, true })
  {
    std::vector<double> radii;
    const std::vector<Vec> atoms =
      packed ? packed_atoms(radii) : protein_atoms("proteins/1crn.pdb", radii);
    Surface listed(atoms, radii, {}), flagged(atoms, radii, {});
    const mesolens::SesPatchIntegrals patches = flagged.take_uncut_patches();
    ASSERT_EQ(patches.arc_uncut.size(), flagged.boundary.arcs.size());
    ASSERT_EQ(patches.vertex_uncut.size(), flagged.boundary.vertices.size());
    EXPECT_GT(count_set(patches.arc_uncut), 0u);
    EXPECT_GT(count_set(patches.vertex_uncut), 0u);
    EXPECT_LT(count_set(patches.vertex_uncut), patches.vertex_uncut.size());
    std::size_t certified = 0;
    const std::vector<Vec> points = points_near(flagged, packed ? 60 : 6, 9);
    EXPECT_EQ(differences(flagged, listed, points, PieceKind::Arc, certified), 0u);
    EXPECT_EQ(differences(flagged, listed, points, PieceKind::Vertex, certified), 0u);
    EXPECT_GT(certified, 100u);
    EXPECT_GT(check_against_search(flagged, points_near(flagged, packed ? 30 : 6, 4)), 0.5);
  }
}

TEST(SesPieceProjection, ATorusAForeignProbeMayCutStaysListed)
{
  // 1ubq has a torus that a probe touching neither of its atoms may cut (the probe passes
  // between its atoms, so no general argument clears it, and the integrals cannot certify it
  // clear): it must stay listed (flagging every torus uncut leaves none, and the assertion
  // below fails), and the points certified around it must lie on the surface. This torus is not
  // actually cut, so wrongly flagging it alone would go unseen here; concave patches, cut far
  // more often, are what the test above checks the flags on (flagging them all makes it fail).
  std::vector<double> radii;
  const std::vector<Vec> atoms = protein_atoms("proteins/1ubq.pdb", radii);
  Surface listed(atoms, radii, {}), flagged(atoms, radii, {});
  const mesolens::SesPatchIntegrals patches = flagged.take_uncut_patches();
  std::vector<Vec> points;
  std::mt19937 random(5);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (std::size_t k = 0; k < patches.arc_uncut.size(); ++k)
  {
    if (patches.arc_uncut[k])
    {
      continue;
    }
    // Around the probe's path: its positions on the arc, then a probe radius out or less.
    const mesolens::SasArc& arc = flagged.boundary.arcs[k];
    for (int n = 0; n < 400; ++n)
    {
      const Vec u = Vec(normal(random), normal(random), normal(random)).normalized();
      points.push_back(arc.point(arc.start + arc.span * unit(random)) +
                       probe * (0.7 + 0.4 * unit(random)) * u);
    }
  }
  ASSERT_GT(points.size(), 0u) << "no torus cut by a foreign probe in 1ubq";
  EXPECT_GT(count_set(patches.arc_uncut), patches.arc_uncut.size() / 2);
  std::size_t certified = 0;
  EXPECT_EQ(differences(flagged, listed, points, PieceKind::Arc, certified), 0u);
  EXPECT_GT(certified, 0u);
}

TEST(SesPieceProjection, ThreadsGiveTheSameAnswers)
{
  // Patches' cutters are listed by the first thread that needs them: two threads asking at once
  // get what one thread alone gets.
  std::vector<double> radii;
  const std::vector<Vec> atoms = protein_atoms("proteins/1crn.pdb", radii);
  const Surface shared(atoms, radii, {}), alone(atoms, radii, {});
  const std::vector<Vec> points = points_near(shared, 4, 5);
  const auto answers = [&](const Surface& surface, std::size_t k) {
    std::vector<Vec> found;
    for (const PieceKind kind : { PieceKind::Arc, PieceKind::Vertex })
    {
      const std::size_t count =
        kind == PieceKind::Arc ? surface.boundary.arcs.size() : surface.boundary.vertices.size();
      for (std::size_t index = k % 13; index < count; index += 13)
      {
        Vec y;
        ClosestPiece nearest;
        const bool certified =
          surface.pieces->nearest(points[k], kind, std::uint32_t(index), y, nearest);
        found.push_back(certified ? y : Vec::Constant(-1));
      }
    }
    return found;
  };
  std::vector<std::vector<Vec>> threaded(points.size());
  mesolens_test::two_threads()(points.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k)
    {
      threaded[k] = answers(shared, k);
    }
  });
  std::size_t certified = 0;
  for (std::size_t k = 0; k < points.size(); ++k)
  {
    const std::vector<Vec> serial = answers(alone, k);
    ASSERT_EQ(serial, threaded[k]) << "point " << k;
    certified += std::count_if(serial.begin(), serial.end(),
                               [](const Vec& y) { return y != Vec::Constant(-1); });
  }
  EXPECT_GT(certified, 0u);
}

TEST(SesPieceProjection, DegeneratePointsAreRefused)
{
  std::vector<double> radii;
  const std::vector<Vec> atoms = protein_atoms("proteins/1crn.pdb", radii);
  const Surface surface(atoms, radii, {});
  Vec y;
  ClosestPiece nearest;
  // At a sphere's centre, on a circle's axis, at a probe's centre: no direction to project in.
  EXPECT_FALSE(surface.pieces->nearest(surface.centres[0], PieceKind::Face, 0, y, nearest));
  const auto& arc = surface.boundary.arcs.at(0);
  EXPECT_FALSE(surface.pieces->nearest(arc.centre, PieceKind::Arc, 0, y, nearest));
  EXPECT_FALSE(surface.pieces->nearest(arc.point(arc.start), PieceKind::Arc, 0, y, nearest));
  const Vec& vertex = surface.boundary.vertices.at(0).position;
  EXPECT_FALSE(surface.pieces->nearest(vertex, PieceKind::Vertex, 0, y, nearest));
  EXPECT_FALSE(surface.pieces->nearest(vertex, PieceKind::None, 0, y, nearest));
  // A point off the sphere it is said to be on.
  EXPECT_FALSE(surface.pieces->certify(surface.centres[0] + Vec(0, 0, radii[0] + 0.01),
                                       PieceKind::Face, 0, nearest));
}

/// Samples every block of a grid over `surface` with the contour's field and checks each point
/// against the general search: the same sign, and inside the union the same distance to the
/// nearest probe position (up to the field's limit) from a piece that lies that far.
void check_field_against_search(const Surface& surface, double spacing)
{
  const double limit = probe + spacing;
  const auto field = mesolens::excluded_surface_field(
    *surface.distance, *surface.pieces, surface.boundary, surface.centres, surface.inflated,
    surface.atom_radii, probe, limit);
  Vec low = Vec::Constant(1e300), high = -low;
  for (std::size_t i = 0; i < surface.centres.size(); ++i)
  {
    low = low.cwiseMin(surface.centres[i] - Vec::Constant(surface.inflated[i] + 2.0));
    high = high.cwiseMax(surface.centres[i] + Vec::Constant(surface.inflated[i] + 2.0));
  }
  const mesolens::ContourGrid grid(low, high, spacing);
  field->prepare(grid, {});
  const auto local = field->local();
  constexpr int side = mesolens::ContourGrid::block_points;
  std::vector<double> values(side * side * side);
  std::vector<std::uint32_t> hints(side * side * side);
  std::size_t checked = 0, near_surface = 0;
  for (std::size_t b = 0; b < grid.block_count(); ++b)
  {
    const auto first = grid.block_first(b);
    const bool sampled = local->sample_block(grid, b, values.data(), hints.data());
    for (int z = 0; z < side; ++z)
      for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x)
        {
          const Vec point = grid.point(first[0] + x, first[1] + y, first[2] + z);
          const ClosestPiece exact = surface.distance->closest(point, {}, limit);
          if (!sampled)
          {
            // Unsampled blocks hold no zero: all outside the union or deeper than the limit.
            ASSERT_TRUE(exact.distance <= 0 || exact.distance >= limit) << point.transpose();
            continue;
          }
          const std::size_t at = std::size_t(x + side * (y + side * z));
          ++checked;
          ASSERT_EQ(values[at] > 0, exact.distance - probe > 0) << point.transpose();
          if (exact.distance > 0 && exact.distance < limit)
          {
            EXPECT_NEAR(values[at] + probe, exact.distance, 1e-12) << point.transpose();
            const PieceKind kind = mesolens::hint_kind(hints[at]);
            const std::uint32_t index = mesolens::hint_index(hints[at]);
            ASSERT_NE(kind, PieceKind::None);
            // The hinted piece lies that far (faces: its whole sphere; arcs: the exposed arc).
            const double hinted = kind == PieceKind::Arc
              ? surface.distance->arc_distance(index, point)
              : surface.distance->piece_distance(point, kind, index);
            EXPECT_NEAR(hinted, exact.distance, 1e-12) << point.transpose();
            near_surface += std::abs(exact.distance - probe) < spacing ? 1 : 0;
          }
        }
  }
  EXPECT_GT(checked, 10000u);
  EXPECT_GT(near_surface, 1000u);
}

TEST(SesContourField, CrambinsGridMatchesTheGeneralSearch)
{
  std::vector<double> radii;
  const std::vector<Vec> atoms = protein_atoms("proteins/1crn.pdb", radii);
  const Surface surface(atoms, radii, {});
  check_field_against_search(surface, 0.9);
}

TEST(SesContourField, PinchedToriAndOverlappingProbesMatchTheGeneralSearch)
{
  std::vector<double> radii;
  const std::vector<Vec> atoms = packed_atoms(radii);
  const Surface surface(atoms, radii, {});
  check_field_against_search(surface, 0.37);
}

TEST(SesContourField, VerticesLieOnTheSurfaceOnTheirGridEdges)
{
  for (const bool packed : { false, true })
  {
    std::vector<double> radii;
    const std::vector<Vec> atoms =
      packed ? packed_atoms(radii) : protein_atoms("proteins/1crn.pdb", radii);
    const Surface surface(atoms, radii, mesolens_test::two_threads());
    const double spacing = packed ? 0.41 : 1.1;
    const auto field = mesolens::excluded_surface_field(
      *surface.distance, *surface.pieces, surface.boundary, surface.centres, surface.inflated,
      surface.atom_radii, probe, probe + spacing);
    Vec low = Vec::Constant(1e300), high = -low;
    for (std::size_t i = 0; i < atoms.size(); ++i)
    {
      low = low.cwiseMin(atoms[i] - Vec::Constant(surface.inflated[i] + 1.0));
      high = high.cwiseMax(atoms[i] + Vec::Constant(surface.inflated[i] + 1.0));
    }
    const mesolens::ContourMesh mesh = mesolens::contour_tetrahedra(
      *field, low, high, spacing, mesolens_test::two_threads(), [](double) {});
    ASSERT_GT(mesh.vertices.size(), 1000u);
    for (const auto& vertex : mesh.vertices)
    {
      const ClosestPiece nearest = surface.distance->closest(vertex.position);
      ASSERT_NEAR(nearest.distance, probe, 1e-7) << vertex.position.transpose();
      // On a lattice edge, in spacings from `low`: along an axis, with the other two coordinates
      // on the grid (whole numbers) or the centred grid (halves); or along a diagonal from a
      // grid point to a cube's centre, all three as far from whole numbers.
      const Vec at = (vertex.position - low) / spacing;
      int on_grid = 0, on_centres = 0;
      double least = 1, most = 0;
      for (int a = 0; a < 3; ++a)
      {
        const double off = std::abs(at[a] - std::round(at[a]));
        on_grid += off < 1e-6 ? 1 : 0;
        on_centres += std::abs(off - 0.5) < 1e-6 ? 1 : 0;
        least = std::min(least, off);
        most = std::max(most, off);
      }
      EXPECT_TRUE(on_grid == 2 || on_centres == 2 || (most - least < 1e-6 && least > 1e-6))
        << vertex.position.transpose();
      EXPECT_EQ(vertex.patch,
                static_cast<std::uint8_t>(nearest.kind == PieceKind::Arc        ? 1
                                            : nearest.kind == PieceKind::Vertex ? 2
                                                                                : 0))
        << vertex.position.transpose();
    }
  }
}

} // namespace
