// SPDX-License-Identifier: GPL-3.0-or-later
#include "surface/detail/sas_boundary.h"

#include "mesolens/common/errors.h"
#include "mesolens/surface/sphere_union_area.h"

#include "common/detail/grid_cells.h"
#include "surface/detail/power_cell.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <string>
#include <unordered_map>

namespace mesolens {

namespace {
using Vec = Eigen::Vector3d;
constexpr double pi = 3.14159265358979323846;
/// Spheres with more caps than this keep those of their power cell's faces alone: the
/// arrangement grows with the square of the caps, the cell with their number. (Atoms of a
/// protein under a 1.4 Å probe have about 40, where the cell saves little; large probes give
/// hundreds.)
constexpr std::size_t power_cell_caps = 64;

/// The part of the unit sphere of one sphere that a neighbour covers: u . axis > height.
struct Cap
{
  Vec axis = Vec::Zero();
  double height = 0; ///< cosine of the cap's angular radius, in (-1, 1)
  double sine = 0;   ///< of the angular radius: the radius of its circle
  Vec e1 = Vec::Zero(),
      e2 = Vec::Zero(); ///< with axis, a right-handed frame: the circle's azimuth 0 and 90 degrees
  std::uint32_t neighbour = 0; ///< the sphere that covers it

  Vec point(double azimuth) const
  {
    return this->height * this->axis +
      this->sine * (std::cos(azimuth) * this->e1 + std::sin(azimuth) * this->e2);
  }
  /// The boundary's direction of travel at `azimuth` with the uncovered side on the left:
  /// clockwise about the axis (decreasing azimuth).
  Vec tangent(double azimuth) const
  {
    return std::sin(azimuth) * this->e1 - std::cos(azimuth) * this->e2;
  }
  double azimuth_of(const Vec& u) const
  {
    const Vec in_plane = u - this->height * this->axis;
    return std::atan2(in_plane.dot(this->e2), in_plane.dot(this->e1));
  }
};

/// Disjoint sets of 0 .. n - 1 in a buffer reused from sphere to sphere.
struct UnionFind
{
  std::vector<std::size_t>& parent;
  UnionFind(std::vector<std::size_t>& buffer, std::size_t n)
    : parent(buffer)
  {
    parent.resize(n);
    std::iota(parent.begin(), parent.end(), std::size_t(0));
  }
  std::size_t find(std::size_t x)
  {
    while (parent[x] != x)
    {
      parent[x] = parent[parent[x]];
      x = parent[x];
    }
    return x;
  }
  void join(std::size_t a, std::size_t b)
  {
    parent[find(a)] = find(b);
  }
};

/// The index of the lowest set bit of `word` (not zero).
inline std::size_t lowest_bit(std::uint64_t word)
{
#if defined(__GNUC__) || defined(__clang__)
  return std::size_t(__builtin_ctzll(word));
#else
  std::size_t index = 0;
  for (; !(word & 1); word >>= 1)
  {
    ++index;
  }
  return index;
#endif
}

/// Per cap, the set of caps overlapping it, as bits in a buffer reused from sphere to sphere:
/// the sets of two caps intersect in a few words, and members come out in increasing order (the
/// larger caps first).
struct CapSets
{
  std::vector<std::uint64_t>& bits;
  std::size_t count, words;
  CapSets(std::vector<std::uint64_t>& buffer, std::size_t set_count)
    : bits(buffer)
    , count(set_count)
    , words((set_count + 63) / 64)
  {
    bits.assign(set_count * this->words, 0);
  }
  void add(std::size_t set, std::size_t member)
  {
    this->bits[set * this->words + member / 64] |= std::uint64_t(1) << (member % 64);
  }
  /// Calls visit(member) for each member of set a (and of set b, when given) above `after`
  /// (SIZE_MAX: all), in increasing order, until it returns true; whether one did.
  template<typename Visit>
  bool any(std::size_t a, std::size_t b, std::size_t after, Visit&& visit) const
  {
    const std::uint64_t* in_a = &this->bits[a * this->words];
    const std::uint64_t* in_b = b == SIZE_MAX ? nullptr : &this->bits[b * this->words];
    const std::size_t first = after == SIZE_MAX ? 0 : after + 1;
    for (std::size_t w = first / 64; w < this->words; ++w)
    {
      std::uint64_t word = in_b ? in_a[w] & in_b[w] : in_a[w];
      if (w == first / 64)
      {
        word &= ~std::uint64_t(0) << (first % 64);
      }
      while (word)
      {
        const std::size_t member = 64 * w + lowest_bit(word);
        if (visit(member))
        {
          return true;
        }
        word &= word - 1;
      }
    }
    return false;
  }
  /// The number of groups of sets joined by membership (the components of the overlap graph),
  /// with `seen` and `frontier` as buffers.
  std::size_t components(std::vector<std::uint64_t>& seen,
                         std::vector<std::uint64_t>& frontier) const
  {
    seen.assign(this->words, 0);
    frontier.assign(this->words, 0);
    std::size_t groups = 0;
    for (std::size_t start = 0; start < this->count; ++start)
    {
      if (seen[start / 64] >> (start % 64) & 1)
      {
        continue;
      }
      ++groups;
      // Members reached and not yet expanded are in the frontier.
      seen[start / 64] |= std::uint64_t(1) << (start % 64);
      frontier[start / 64] |= std::uint64_t(1) << (start % 64);
      for (std::size_t w = 0; w < this->words;)
      {
        if (frontier[w] == 0)
        {
          ++w;
          continue;
        }
        const std::size_t member = 64 * w + lowest_bit(frontier[w]);
        frontier[w] &= frontier[w] - 1;
        const std::uint64_t* neighbours = &this->bits[member * this->words];
        std::size_t lowest = w;
        for (std::size_t v = 0; v < this->words; ++v)
        {
          const std::uint64_t fresh = neighbours[v] & ~seen[v];
          if (fresh)
          {
            seen[v] |= fresh;
            frontier[v] |= fresh;
            lowest = std::min(lowest, v);
          }
        }
        w = lowest;
      }
    }
    return groups;
  }
};

/// What bounds one sphere's exposed part, on its unit sphere: arcs of caps' circles (azimuths
/// [low, high] in the cap's frame) and the corners between them (unit vectors).
struct UnitPieces
{
  struct Arc
  {
    Cap cap;
    double low = 0, high = 0;
  };
  struct Corner
  {
    std::uint32_t neighbour_a = 0, neighbour_b = 0;
    Vec direction = Vec::Zero();
  };
  /// A closed boundary curve: its share of the turning (geodesic curvature and corners), of
  /// the normal integral, and a point on it.
  struct Loop
  {
    double turning = 0;
    Vec normal_integral = Vec::Zero();
    Vec sample = Vec::Zero();
  };
  std::vector<Arc> arcs;
  std::vector<Corner> corners;
  std::vector<Loop> loops;
  std::size_t degenerate_corners = 0; ///< corners where a third circle passes too

  void clear()
  {
    this->arcs.clear();
    this->corners.clear();
    this->loops.clear();
    this->degenerate_corners = 0;
  }
};

/// Where the circles of two overlapping caps cross (false when they do not: one inside the
/// other, tangent or concentric), into `points`.
bool circle_crossings(const Cap& a, const Cap& b, Vec (&points)[2], double* closeness = nullptr)
{
  // The circles cross when |angle a - angle b| < between (between < a + b holds already).
  const double g = std::clamp(a.axis.dot(b.axis), -1.0, 1.0);
  if (!(g < a.height * b.height + a.sine * b.sine) || 1.0 - g * g <= 1e-24)
  {
    return false;
  }
  // With unit axes |m|^2 = 1 - g^2, and |w|^2 (1 - g^2) = ha^2 + hb^2 - 2 ha hb g.
  const double across = 1.0 - g * g;
  const double inverse = 1.0 / across;
  const double alpha = (a.height - b.height * g) * inverse;
  const double beta = (b.height - a.height * g) * inverse;
  const double rest =
    (across - a.height * a.height - b.height * b.height + 2.0 * a.height * b.height * g) * inverse;
  if (closeness)
  {
    *closeness = rest; // how far from tangent
  }
  if (rest <= 0)
  {
    return false;
  }
  // Unit vectors already (w and m are orthogonal, |w|^2 + gamma^2 |m|^2 = 1), to rounding.
  const double gamma = std::sqrt(rest * inverse);
  const Vec w = alpha * a.axis + beta * b.axis;
  const Vec m = a.axis.cross(b.axis);
  points[0] = w - gamma * m;
  points[1] = w + gamma * m;
  return true;
}

/// An exposed arc of a cap's circle as exposed_unit_area() follows it.
struct ExposedArc
{
  std::size_t cap;
  double start_azimuth, end_azimuth;
  std::size_t start, end; // vertex ids
  double turning;         // its geodesic curvature, then plus the corner at its end
  Vec normal_integral;    // half of x cross dx along it
  Vec middle;
};

/// A cap's place in the order of sort_larger_first().
struct CapKey
{
  double height;
  std::uint32_t neighbour, index;
};

/// Sorts `caps` largest first (the lower height; ties to the lower neighbour), by key and then
/// moved: the caps are large to move, and large probes give hundreds. `keys` and `sorted` are
/// buffers.
void sort_larger_first(std::vector<Cap>& caps, std::vector<CapKey>& keys, std::vector<Cap>& sorted)
{
  keys.clear();
  for (std::size_t k = 0; k < caps.size(); ++k)
  {
    keys.push_back({ caps[k].height, caps[k].neighbour, static_cast<std::uint32_t>(k) });
  }
  std::sort(keys.begin(), keys.end(), [](const CapKey& a, const CapKey& b) {
    return a.height < b.height || (a.height == b.height && a.neighbour < b.neighbour);
  });
  sorted.clear();
  for (const CapKey& key : keys)
  {
    sorted.push_back(caps[key.index]);
  }
  caps.swap(sorted);
}

/// The buffers of exposed_unit_area(), reused from sphere to sphere (their capacity stays).
struct UnitWorkspace
{
  std::vector<Cap> kept;
  std::vector<CapKey> keys;               ///< for sort_larger_first()
  std::vector<Cap> sorted;                ///< for sort_larger_first()
  std::vector<std::uint64_t> overlapping; ///< for CapSets
  std::vector<Vec> vertices;
  std::vector<std::vector<std::pair<double, std::size_t>>> on_circle;
  std::vector<ExposedArc> arcs;
  std::vector<std::uint64_t> seen, frontier; ///< for CapSets::components()
  std::vector<std::size_t> leaving, chains, loop_of_root;
};

/// Resizes a list of lists to `count`, each emptied (keeping their capacity).
template<typename List>
void reset_lists(std::vector<List>& lists, std::size_t count)
{
  if (lists.size() < count)
  {
    lists.resize(count);
  }
  for (std::size_t k = 0; k < count; ++k)
  {
    lists[k].clear();
  }
}

/// Drops the caps inside another cap: they bound nothing (cap b lies in cap a when the angle
/// between their axes plus b's radius is at most a's radius; compared as cosines, without acos).
/// Caps equal to rounding count as nested: those of coincident neighbours, whose circles
/// coincide and have no crossings to trace (h^2 + s^2 may round above 1 = axis . axis).
void drop_nested_caps(std::vector<Cap>& caps, std::vector<Cap>& kept)
{
  constexpr double rounding = 1e-14;
  kept.clear();
  for (const Cap& cap : caps)
  {
    bool inside = false;
    for (const Cap& larger : kept)
    {
      // between <= larger.angle - cap.angle  <=>  cos(between) >= cos(larger - cap)
      // (larger.height <= cap.height: sorted, the larger angular radius first.)
      inside =
        cap.axis.dot(larger.axis) >= larger.height * cap.height + larger.sine * cap.sine - rounding;
      if (inside)
      {
        break;
      }
    }
    if (!inside)
    {
      kept.push_back(cap);
    }
  }
  caps.swap(kept);
}

/// Gives each cap the frame of its circle.
void set_circle_frames(std::vector<Cap>& caps)
{
  for (Cap& cap : caps)
  {
    const Vec helper = std::abs(cap.axis[0]) < 0.9 ? Vec::UnitX() : Vec::UnitY();
    cap.e1 = cap.axis.cross(helper).normalized();
    cap.e2 = cap.axis.cross(cap.e1);
  }
}

/// The overlapping caps (between < angle a + angle b: while a + b < pi, cos(between) >
/// cos(a + b)): they make the union's components, and only they can cover a point of each
/// other's circles.
CapSets overlapping_caps(const std::vector<Cap>& caps, std::vector<std::uint64_t>& buffer)
{
  const std::size_t count = caps.size();
  CapSets overlapping(buffer, count);
  for (std::size_t a = 0; a < count; ++a)
  {
    for (std::size_t b = a + 1; b < count; ++b)
    {
      // Caps whose angular radii add up to more than a half turn always overlap (then the
      // cosine of the sum no longer orders the angles).
      const double g = caps[a].axis.dot(caps[b].axis);
      if (caps[a].height + caps[b].height < 0 ||
          g > caps[a].height * caps[b].height - caps[a].sine * caps[b].sine)
      {
        overlapping.add(a, b);
        overlapping.add(b, a);
      }
    }
  }
  return overlapping;
}

/// The arrangement of the caps' circles on the unit sphere, traced into the exposed part's
/// boundary: its corners, its arcs (each with the corner at its end), and its loops.
class UnitArrangement
{
public:
  UnitArrangement(const std::vector<Cap>& caps, const CapSets& overlapping, UnitPieces* pieces,
                  UnitWorkspace& work)
    : caps_(caps)
    , overlapping_(overlapping)
    , pieces_(pieces)
    , work_(work)
  {
  }

  /// The crossing points of the caps' circles that no other cap covers (work.vertices), and on
  /// each circle their azimuths (work.on_circle).
  void find_corners();
  /// The exposed arcs (work.arcs), travelled clockwise about each axis (uncovered side on the
  /// left), and the whole circles no cap covers; their geodesic curvature into turning(), and
  /// into `normal_integral` half the integral of x cross dx along them (the exposed part's
  /// vector area, the integral of its normal).
  void trace_arcs(Vec& normal_integral);
  /// The turning at each corner, from the arc ending there to the arc leaving it.
  void turn_at_corners();
  /// The arcs joined end to end into loops, with their shares of the turning and the normal
  /// integral.
  void close_loops();

  double turning() const
  {
    return this->turning_;
  }
  std::size_t loops() const
  {
    return this->loops_;
  }

private:
  /// Whether a cap overlapping cap `on` (and cap `also`, unless SIZE_MAX) holds u.
  bool covered(const Vec& u, std::size_t on, std::size_t also = SIZE_MAX) const
  {
    return this->overlapping_.any(on, also, SIZE_MAX, [&](std::size_t c) {
      return u.dot(this->caps_[c].axis) > this->caps_[c].height;
    });
  }

  const std::vector<Cap>& caps_;
  const CapSets overlapping_; ///< by value: a view of the workspace's bits, read in hot loops
  UnitPieces* pieces_;
  UnitWorkspace& work_;
  double turning_ = 0; ///< the boundary's geodesic curvature integrated, plus the corners
  std::size_t loops_ = 0;
};

void UnitArrangement::find_corners()
{
  const std::vector<Cap>& caps = this->caps_;
  UnitPieces* const pieces = this->pieces_;
  std::vector<Vec>& vertices = this->work_.vertices;
  vertices.clear();
  auto& on_circle = this->work_.on_circle;
  reset_lists(on_circle, caps.size());
  for (std::size_t a = 0; a < caps.size(); ++a)
  {
    this->overlapping_.any(a, SIZE_MAX, a, [&](std::size_t b) {
      Vec crossing[2];
      if (!circle_crossings(caps[a], caps[b], crossing))
      {
        return false;
      }
      for (const Vec& u : crossing)
      {
        // A crossing inside a third cap is no corner of the exposed part: exposure along a
        // circle changes only at crossings no other cap covers, so those alone cut the arcs.
        // (A cap holding a point of both circles overlaps both caps.)
        if (this->covered(u, a, b))
        {
          continue;
        }
        // A third circle through the crossing (to rounding): four spheres meet at one point.
        if (pieces && this->overlapping_.any(a, SIZE_MAX, SIZE_MAX, [&](std::size_t c) {
              return c != b && std::abs(u.dot(caps[c].axis) - caps[c].height) < 1e-9;
            }))
        {
          ++pieces->degenerate_corners;
        }
        const std::size_t id = vertices.size();
        vertices.push_back(u);
        if (pieces)
        {
          pieces->corners.push_back({ caps[a].neighbour, caps[b].neighbour, u });
        }
        on_circle[a].emplace_back(caps[a].azimuth_of(u), id);
        on_circle[b].emplace_back(caps[b].azimuth_of(u), id);
      }
      return false;
    });
  }
}

void UnitArrangement::trace_arcs(Vec& normal_integral)
{
  const std::vector<Cap>& caps = this->caps_;
  UnitPieces* const pieces = this->pieces_;
  std::vector<ExposedArc>& arcs = this->work_.arcs;
  arcs.clear();
  for (std::size_t a = 0; a < caps.size(); ++a)
  {
    const Cap& cap = caps[a];
    auto& crossings = this->work_.on_circle[a];
    if (crossings.empty())
    {
      if (!this->covered(cap.point(0.0), a))
      {
        this->turning_ += -cap.height * 2.0 * pi;
        normal_integral += -pi * cap.sine * cap.sine * cap.axis;
        ++this->loops_;
        if (pieces)
        {
          pieces->arcs.push_back({ cap, 0.0, 2.0 * pi });
          pieces->loops.push_back(
            { -cap.height * 2.0 * pi, -pi * cap.sine * cap.sine * cap.axis, cap.point(0.0) });
        }
      }
      continue;
    }
    std::sort(crossings.begin(), crossings.end());
    for (std::size_t k = 0; k < crossings.size(); ++k)
    {
      const double low = crossings[k].first;
      double high = k + 1 < crossings.size() ? crossings[k + 1].first : crossings[0].first + 2 * pi;
      if (high - low <= 0)
      {
        continue;
      }
      if (this->covered(cap.point(0.5 * (low + high)), a))
      {
        continue;
      }
      this->turning_ += -cap.height * (high - low);
      // The vector area of a surface is half the boundary integral of x cross dx.
      const double h = cap.height, r = cap.sine;
      const Vec along_arc = h * r * (std::sin(high) - std::sin(low)) * cap.e1 +
        h * r * (std::cos(low) - std::cos(high)) * cap.e2 - r * r * (high - low) * cap.axis;
      normal_integral += 0.5 * along_arc;
      if (pieces)
      {
        pieces->arcs.push_back({ cap, low, high });
      }
      const std::size_t next = k + 1 < crossings.size() ? k + 1 : 0;
      arcs.push_back({ a, high, low, crossings[next].second, crossings[k].second,
                       -cap.height * (high - low), 0.5 * along_arc,
                       cap.point(0.5 * (low + high)) });
    }
  }
}

void UnitArrangement::turn_at_corners()
{
  std::vector<ExposedArc>& arcs = this->work_.arcs;
  std::vector<std::size_t>& leaving = this->work_.leaving; // per vertex, the first arc leaving it
  leaving.assign(this->work_.vertices.size(), SIZE_MAX);
  for (std::size_t k = 0; k < arcs.size(); ++k)
  {
    if (leaving[arcs[k].start] == SIZE_MAX)
    {
      leaving[arcs[k].start] = k;
    }
  }
  for (ExposedArc& arc : arcs)
  {
    if (leaving[arc.end] == SIZE_MAX)
    {
      continue; // a degenerate crossing (three circles through a point): no corner counted
    }
    const ExposedArc& out = arcs[leaving[arc.end]];
    const Vec& p = this->work_.vertices[arc.end];
    const Vec in_direction = this->caps_[arc.cap].tangent(arc.end_azimuth);
    const Vec out_direction = this->caps_[out.cap].tangent(out.start_azimuth);
    const double corner =
      std::atan2(p.dot(in_direction.cross(out_direction)), in_direction.dot(out_direction));
    this->turning_ += corner;
    arc.turning += corner;
  }
}

void UnitArrangement::close_loops()
{
  const std::vector<ExposedArc>& arcs = this->work_.arcs;
  UnitPieces* const pieces = this->pieces_;
  UnionFind chains(this->work_.chains, this->work_.vertices.size());
  for (const ExposedArc& arc : arcs)
  {
    chains.join(arc.start, arc.end);
  }
  std::vector<std::size_t>& loop_of_root = this->work_.loop_of_root;
  loop_of_root.assign(this->work_.vertices.size(), SIZE_MAX);
  for (const ExposedArc& arc : arcs)
  {
    const std::size_t root = chains.find(arc.start);
    if (loop_of_root[root] == SIZE_MAX)
    {
      loop_of_root[root] = pieces ? pieces->loops.size() : 0;
      ++this->loops_;
      if (pieces)
      {
        pieces->loops.push_back({ 0.0, Vec::Zero(), arc.middle });
      }
    }
    if (pieces)
    {
      UnitPieces::Loop& loop = pieces->loops[loop_of_root[root]];
      loop.turning += arc.turning;
      loop.normal_integral += arc.normal_integral;
    }
  }
}

/// The exposed area of the unit sphere under `caps` (times R^2 by the caller), and in
/// `normal_integral` the integral of the outward unit normal over it (for the volume). With
/// `pieces`, also the arcs and corners that bound it. `caps` sorted by sort_larger_first().
double exposed_unit_area(std::vector<Cap>& caps, Vec& normal_integral, UnitPieces* pieces,
                         UnitWorkspace& work)
{
  normal_integral = Vec::Zero();
  drop_nested_caps(caps, work.kept);
  set_circle_frames(caps);
  if (caps.empty())
  {
    return 4.0 * pi;
  }
  const CapSets overlapping = overlapping_caps(caps, work.overlapping);
  const std::size_t unions = overlapping.components(work.seen, work.frontier);
  UnitArrangement arrangement(caps, overlapping, pieces, work);
  arrangement.find_corners();
  arrangement.trace_arcs(normal_integral);
  arrangement.turn_at_corners();
  arrangement.close_loops();
  // Gauss-Bonnet on the unit sphere: area = 2 pi chi - turning, with chi = loops + 2 - 2 unions
  // (the exposed part and the caps' union share their loops and together make the sphere).
  const double chi = double(arrangement.loops()) + 2.0 - 2.0 * double(unions);
  return std::clamp(2.0 * pi * chi - arrangement.turning(), 0.0, 4.0 * pi);
}

/// The largest radius; throws InvalidInput for lists of different lengths, a non-finite
/// centre or radius, a radius that is not positive, or a centre coordinate or radius beyond
/// largest_sphere_coordinate.
double check_spheres(PointSpan<const double> centres, const std::vector<double>& radii)
{
  const std::size_t n = centres.size();
  if (radii.size() != n)
  {
    throw InvalidInput("the sphere union needs one radius per centre: " + std::to_string(n) +
                       " centres, " + std::to_string(radii.size()) + " radii");
  }
  double largest = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (!std::isfinite(centres[i][0]) || !std::isfinite(centres[i][1]) ||
        !std::isfinite(centres[i][2]) || !std::isfinite(radii[i]) || !(radii[i] > 0))
    {
      throw InvalidInput("sphere " + std::to_string(i) +
                         " has a non-finite centre or a radius that is not positive");
    }
    if (std::abs(centres[i][0]) > largest_sphere_coordinate ||
        std::abs(centres[i][1]) > largest_sphere_coordinate ||
        std::abs(centres[i][2]) > largest_sphere_coordinate || radii[i] > largest_sphere_coordinate)
    {
      throw InvalidInput("sphere " + std::to_string(i) + " lies or reaches beyond " +
                         std::to_string(largest_sphere_coordinate) +
                         " length units from the origin, where the arithmetic has too few "
                         "digits left; move the spheres near the origin");
    }
    largest = std::max(largest, radii[i]);
  }
  return largest;
}

/// The spheres in cubic cells (grid_cell_key()) of the largest diameter: overlapping ones are
/// in neighbouring cells.
struct SphereCells
{
  double cell = 0;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> spheres;

  SphereCells(PointSpan<const double> centres, double largest)
    : cell(2.0 * largest)
  {
    for (std::size_t i = 0; i < centres.size(); ++i)
    {
      this->spheres[grid_cell_key(grid_cell(centres.point(i), this->cell))].push_back(
        static_cast<std::uint32_t>(i));
    }
  }
};

/// Each sphere's pieces of the boundary, the arcs and vertices it reports (those whose other
/// spheres come after it) and its loops, until they are gathered in order.
struct PiecesBySphere
{
  std::vector<std::vector<SasArc>> arcs;
  std::vector<std::vector<SasVertex>> vertices;
  std::vector<std::vector<SasLoop>> loops;
  std::vector<std::size_t> degenerate;

  explicit PiecesBySphere(std::size_t count)
    : arcs(count)
    , vertices(count)
    , loops(count)
    , degenerate(count, 0)
  {
  }
};

/// The spheres and their cells: what each sphere's stage reads.
struct Spheres
{
  PointSpan<const double> centres;
  const std::vector<double>& radii;
  SphereCells cells;
};

/// The buffers one range of spheres reuses.
struct SphereWork
{
  std::vector<Cap> caps;
  std::vector<PowerPlane> planes;
  std::vector<char> bounding;
  PowerCellWork cell_work;
  UnitPieces pieces;
  UnitWorkspace unit;
};

/// The caps that sphere i's neighbours cut from it (into `caps`, unsorted); true when one of
/// them holds it whole (buried: then `caps` is left incomplete).
bool neighbour_caps(std::size_t i, const Spheres& spheres, std::vector<Cap>& caps)
{
  PointSpan<const double> centres = spheres.centres;
  const std::vector<double>& radii = spheres.radii;
  const SphereCells& cells = spheres.cells;
  const Vec c(centres[i][0], centres[i][1], centres[i][2]);
  const double r = radii[i];
  const GridCell home = grid_cell(centres.point(i), cells.cell);
  caps.clear();
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dz = -1; dz <= 1; ++dz)
      {
        const auto found = cells.spheres.find(grid_cell_key(home, dx, dy, dz));
        if (found == cells.spheres.end())
        {
          continue;
        }
        for (const std::uint32_t j : found->second)
        {
          if (j == i)
          {
            continue;
          }
          const double rj = radii[j];
          const Vec offset = Vec(centres[j][0], centres[j][1], centres[j][2]) - c;
          const double d = offset.norm();
          if (d >= r + rj)
          {
            continue; // apart
          }
          // Equal spheres, to rounding, each hold the other (a centre 1e-127 away is absorbed
          // in d + r): of these the first stays.
          if (d + r <= rj && !(d + rj <= r && j > i))
          {
            return true; // inside j
          }
          if (d + rj <= r)
          {
            continue; // j inside this sphere
          }
          Cap cap;
          cap.neighbour = j;
          cap.axis = offset / d;
          cap.height = std::clamp((r * r + d * d - rj * rj) / (2.0 * r * d), -1.0, 1.0);
          cap.sine = std::sqrt(std::max(0.0, 1.0 - cap.height * cap.height));
          caps.push_back(cap);
        }
      }
  return false;
}

/// Keeps the caps of the neighbours bounding the sphere's power cell alone (sorted largest
/// first): only they can bound its exposed part, the sphere's points in its cell. False when
/// the cell holds no point of the sphere (buried).
bool keep_power_cell_caps(SphereWork& work)
{
  std::vector<Cap>& caps = work.caps;
  work.planes.clear();
  for (const Cap& cap : caps)
  {
    work.planes.push_back({ cap.axis, cap.height });
  }
  const int cell = power_cell_faces(work.planes, work.bounding, work.cell_work);
  if (cell == 0)
  {
    return false; // no point of it outside every neighbour
  }
  if (cell == 1)
  {
    std::size_t kept = 0;
    for (std::size_t k = 0; k < caps.size(); ++k)
    {
      if (work.bounding[k])
      {
        caps[kept++] = caps[k];
      }
    }
    caps.resize(kept);
  }
  return true;
}

/// Sphere i's (centre c, radius r) pieces from those of its unit sphere: the arcs and vertices
/// it reports (the lower sphere reports each), and its loops.
void scale_pieces(std::size_t i, const Vec& c, double r, const UnitPieces& pieces,
                  PiecesBySphere& out)
{
  const std::uint32_t self = static_cast<std::uint32_t>(i);
  for (const UnitPieces::Arc& piece : pieces.arcs)
  {
    if (piece.cap.neighbour < self)
    {
      continue; // the lower sphere reports it
    }
    SasArc arc;
    arc.first = self;
    arc.second = piece.cap.neighbour;
    arc.centre = c + r * piece.cap.height * piece.cap.axis;
    arc.axis = piece.cap.axis;
    arc.e1 = piece.cap.e1;
    arc.e2 = piece.cap.e2;
    arc.radius = r * piece.cap.sine;
    arc.start = piece.low;
    arc.span = piece.high - piece.low;
    out.arcs[i].push_back(arc);
  }
  for (const UnitPieces::Corner& corner : pieces.corners)
  {
    if (corner.neighbour_a < self || corner.neighbour_b < self)
    {
      continue;
    }
    SasVertex vertex;
    vertex.spheres = { self, std::min(corner.neighbour_a, corner.neighbour_b),
                       std::max(corner.neighbour_a, corner.neighbour_b) };
    vertex.position = c + r * corner.direction;
    out.vertices[i].push_back(vertex);
  }
  out.degenerate[i] = pieces.degenerate_corners;
  for (const UnitPieces::Loop& loop : pieces.loops)
  {
    out.loops[i].push_back(
      { self, loop.turning, r * r * loop.normal_integral, c + r * loop.sample });
  }
}

/// Sphere i's neighbours (result.neighbours), exposed area and normal integral, and with
/// `with_pieces` the pieces of the boundary on it (into `by_sphere`).
void expose_sphere(std::size_t i, const Spheres& spheres, bool with_pieces, SphereWork& work,
                   SasBoundary& result, PiecesBySphere& by_sphere)
{
  std::vector<Cap>& caps = work.caps;
  bool buried = neighbour_caps(i, spheres, caps);
  // The largest caps first (ties to the lower index): the power cell shrinks fastest, and
  // coverage tests that scan the neighbours find a covering one sooner.
  sort_larger_first(caps, work.unit.keys, work.unit.sorted);
  if (!buried && caps.size() > power_cell_caps)
  {
    buried = !keep_power_cell_caps(work);
  }
  auto& neighbours = result.neighbours[i];
  neighbours.reserve(caps.size());
  for (const Cap& cap : caps)
  {
    neighbours.push_back(cap.neighbour);
  }
  if (buried)
  {
    return;
  }
  const Vec c(spheres.centres[i][0], spheres.centres[i][1], spheres.centres[i][2]);
  const double r = spheres.radii[i];
  Vec normal_integral = Vec::Zero();
  work.pieces.clear();
  const double solid_angle =
    exposed_unit_area(caps, normal_integral, with_pieces ? &work.pieces : nullptr, work.unit);
  result.area[i] = r * r * solid_angle;
  result.normal_integral[i] = r * r * normal_integral;
  if (with_pieces)
  {
    scale_pieces(i, c, r, work.pieces, by_sphere);
  }
}

/// The spheres' pieces side by side in sphere order: their places first, then copied.
void gather_pieces(PiecesBySphere& by_sphere, SasBoundary& result, const ParallelFor& parallel_for)
{
  const std::size_t listed = by_sphere.arcs.size();
  std::vector<std::size_t> arc_at(listed + 1, 0), vertex_at(listed + 1, 0), loop_at(listed + 1, 0);
  for (std::size_t i = 0; i < listed; ++i)
  {
    arc_at[i + 1] = arc_at[i] + by_sphere.arcs[i].size();
    vertex_at[i + 1] = vertex_at[i] + by_sphere.vertices[i].size();
    loop_at[i + 1] = loop_at[i] + by_sphere.loops[i].size();
    result.degenerate_vertices += by_sphere.degenerate[i];
  }
  result.arcs.resize(arc_at[listed]);
  result.vertices.resize(vertex_at[listed]);
  result.loops.resize(loop_at[listed]);
  run_parallel(parallel_for, listed, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
    {
      auto& arcs = by_sphere.arcs[i];
      auto& vertices = by_sphere.vertices[i];
      auto& loops = by_sphere.loops[i];
      std::copy(arcs.begin(), arcs.end(), result.arcs.begin() + arc_at[i]);
      std::copy(vertices.begin(), vertices.end(), result.vertices.begin() + vertex_at[i]);
      std::copy(loops.begin(), loops.end(), result.loops.begin() + loop_at[i]);
      arcs = {};
      vertices = {};
      loops = {};
    }
  });
}
} // namespace

bool uncovered_unit_area(const std::vector<UnitCap>& unit_caps, double& area,
                         Vec& direction_integral)
{
  // Buffers kept per thread: this runs once per cut concave patch.
  thread_local std::vector<Cap> caps;
  thread_local UnitWorkspace work;
  caps.resize(unit_caps.size());
  for (std::size_t k = 0; k < caps.size(); ++k)
  {
    caps[k].axis = unit_caps[k].axis;
    caps[k].height = unit_caps[k].height;
    caps[k].sine = std::sqrt(std::max(0.0, 1.0 - caps[k].height * caps[k].height));
    caps[k].neighbour = static_cast<std::uint32_t>(k);
  }
  // Refused near degeneracy: circles nearly tangent, or a third through their crossing (the
  // arrangement would depend on rounding). A crossing deep inside a fourth cap is no corner
  // whatever the rounding (nor are the crossings of the three circles beside it): allowed, as
  // where the edges of a piece of a concave patch, extended, pass through a torus's cusp that
  // another edge of the piece leaves outside.
  constexpr double near = 1e-9, deep = 1e-7;
  const auto deep_in_fourth = [&](const Vec& u, std::size_t a, std::size_t b, std::size_t c) {
    for (std::size_t d = 0; d < caps.size(); ++d)
    {
      if (d != a && d != b && d != c && u.dot(caps[d].axis) - caps[d].height > deep)
      {
        return true;
      }
    }
    return false;
  };
  for (std::size_t a = 0; a < caps.size(); ++a)
  {
    for (std::size_t b = a + 1; b < caps.size(); ++b)
    {
      Vec crossing[2];
      double closeness = 1;
      const bool cross = circle_crossings(caps[a], caps[b], crossing, &closeness);
      if (std::abs(closeness) < near)
      {
        return false;
      }
      for (std::size_t c = 0; cross && c < caps.size(); ++c)
      {
        for (const Vec& u : crossing)
        {
          if (c != a && c != b && std::abs(u.dot(caps[c].axis) - caps[c].height) < near &&
              !deep_in_fourth(u, a, b, c))
          {
            return false;
          }
        }
      }
    }
  }
  sort_larger_first(caps, work.keys, work.sorted);
  area = exposed_unit_area(caps, direction_integral, nullptr, work);
  return true;
}

SasBoundary sas_boundary(PointSpan<const double> centres, const std::vector<double>& radii,
                         bool with_pieces, const ParallelFor& parallel_for)
{
  const std::size_t n = centres.size();
  const double largest = check_spheres(centres, radii);
  SasBoundary result;
  result.area.assign(n, 0.0);
  result.normal_integral.assign(n, Vec::Zero());
  result.neighbours.assign(n, {});
  PiecesBySphere by_sphere(with_pieces ? n : 0);
  if (n == 0)
  {
    return result;
  }
  const Spheres spheres{ centres, radii, SphereCells(centres, largest) };
  run_parallel(parallel_for, n, [&](std::size_t begin, std::size_t end) {
    SphereWork work; // reused by the spheres of this range
    for (std::size_t i = begin; i < end; ++i)
    {
      expose_sphere(i, spheres, with_pieces, work, result, by_sphere);
    }
  });
  gather_pieces(by_sphere, result, parallel_for);
  return result;
}

} // namespace mesolens
