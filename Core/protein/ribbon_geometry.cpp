// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/protein/ribbon_geometry.h"

#include "mesolens/common/errors.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace mesolens {

namespace {
using Vec = Eigen::Vector3d;

constexpr double pi = 3.14159265358979323846;
/// Shorter side or curvature vectors (Å) give no direction worth following.
constexpr double min_guide_length = 1e-3;
/// Parameter step of the finite differences that give a section's change along the curve.
constexpr double slope_step = 1e-4;
/// Helices at least this long become cylinders (a shorter one has too few points to fit).
constexpr std::size_t min_cylinder_residues = 4;

Vec to_vec(const std::array<double, 3>& a)
{
  return { a[0], a[1], a[2] };
}

std::array<double, 3> to_array(const Vec& v)
{
  return { v.x(), v.y(), v.z() };
}

/// A unit vector perpendicular to the unit vector `v`.
Vec any_perpendicular(const Vec& v)
{
  Eigen::Index least = 0;
  v.cwiseAbs().minCoeff(&least);
  return v.cross(Vec::Unit(least)).normalized();
}

/// `v` made perpendicular to the unit vector `axis` and normalized; any perpendicular when `v`
/// is (nearly) along `axis`. Projecting a frame vector onto the next normal plane like this is
/// a discrete parallel transport: it turns no more than the curve does.
Vec carry_over(const Vec& v, const Vec& axis)
{
  const Vec w = v - v.dot(axis) * axis;
  const double length = w.norm();
  return length > 1e-9 ? Vec(w / length) : any_perpendicular(axis);
}

/// Finite and within largest_ribbon_coordinate (farther out the spline overflows).
bool within_limits(const std::array<double, 3>& p)
{
  return std::abs(p[0]) <= largest_ribbon_coordinate &&
    std::abs(p[1]) <= largest_ribbon_coordinate && std::abs(p[2]) <= largest_ribbon_coordinate;
}

/// The natural cubic spline through knots at parameters 0, 1, ..., n - 1: C2, interpolating,
/// zero second derivative at both ends. Its second derivatives M solve the tridiagonal system
/// M[i-1] + 4 M[i] + M[i+1] = 6 (P[i-1] - 2 P[i] + P[i+1]), solved in O(n) (Thomas algorithm).
class NaturalCubicSpline
{
public:
  explicit NaturalCubicSpline(std::vector<Vec> knots)
    : Knots(std::move(knots))
    , Second(this->Knots.size(), Vec::Zero())
  {
    const std::size_t n = this->Knots.size();
    if (n < 3)
    {
      return;
    }
    // Forward elimination over the interior unknowns 1 .. n-2 (diagonal 4, off-diagonals 1).
    std::vector<double> diagonal(n, 4.0);
    for (std::size_t i = 1; i + 1 < n; ++i)
    {
      this->Second[i] = 6.0 * (this->Knots[i - 1] - 2.0 * this->Knots[i] + this->Knots[i + 1]);
      if (i > 1)
      {
        const double factor = 1.0 / diagonal[i - 1];
        diagonal[i] -= factor;
        this->Second[i] -= factor * this->Second[i - 1];
      }
    }
    for (std::size_t i = n - 2; i >= 1; --i)
    {
      const Vec next = i + 2 < n ? this->Second[i + 1] : Vec::Zero();
      this->Second[i] = (this->Second[i] - next) / diagonal[i];
    }
  }

  Vec value(double t) const
  {
    if (this->Knots.size() == 1)
    {
      return this->Knots[0];
    }
    std::size_t i;
    const double u = this->locate(t, i);
    const double v = 1.0 - u;
    return v * this->Knots[i] + u * this->Knots[i + 1] +
      ((v * v * v - v) * this->Second[i] + (u * u * u - u) * this->Second[i + 1]) / 6.0;
  }

  Vec derivative(double t) const
  {
    if (this->Knots.size() == 1)
    {
      return Vec::Zero();
    }
    std::size_t i;
    const double u = this->locate(t, i);
    const double v = 1.0 - u;
    return this->Knots[i + 1] - this->Knots[i] +
      ((1.0 - 3.0 * v * v) * this->Second[i] + (3.0 * u * u - 1.0) * this->Second[i + 1]) / 6.0;
  }

private:
  /// The interval [i, i + 1] holding t, and t's fraction in it.
  double locate(double t, std::size_t& i) const
  {
    const double last = static_cast<double>(this->Knots.size() - 1);
    t = std::min(std::max(t, 0.0), last);
    i = std::min(static_cast<std::size_t>(t), this->Knots.size() - 2);
    return t - static_cast<double>(i);
  }

  std::vector<Vec> Knots;
  std::vector<Vec> Second;
};

/// An elliptic cross-section's semi-axes, Å.
struct Section
{
  double half_width = 0;
  double half_thickness = 0;
};

Section lerp(const Section& a, const Section& b, double w)
{
  return { a.half_width + w * (b.half_width - a.half_width),
           a.half_thickness + w * (b.half_thickness - a.half_thickness) };
}

/// The cross-section along one segment as a function of the curve parameter t (in residues,
/// 0 at the segment's first residue). Each residue holds its style's section at its own atom;
/// between residues of two styles the section follows a smoothstep; the interval before a
/// strand's last residue is its arrowhead.
class SectionProfile
{
public:
  SectionProfile(std::vector<RibbonStyle> styles, const RibbonParams& settings, double shoulder)
    : Styles(std::move(styles))
    , Shoulder(shoulder)
  {
    const double ribbon = 0.5 * settings.ribbon_thickness;
    this->HelixSection = { 0.5 * settings.helix_width, ribbon };
    this->StrandSection = { 0.5 * settings.strand_width, ribbon };
    this->CoilSection = { settings.coil_radius, settings.coil_radius };
    this->NucleicSection = { settings.nucleic_radius, settings.nucleic_radius };
    this->ArrowWidth = settings.arrow_width_factor * this->StrandSection.half_width;
  }

  /// Whether residue i is the last of a strand, where its arrowhead ends. Strands shorter than
  /// two residues were made coil, so a strand residue followed by no strand is one.
  bool is_arrow_tip(std::size_t i) const
  {
    return this->Styles[i] == RibbonStyle::Strand &&
      (i + 1 == this->Styles.size() || this->Styles[i + 1] != RibbonStyle::Strand);
  }

  Section at(double t) const
  {
    const std::size_t n = this->Styles.size();
    if (n == 1)
    {
      return this->base(0);
    }
    t = std::min(std::max(t, 0.0), static_cast<double>(n - 1));
    const std::size_t i = std::min(static_cast<std::size_t>(t), n - 2);
    const double u = t - static_cast<double>(i);
    if (this->is_arrow_tip(i + 1))
    {
      return this->arrow(u);
    }
    // After an arrowhead's tip the section starts from the tip's (coil) section.
    const Section from = this->is_arrow_tip(i) ? this->CoilSection : this->base(i);
    return lerp(from, this->base(i + 1), u * u * (3.0 - 2.0 * u));
  }

private:
  Section base(std::size_t i) const
  {
    switch (this->Styles[i])
    {
      case RibbonStyle::Helix:
        return this->HelixSection;
      case RibbonStyle::Strand:
        return this->StrandSection;
      case RibbonStyle::NucleicAcid:
        return this->NucleicSection;
      default:
        return this->CoilSection;
    }
  }

  /// The arrowhead over the strand's last residue interval, u in [0, 1]: widening to the arrow
  /// width over [0, shoulder], then tapering linearly to the coil section at u = 1.
  Section arrow(double u) const
  {
    Section section;
    const double strand = this->StrandSection.half_width;
    section.half_width = u < this->Shoulder
      ? strand + (this->ArrowWidth - strand) * u / this->Shoulder
      : this->ArrowWidth +
        (this->CoilSection.half_width - this->ArrowWidth) * (u - this->Shoulder) /
          (1.0 - this->Shoulder);
    section.half_thickness = this->StrandSection.half_thickness +
      u * (this->CoilSection.half_thickness - this->StrandSection.half_thickness);
    return section;
  }

  std::vector<RibbonStyle> Styles;
  double Shoulder;
  Section HelixSection, StrandSection, CoilSection, NucleicSection;
  double ArrowWidth = 0;
};

/// A run of residues [first, first + count) of one segment, in local indices.
struct ResidueRun
{
  std::size_t first = 0;
  std::size_t count = 0;
};

/// The helices of at least min_cylinder_residues residues.
std::vector<ResidueRun> cylinder_runs(const std::vector<RibbonStyle>& styles)
{
  std::vector<ResidueRun> runs;
  for (std::size_t i = 0; i < styles.size();)
  {
    std::size_t end = i;
    while (end < styles.size() && styles[end] == RibbonStyle::Helix)
    {
      ++end;
    }
    if (end - i >= min_cylinder_residues)
    {
      runs.push_back({ i, end - i });
    }
    i = std::max(end, i + 1);
  }
  return runs;
}

/// The styles of a segment's residues as their codes give them.
std::vector<RibbonStyle> coded_styles(const std::vector<RibbonResidue>& residues,
                                      const RibbonSegment& segment)
{
  std::vector<RibbonStyle> styles(segment.residue_count);
  for (std::size_t i = 0; i < styles.size(); ++i)
  {
    const RibbonResidue& residue = residues[segment.first_residue + i];
    styles[i] = ribbon_style(residue.secondary_structure, residue.nucleotide);
  }
  return styles;
}

/// The styles a segment is drawn with: lone residues and one-residue strands are coil, and so
/// are helices when they are drawn as cylinders (the tube then runs up to the cylinder's ends).
std::vector<RibbonStyle> drawn_styles(const std::vector<RibbonStyle>& styles,
                                      bool helix_as_cylinder)
{
  const std::size_t n = styles.size();
  std::vector<RibbonStyle> drawn = styles;
  for (std::size_t i = 0; i < n; ++i)
  {
    const bool lone_strand = styles[i] == RibbonStyle::Strand &&
      (i == 0 || styles[i - 1] != RibbonStyle::Strand) &&
      (i + 1 == n || styles[i + 1] != RibbonStyle::Strand);
    const bool helix_drawn_apart = helix_as_cylinder && styles[i] == RibbonStyle::Helix;
    if ((n == 1 && styles[i] != RibbonStyle::NucleicAcid) || lone_strand || helix_drawn_apart)
    {
      drawn[i] = RibbonStyle::Coil;
    }
  }
  return drawn;
}

/// Per residue, the unit side (width) direction of the ribbon: the carbonyl O's direction
/// perpendicular to the tangent, else the curve's binormal, flips removed, gaps carried over.
std::vector<Vec> residue_sides(const std::vector<RibbonResidue>& residues, std::size_t first,
                               const std::vector<Vec>& atoms, const std::vector<Vec>& tangents)
{
  const std::size_t n = atoms.size();
  std::vector<Vec> sides(n, Vec::Zero());
  std::vector<char> known(n, 0);
  Vec previous = Vec::Zero();
  for (std::size_t i = 0; i < n; ++i)
  {
    Vec guide = Vec::Zero();
    const auto& oxygen = residues[first + i].carbonyl_oxygen;
    if (oxygen)
    {
      const Vec o = to_vec(*oxygen) - atoms[i];
      guide = o - o.dot(tangents[i]) * tangents[i];
    }
    else if (i > 0 && i + 1 < n)
    {
      guide = tangents[i].cross(atoms[i - 1] + atoms[i + 1] - 2.0 * atoms[i]);
    }
    if (guide.norm() > min_guide_length)
    {
      // Consecutive peptide planes of a strand point alternately up and down: keep one side.
      sides[i] = previous.dot(guide) < 0 ? Vec(-guide.normalized()) : Vec(guide.normalized());
      previous = sides[i];
      known[i] = 1;
    }
  }
  // Residues without a direction of their own (a straight stretch, a chain end without O)
  // take their neighbour's; a chain straight throughout gets any side.
  std::size_t start =
    static_cast<std::size_t>(std::find(known.begin(), known.end(), 1) - known.begin());
  if (start == n)
  {
    start = 0;
    sides[0] = any_perpendicular(tangents[0]);
  }
  for (std::size_t i = start; i-- > 0;)
  {
    sides[i] = carry_over(sides[i + 1], tangents[i]);
  }
  for (std::size_t i = start + 1; i < n; ++i)
  {
    if (!known[i])
    {
      sides[i] = carry_over(sides[i - 1], tangents[i]);
    }
  }
  return sides;
}

Vec unit_or(const Vec& v, const Vec& fallback)
{
  const double length = v.norm();
  return length > 1e-12 ? Vec(v / length) : fallback;
}

/// The straight axis of a helix of at least min_cylinder_residues Cα, as the ends of the
/// cylinder: the least-squares line through local axis points, each the centre of the circle
/// through three consecutive Cα seen along a first estimate of the axis (the sum of cross
/// products of consecutive bisectors, which point at the axis). Both are exact for an ideal
/// helix of any pitch and radius; a line fit of the Cα themselves is not for short helices.
/// The cylinder spans the projections of the first and last Cα.
std::array<Vec, 2> helix_axis(const std::vector<Vec>& atoms, const ResidueRun& run)
{
  const std::size_t first = run.first;
  const std::size_t last = run.first + run.count - 1;
  const Vec along = atoms[last] - atoms[first];
  const auto bisector = [&](std::size_t i) {
    return Vec(atoms[i - 1] + atoms[i + 1] - 2.0 * atoms[i]);
  };
  Vec rough = Vec::Zero();
  for (std::size_t i = first + 1; i + 1 < last; ++i)
  {
    rough += bisector(i).cross(bisector(i + 1));
  }
  rough = unit_or(rough.dot(along) < 0 ? Vec(-rough) : rough, unit_or(along, Vec::UnitX()));
  std::vector<Vec> axis_points;
  for (std::size_t i = first + 1; i < last; ++i)
  {
    // The circumcentre of the three atoms seen along the axis, relative to the middle one.
    const Vec before = atoms[i - 1] - atoms[i];
    const Vec after = atoms[i + 1] - atoms[i];
    const Vec a_across = before - before.dot(rough) * rough;
    const Vec b_across = after - after.dot(rough) * rough;
    const Vec normal = a_across.cross(b_across);
    if (normal.squaredNorm() > 1e-12)
    {
      axis_points.push_back(
        atoms[i] +
        (a_across.squaredNorm() * b_across - b_across.squaredNorm() * a_across).cross(normal) /
          (2.0 * normal.squaredNorm()));
    }
  }
  Vec centre = Vec::Zero();
  Vec direction = rough;
  if (axis_points.size() >= 2)
  {
    for (const Vec& p : axis_points)
    {
      centre += p;
    }
    centre /= static_cast<double>(axis_points.size());
    Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
    for (const Vec& p : axis_points)
    {
      scatter += (p - centre) * (p - centre).transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
    direction = solver.eigenvectors().col(2);
    direction = direction.dot(along) < 0 ? Vec(-direction) : direction;
  }
  else
  {
    for (std::size_t i = first; i <= last; ++i)
    {
      centre += atoms[i];
    }
    centre /= static_cast<double>(run.count);
  }
  double start = (atoms[first] - centre).dot(direction);
  double end = (atoms[last] - centre).dot(direction);
  if (end - start < 1e-3) // a helix folded onto itself: keep a short cylinder, never a flat one
  {
    const double middle = 0.5 * (start + end);
    start = middle - 0.5;
    end = middle + 0.5;
  }
  return { centre + start * direction, centre + end * direction };
}

/// A part of a segment to mesh: a tube over samples [first_sample, last_sample] or the cylinder
/// of the helix `run` between the points `axis`.
struct PiecePlan
{
  RibbonPiece::Kind kind = RibbonPiece::Kind::Tube;
  std::size_t first_sample = 0;
  std::size_t last_sample = 0;
  ResidueRun run;
  std::array<Vec, 2> axis;
};

/// A segment's centre line and what to mesh along it. Slopes are the sections' rates of change
/// per Å of arc length (they tilt the normals of a tapering ribbon).
struct SegmentCurve
{
  std::vector<RibbonSample> samples;
  std::vector<double> width_slope;
  std::vector<double> thickness_slope;
  std::vector<PiecePlan> pieces;
};

/// The sample parameters of a segment of n residues: `subdivisions` per residue interval, plus
/// one at the shoulder of each arrowhead. Sets residue_sample[i] to the sample at residue i.
std::vector<double> sample_parameters(const SectionProfile& profile, std::size_t n,
                                      int subdivisions, double shoulder,
                                      std::vector<std::size_t>& residue_sample)
{
  std::vector<double> parameters;
  parameters.reserve((n - 1) * subdivisions + n);
  residue_sample.assign(n, 0);
  for (std::size_t i = 0; i + 1 < n; ++i)
  {
    residue_sample[i] = parameters.size();
    for (int k = 0; k < subdivisions; ++k)
    {
      parameters.push_back(static_cast<double>(i) + static_cast<double>(k) / subdivisions);
      if (k == 0 && profile.is_arrow_tip(i + 1))
      {
        parameters.push_back(static_cast<double>(i) + shoulder);
      }
    }
  }
  residue_sample[n - 1] = parameters.size();
  parameters.push_back(static_cast<double>(n - 1));
  return parameters;
}

/// Fills one sample at local parameter t: position, frame, section and its slopes.
void fill_sample(const NaturalCubicSpline& path, const NaturalCubicSpline& side_path,
                 const SectionProfile& profile, std::size_t n, double t, Vec& tangent, Vec& side,
                 RibbonSample& sample, double& width_slope, double& thickness_slope)
{
  const Vec velocity = path.derivative(t);
  const double speed = velocity.norm();
  tangent = unit_or(velocity, tangent);
  const Vec guide = side_path.value(t);
  const Vec across = guide - guide.dot(tangent) * tangent;
  const Vec previous_side = side;
  side = across.norm() > 1e-6 ? Vec(across.normalized()) : carry_over(previous_side, tangent);
  if (side.dot(previous_side) < 0)
  {
    side = -side;
  }
  sample.position = to_array(path.value(t));
  sample.tangent = to_array(tangent);
  sample.side = to_array(side);
  sample.normal = to_array(tangent.cross(side));
  const Section section = profile.at(t);
  sample.half_width = section.half_width;
  sample.half_thickness = section.half_thickness;
  const double low = std::max(t - slope_step, 0.0);
  const double high = std::min(t + slope_step, static_cast<double>(n - 1));
  width_slope = thickness_slope = 0;
  if (high > low && speed > 1e-12)
  {
    const Section before = profile.at(low);
    const Section after = profile.at(high);
    width_slope = (after.half_width - before.half_width) / ((high - low) * speed);
    thickness_slope = (after.half_thickness - before.half_thickness) / ((high - low) * speed);
  }
}

/// Splits a segment into tube pieces and helix cylinders.
std::vector<PiecePlan> plan_pieces(const std::vector<ResidueRun>& cylinders,
                                   const std::vector<std::size_t>& residue_sample,
                                   const std::vector<Vec>& atoms)
{
  const std::size_t n = atoms.size();
  std::vector<PiecePlan> pieces;
  std::size_t start = 0; // the residue where the next tube begins
  for (const ResidueRun& run : cylinders)
  {
    if (run.first > start)
    {
      pieces.push_back(
        { RibbonPiece::Kind::Tube, residue_sample[start], residue_sample[run.first], {}, {} });
    }
    pieces.push_back({ RibbonPiece::Kind::Cylinder, 0, 0, run, helix_axis(atoms, run) });
    start = run.first + run.count - 1;
  }
  if (n == 1 || start + 1 < n)
  {
    pieces.push_back(
      { RibbonPiece::Kind::Tube, residue_sample[start], residue_sample[n - 1], {}, {} });
  }
  return pieces;
}

SegmentCurve build_curve(const std::vector<RibbonResidue>& residues, const RibbonSegment& segment,
                         std::size_t segment_index, int subdivisions, const RibbonParams& settings)
{
  const std::size_t n = segment.residue_count;
  const std::size_t first = segment.first_residue;
  // The shoulder: a tenth of a residue, or half a sample step when those are shorter, so it
  // always falls strictly between two regular samples.
  const double shoulder = std::min(0.1, 0.5 / subdivisions);
  const std::vector<RibbonStyle> coded = coded_styles(residues, segment);
  const SectionProfile profile(drawn_styles(coded, settings.helix_as_cylinder), settings, shoulder);
  std::vector<Vec> atoms(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    atoms[i] = to_vec(residues[first + i].trace);
  }
  const NaturalCubicSpline path(atoms);
  const Vec chord = n > 1 ? unit_or(atoms[1] - atoms[0], Vec::UnitX()) : Vec(Vec::UnitX());
  std::vector<Vec> tangents(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    tangents[i] = unit_or(path.derivative(static_cast<double>(i)), i > 0 ? tangents[i - 1] : chord);
  }
  const NaturalCubicSpline side_path(residue_sides(residues, first, atoms, tangents));

  std::vector<std::size_t> residue_sample;
  const std::vector<double> parameters =
    sample_parameters(profile, n, subdivisions, shoulder, residue_sample);
  SegmentCurve curve;
  curve.samples.resize(parameters.size());
  curve.width_slope.resize(parameters.size());
  curve.thickness_slope.resize(parameters.size());
  Vec tangent = chord;
  Vec side = Vec::Zero(); // no previous side yet: the first sample takes its own as it is
  for (std::size_t k = 0; k < parameters.size(); ++k)
  {
    const double t = parameters[k];
    RibbonSample& sample = curve.samples[k];
    sample.segment = segment_index;
    sample.parameter = static_cast<double>(first) + t;
    sample.residue = first + std::min(static_cast<std::size_t>(t + 0.5), n - 1);
    fill_sample(path, side_path, profile, n, t, tangent, side, sample, curve.width_slope[k],
                curve.thickness_slope[k]);
  }
  const std::vector<ResidueRun> cylinders =
    settings.helix_as_cylinder && n > 1 ? cylinder_runs(coded) : std::vector<ResidueRun>{};
  curve.pieces = plan_pieces(cylinders, residue_sample, atoms);
  return curve;
}

/// One cross-section to mesh: an ellipse with semi-axes a (along side) and b (along normal)
/// around `centre`, changing along the curve at rates a_slope, b_slope per Å.
struct Ring
{
  Vec centre, tangent, side, normal;
  double a = 0, b = 0, a_slope = 0, b_slope = 0;
  std::size_t residue = 0;
};

Ring ring_of(const RibbonSample& sample, double width_slope, double thickness_slope)
{
  return {
    to_vec(sample.position), to_vec(sample.tangent), to_vec(sample.side), to_vec(sample.normal),
    sample.half_width,       sample.half_thickness,  width_slope,         thickness_slope,
    sample.residue
  };
}

/// Steps of a half-ellipsoid end cap from the last ring to the pole.
int cap_steps(int sides)
{
  return std::max(1, sides / 4);
}

std::size_t piece_rings(std::size_t main_rings, int sides)
{
  return main_rings + 2 * static_cast<std::size_t>(cap_steps(sides) - 1);
}

/// Writes one closed piece into preallocated mesh arrays: a pole, the start cap's rings, the
/// main rings, the end cap's rings and a pole; then the triangles between them.
class ClosedSweepWriter
{
public:
  ClosedSweepWriter(RibbonMesh& mesh, const std::vector<RibbonResidue>& residues,
                    const RibbonPiece& piece, int sides)
    : Mesh(mesh)
    , Residues(residues)
    , Piece(piece)
    , Sides(sides)
    , Next(piece.first_vertex)
  {
    for (int j = 0; j < sides; ++j)
    {
      this->Cosines.push_back(std::cos(2.0 * pi * j / sides));
      this->Sines.push_back(std::sin(2.0 * pi * j / sides));
    }
  }

  /// Writes the piece; `ring_vertex(k, v)` learns where main ring k starts. Cap depths in Å.
  template<typename RingVertex>
  void write(const std::vector<Ring>& rings, double start_depth, double end_depth,
             RingVertex&& ring_vertex)
  {
    const int steps = cap_steps(this->Sides);
    this->cap_point(rings.front(), start_depth, -1.0);
    for (int q = steps - 1; q >= 1; --q)
    {
      this->cap_ring(rings.front(), start_depth, -1.0, 0.5 * pi * q / steps);
    }
    for (std::size_t k = 0; k < rings.size(); ++k)
    {
      ring_vertex(k, this->Next);
      this->ring(rings[k]);
    }
    for (int q = 1; q < steps; ++q)
    {
      this->cap_ring(rings.back(), end_depth, 1.0, 0.5 * pi * q / steps);
    }
    this->cap_point(rings.back(), end_depth, 1.0);
    this->triangulate(piece_rings(rings.size(), this->Sides));
  }

private:
  void vertex(const Vec& position, const Vec& normal, std::size_t residue)
  {
    const std::size_t v = this->Next++;
    const Vec unit = normal.normalized();
    for (int c = 0; c < 3; ++c)
    {
      this->Mesh.points[3 * v + c] = position[c];
      this->Mesh.normals[3 * v + c] = unit[c];
    }
    this->Mesh.vertex_residue_id[v] = this->Residues[residue].id;
    this->Mesh.vertex_secondary_structure[v] = this->Residues[residue].secondary_structure;
  }

  /// A cross-section; the normal of the swept ellipse p = c + a cos θ S + b sin θ N is
  /// ∂p/∂θ × ∂p/∂s = b cos θ S + a sin θ N − (a b' sin² θ + a' b cos² θ) T (s the arc length),
  /// which leans forward where the section narrows, as on an arrowhead.
  void ring(const Ring& r)
  {
    for (int j = 0; j < this->Sides; ++j)
    {
      const double c = this->Cosines[j], s = this->Sines[j];
      const Vec position = r.centre + r.a * c * r.side + r.b * s * r.normal;
      const Vec normal = r.b * c * r.side + r.a * s * r.normal -
        (r.a * r.b_slope * s * s + r.a_slope * r.b * c * c) * r.tangent;
      this->vertex(position, normal, r.residue);
    }
  }

  /// A ring of the half-ellipsoid cap with semi-axes a, b and `depth` at latitude phi, on the
  /// side `sign` (+1: beyond the end, -1: before the start).
  void cap_ring(const Ring& r, double depth, double sign, double phi)
  {
    const double cp = std::cos(phi), sp = std::sin(phi);
    for (int j = 0; j < this->Sides; ++j)
    {
      const double c = this->Cosines[j], s = this->Sines[j];
      const Vec position =
        r.centre + cp * (r.a * c * r.side + r.b * s * r.normal) + sign * depth * sp * r.tangent;
      const Vec normal =
        (cp * c / r.a) * r.side + (cp * s / r.b) * r.normal + (sign * sp / depth) * r.tangent;
      this->vertex(position, normal, r.residue);
    }
  }

  /// The cap's pole.
  void cap_point(const Ring& r, double depth, double sign)
  {
    this->vertex(r.centre + sign * depth * r.tangent, sign * r.tangent, r.residue);
  }

  void triangulate(std::size_t ring_count)
  {
    const std::int64_t first = static_cast<std::int64_t>(this->Piece.first_vertex);
    const std::int64_t sides = this->Sides;
    const std::int64_t end_pole = first + 1 + static_cast<std::int64_t>(ring_count) * sides;
    const auto at = [&](std::size_t ring, std::int64_t j) {
      return first + 1 + static_cast<std::int64_t>(ring) * sides + (j == sides ? 0 : j);
    };
    std::size_t t = 3 * this->Piece.first_triangle;
    const auto emit = [&](std::int64_t a, std::int64_t b, std::int64_t c) {
      this->Mesh.triangles[t++] = a;
      this->Mesh.triangles[t++] = b;
      this->Mesh.triangles[t++] = c;
    };
    for (std::int64_t j = 0; j < sides; ++j)
    {
      emit(first, at(0, j + 1), at(0, j));
    }
    for (std::size_t r = 0; r + 1 < ring_count; ++r)
    {
      for (std::int64_t j = 0; j < sides; ++j)
      {
        emit(at(r, j), at(r, j + 1), at(r + 1, j + 1));
        emit(at(r, j), at(r + 1, j + 1), at(r + 1, j));
      }
    }
    for (std::int64_t j = 0; j < sides; ++j)
    {
      emit(at(ring_count - 1, j), at(ring_count - 1, j + 1), end_pole);
    }
  }

  RibbonMesh& Mesh;
  const std::vector<RibbonResidue>& Residues;
  const RibbonPiece& Piece;
  int Sides;
  std::size_t Next;
  std::vector<double> Cosines, Sines;
};

/// The rings of a helix cylinder: one per residue, evenly spaced between the axis' ends.
std::vector<Ring> cylinder_rings(const PiecePlan& plan, std::size_t first_residue, double radius)
{
  const Vec tangent = unit_or(plan.axis[1] - plan.axis[0], Vec::UnitX());
  const Vec side = any_perpendicular(tangent);
  std::vector<Ring> rings(plan.run.count);
  for (std::size_t j = 0; j < plan.run.count; ++j)
  {
    const double w = static_cast<double>(j) / static_cast<double>(plan.run.count - 1);
    rings[j] = { plan.axis[0] + w * (plan.axis[1] - plan.axis[0]),
                 tangent,
                 side,
                 tangent.cross(side),
                 radius,
                 radius,
                 0,
                 0,
                 first_residue + plan.run.first + j };
  }
  return rings;
}

/// Lists the pieces with their places in the mesh arrays, sizes the arrays and copies the
/// centre line in; returns each piece's plan, and in sample_offset where each segment's samples
/// start in the centre line.
std::vector<const PiecePlan*> lay_out(RibbonMesh& mesh, const std::vector<SegmentCurve>& curves,
                                      int tube_sides, std::vector<std::size_t>& sample_offset)
{
  const std::size_t sides = static_cast<std::size_t>(tube_sides);
  std::vector<const PiecePlan*> plans;
  std::size_t vertices = 0, triangles = 0;
  sample_offset.assign(curves.size() + 1, 0);
  for (std::size_t s = 0; s < curves.size(); ++s)
  {
    sample_offset[s + 1] = sample_offset[s] + curves[s].samples.size();
    for (const PiecePlan& plan : curves[s].pieces)
    {
      const std::size_t main_rings = plan.kind == RibbonPiece::Kind::Tube
        ? plan.last_sample - plan.first_sample + 1
        : plan.run.count;
      const std::size_t rings = piece_rings(main_rings, tube_sides);
      RibbonPiece piece;
      piece.kind = plan.kind;
      piece.segment = s;
      piece.first_vertex = vertices;
      piece.first_triangle = triangles;
      piece.vertex_count = sides * rings + 2;
      piece.triangle_count = 2 * sides * rings;
      vertices += piece.vertex_count;
      triangles += piece.triangle_count;
      mesh.pieces.push_back(piece);
      plans.push_back(&plan);
    }
  }
  mesh.points.resize(3 * vertices);
  mesh.normals.resize(3 * vertices);
  mesh.vertex_residue_id.resize(vertices);
  mesh.vertex_secondary_structure.resize(vertices);
  mesh.triangles.resize(3 * triangles);
  mesh.centre_line.resize(sample_offset.back());
  for (std::size_t s = 0; s < curves.size(); ++s)
  {
    std::copy(curves[s].samples.begin(), curves[s].samples.end(),
              mesh.centre_line.begin() + static_cast<std::ptrdiff_t>(sample_offset[s]));
  }
  return plans;
}

/// Writes one piece into the arrays lay_out() sized; for a tube, also records in the centre
/// line where each sample's ring starts.
void write_piece(RibbonMesh& mesh, const std::vector<RibbonResidue>& residues,
                 const RibbonParams& settings, const RibbonPiece& piece, const PiecePlan& plan,
                 const SegmentCurve& curve, std::size_t sample_offset)
{
  ClosedSweepWriter writer(mesh, residues, piece, settings.tube_sides);
  if (plan.kind == RibbonPiece::Kind::Cylinder)
  {
    const double radius = settings.cylinder_radius;
    // A flat end with a rounded rim: a cap a fifth as deep as the cylinder is wide.
    writer.write(cylinder_rings(plan, mesh.segments[piece.segment].first_residue, radius),
                 0.2 * radius, 0.2 * radius, [](std::size_t, std::size_t) {});
    return;
  }
  std::vector<Ring> rings;
  rings.reserve(plan.last_sample - plan.first_sample + 1);
  for (std::size_t k = plan.first_sample; k <= plan.last_sample; ++k)
  {
    rings.push_back(ring_of(curve.samples[k], curve.width_slope[k], curve.thickness_slope[k]));
  }
  // Round ends: half-ellipsoids as deep as the end section is thin.
  const double start_depth = std::min(rings.front().a, rings.front().b);
  const double end_depth = std::min(rings.back().a, rings.back().b);
  const std::size_t first = sample_offset + plan.first_sample;
  writer.write(rings, start_depth, end_depth, [&](std::size_t k, std::size_t vertex) {
    mesh.centre_line[first + k].first_ring_vertex = static_cast<std::int64_t>(vertex);
  });
}

void check_settings(const RibbonParams& s)
{
  // Shorter lengths leave the sections' normals no digits (a coil radius of 1e-306 Å gave zero
  // normals); longer ones are no ribbon.
  const auto positive = [](double value, const char* name) {
    if (!(value >= shortest_ribbon_length && value <= longest_ribbon_length))
    {
      throw InvalidInput(std::string("ribbon: ") + name + " must be a length in [" +
                         std::to_string(shortest_ribbon_length) + ", " +
                         std::to_string(longest_ribbon_length) + "] Å, not " +
                         std::to_string(value));
    }
  };
  if (s.subdivisions < 1 || s.subdivisions > largest_ribbon_subdivisions)
  {
    throw InvalidInput("ribbon: subdivisions must be in [1, " +
                       std::to_string(largest_ribbon_subdivisions) + "], not " +
                       std::to_string(s.subdivisions));
  }
  if (s.tube_sides < 3 || s.tube_sides > largest_ribbon_tube_sides)
  {
    throw InvalidInput("ribbon: tube_sides must be in [3, " +
                       std::to_string(largest_ribbon_tube_sides) + "], not " +
                       std::to_string(s.tube_sides));
  }
  positive(s.helix_width, "helix_width");
  positive(s.strand_width, "strand_width");
  positive(s.ribbon_thickness, "ribbon_thickness");
  positive(s.coil_radius, "coil_radius");
  positive(s.nucleic_radius, "nucleic_radius");
  positive(s.cylinder_radius, "cylinder_radius");
  positive(s.protein_break_distance, "protein_break_distance");
  positive(s.nucleic_break_distance, "nucleic_break_distance");
  if (!(s.arrow_width_factor >= 1 && s.arrow_width_factor <= 100))
  {
    throw InvalidInput("ribbon: arrow_width_factor must be in [1, 100], not " +
                       std::to_string(s.arrow_width_factor));
  }
}

std::string describe(const std::vector<RibbonResidue>& residues, std::size_t i)
{
  return "residue " + std::to_string(i) + " (id " + std::to_string(residues[i].id) + ", chain " +
    std::to_string(residues[i].chain) + ")";
}

std::vector<int> subdivisions_by_segment(const RibbonParams& settings, std::size_t segments)
{
  if (settings.segment_subdivisions.empty())
  {
    return std::vector<int>(segments, settings.subdivisions);
  }
  if (settings.segment_subdivisions.size() != segments)
  {
    throw InvalidInput("ribbon: segment_subdivisions has " +
                       std::to_string(settings.segment_subdivisions.size()) +
                       " entries but the input has " + std::to_string(segments) + " segments");
  }
  for (std::size_t s = 0; s < segments; ++s)
  {
    if (settings.segment_subdivisions[s] < 1 ||
        settings.segment_subdivisions[s] > largest_ribbon_subdivisions)
    {
      throw InvalidInput("ribbon: segment_subdivisions[" + std::to_string(s) + "] must be in [1, " +
                         std::to_string(largest_ribbon_subdivisions) + "], not " +
                         std::to_string(settings.segment_subdivisions[s]));
    }
  }
  return settings.segment_subdivisions;
}
} // namespace

RibbonStyle ribbon_style(char secondary_structure, bool nucleotide)
{
  if (nucleotide)
  {
    return RibbonStyle::NucleicAcid;
  }
  switch (secondary_structure)
  {
    case 'H':
    case 'G':
    case 'I':
      return RibbonStyle::Helix;
    case 'E':
    case 'B':
      return RibbonStyle::Strand;
    default:
      return RibbonStyle::Coil;
  }
}

std::vector<RibbonSegment> ribbon_segments(const std::vector<RibbonResidue>& residues,
                                           const RibbonParams& settings)
{
  if (!(settings.protein_break_distance > 0) || !(settings.nucleic_break_distance > 0))
  {
    throw InvalidInput("ribbon: the break distances must be positive");
  }
  std::vector<RibbonSegment> segments;
  for (std::size_t i = 0; i < residues.size(); ++i)
  {
    if (!within_limits(residues[i].trace))
    {
      throw InvalidInput("ribbon: " + describe(residues, i) +
                         " has a non-finite Cα/P position or one beyond 1e8 Å");
    }
    bool joined = false;
    if (i > 0)
    {
      const RibbonResidue& previous = residues[i - 1];
      const bool nucleic = residues[i].nucleotide;
      const double limit =
        nucleic ? settings.nucleic_break_distance : settings.protein_break_distance;
      joined = residues[i].chain == previous.chain && nucleic == previous.nucleotide &&
        (to_vec(residues[i].trace) - to_vec(previous.trace)).norm() <= limit;
    }
    if (joined)
    {
      ++segments.back().residue_count;
    }
    else
    {
      segments.push_back({ i, 1 });
    }
  }
  return segments;
}

RibbonMesh ribbon_mesh(const std::vector<RibbonResidue>& residues, const RibbonParams& settings,
                       const ParallelFor& parallel_for)
{
  RibbonMesh mesh;
  ribbon_mesh(residues, settings, parallel_for, mesh);
  return mesh;
}

void ribbon_mesh(const std::vector<RibbonResidue>& residues, const RibbonParams& settings,
                 const ParallelFor& parallel_for, RibbonMesh& mesh)
{
  check_settings(settings);
  mesh.points.clear();
  mesh.normals.clear();
  mesh.triangles.clear();
  mesh.vertex_residue_id.clear();
  mesh.vertex_secondary_structure.clear();
  mesh.pieces.clear();
  mesh.centre_line.clear();
  mesh.segments = ribbon_segments(residues, settings);
  for (std::size_t i = 0; i < residues.size(); ++i)
  {
    if (residues[i].carbonyl_oxygen && !within_limits(*residues[i].carbonyl_oxygen))
    {
      throw InvalidInput("ribbon: " + describe(residues, i) +
                         " has a non-finite carbonyl O or one beyond 1e8 Å");
    }
  }
  const std::vector<int> subdivisions = subdivisions_by_segment(settings, mesh.segments.size());

  std::vector<SegmentCurve> curves(mesh.segments.size());
  run_parallel(parallel_for, curves.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t s = begin; s < end; ++s)
    {
      curves[s] = build_curve(residues, mesh.segments[s], s, subdivisions[s], settings);
    }
  });

  std::vector<std::size_t> sample_offset;
  const std::vector<const PiecePlan*> plans =
    lay_out(mesh, curves, settings.tube_sides, sample_offset);
  run_parallel(parallel_for, mesh.pieces.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t p = begin; p < end; ++p)
    {
      const std::size_t segment = mesh.pieces[p].segment;
      write_piece(mesh, residues, settings, mesh.pieces[p], *plans[p], curves[segment],
                  sample_offset[segment]);
    }
  });
}

} // namespace mesolens
