// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/cutaway/structured_cutaway.h"

#include "mesolens/common/errors.h"
#include "mesolens/mesh/surface_locator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

namespace mesolens {

namespace {
/// A well-mixed 64-bit key per (seed, molecule) (splitmix64): stable run to run.
std::uint64_t random_key(std::uint64_t seed, std::uint64_t molecule)
{
  std::uint64_t z = seed * 0x9e3779b97f4a7c15ULL + molecule + 0x632be59bd9b4e019ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

void require_fraction(double fraction, const std::string& what)
{
  if (!(fraction >= 0.0 && fraction <= 1.0))
  {
    throw InvalidInput(what + " must be between 0 and 1, not " + std::to_string(fraction));
  }
}

void require_fractions(const CutawayParams& settings)
{
  require_fraction(settings.fraction_hidden, "the fraction hidden");
  for (const auto& [type, fraction] : settings.fraction_by_type)
  {
    require_fraction(fraction, "the fraction hidden of type " + std::to_string(type));
  }
}

double dot(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
} // namespace

double tunable_sigmoid(double n, double k)
{
  if (!(k > -1.0 && k < 1.0))
  {
    throw InvalidInput("the sigmoid's k must lie strictly between -1 and 1, not " +
                       std::to_string(k));
  }
  n = std::clamp(n, -1.0, 1.0);
  return (n - k * n) / (k - 2.0 * k * std::abs(n) + 1.0);
}

bool CutRegion::contains(const std::array<double, 3>& point) const
{
  for (const Plane& plane : this->planes)
  {
    const std::array<double, 3> offset{ point[0] - plane.point[0], point[1] - plane.point[1],
                                        point[2] - plane.point[2] };
    if (dot(offset, plane.normal) >= 0)
    {
      return true;
    }
  }
  for (const Ball& ball : this->balls)
  {
    const std::array<double, 3> offset{ point[0] - ball.centre[0], point[1] - ball.centre[1],
                                        point[2] - ball.centre[2] };
    if (dot(offset, offset) <= ball.radius * ball.radius)
    {
      return true;
    }
  }
  for (const Box& box : this->boxes)
  {
    bool inside = true;
    for (int d = 0; d < 3; ++d)
    {
      inside = inside && point[d] >= box.low[d] && point[d] <= box.high[d];
    }
    if (inside)
    {
      return true;
    }
  }
  return false;
}

StructuredCutaway::StructuredCutaway(const TriangleMesh& structure, PointSpan<const double> centres,
                                     std::vector<int> types, const ParallelFor& parallel_for)
  : Centres(centres.data(), centres.data() + centres.value_count())
  , Types(std::move(types))
{
  if (centres.empty())
  {
    throw InvalidInput("the cutaway needs molecule centres; got none");
  }
  const std::size_t count = centres.size();
  if (!this->Types.empty() && this->Types.size() != count)
  {
    throw InvalidInput("the cutaway got " + std::to_string(this->Types.size()) +
                       " molecule types for " + std::to_string(count) + " molecules");
  }
  if (this->Types.empty())
  {
    this->Types.assign(count, 0);
  }
  for (std::size_t i = 0; i < centres.value_count(); ++i)
  {
    if (!std::isfinite(centres.data()[i]))
    {
      throw InvalidInput("molecule " + std::to_string(i / 3) + " has a non-finite centre");
    }
  }
  const SurfaceLocator locator(structure);
  this->MinimalBarycentric.resize(count);
  this->Triangles.resize(count);
  run_parallel(parallel_for, count, [&](std::size_t begin, std::size_t end) {
    // Molecules next to each other in the input are usually neighbours in space.
    SurfacePoint previous;
    for (std::size_t m = begin; m < end; ++m)
    {
      const SurfacePoint nearest =
        locator.closest_point(centres.point(m), m > begin ? &previous : nullptr);
      previous = nearest;
      const auto& b = nearest.barycentric;
      this->MinimalBarycentric[m] = std::clamp(std::min({ b[0], b[1], b[2] }), 0.0, 1.0 / 3.0);
      this->Triangles[m] = nearest.triangle;
    }
  });
}

std::vector<double> StructuredCutaway::priorities(double k) const
{
  std::vector<double> result(this->molecule_count());
  for (std::size_t m = 0; m < result.size(); ++m)
  {
    result[m] = 0.5 * (tunable_sigmoid(6.0 * this->MinimalBarycentric[m] - 1.0, k) + 1.0);
  }
  return result;
}

std::vector<std::uint8_t> StructuredCutaway::visibility(const CutRegion& cut,
                                                        const CutawayParams& settings,
                                                        PointSpan<const double> centres) const
{
  return this->visibility([&cut](const std::array<double, 3>& p) { return cut.contains(p); },
                          settings, centres);
}

std::vector<std::uint8_t> StructuredCutaway::visibility(
  const std::function<bool(const std::array<double, 3>&)>& inside_cut,
  const CutawayParams& settings, PointSpan<const double> centres) const
{
  require_fractions(settings);
  return this->visibility(this->removal_order(inside_cut, settings, centres), settings);
}

RemovalOrder StructuredCutaway::removal_order(
  const std::function<bool(const std::array<double, 3>&)>& inside_cut,
  const CutawayParams& settings, PointSpan<const double> centres) const
{
  const std::vector<double> priority = this->priorities(settings.k);
  const std::size_t count = this->molecule_count();
  if (!centres.empty() && centres.size() != count)
  {
    throw InvalidInput("the cutaway got " + std::to_string(centres.size()) +
                       " molecule centres for " + std::to_string(count) + " molecules");
  }
  const PointSpan<const double> at =
    centres.empty() ? PointSpan<const double>(this->Centres) : centres;

  // Sort keys made once, smallest first: the priority negated (1 - priority when inverted;
  // none when random; a weighted random key when probabilistic), then the seeded random key,
  // then the index.
  struct Key
  {
    double priority;
    std::uint64_t random;
    std::uint32_t molecule;
    bool operator<(const Key& other) const
    {
      if (this->priority != other.priority)
        return this->priority < other.priority;
      if (this->random != other.random)
        return this->random < other.random;
      return this->molecule < other.molecule;
    }
  };
  std::map<int, std::vector<Key>> inside;
  for (std::size_t m = 0; m < count; ++m)
  {
    if (inside_cut(at.point(m)))
    {
      const std::uint64_t random = random_key(settings.seed, m);
      const double chance = settings.inverted ? 1.0 - priority[m] : priority[m];
      double p = -chance;
      if (settings.random)
      {
        p = 0.0;
      }
      else if (settings.probabilistic)
      {
        // -log(u) / w, smallest first, is u^(1 / w), largest first; w = 0 goes last.
        const double u = (double(random >> 11) + 0.5) * 0x1.0p-53;
        p = chance > 0 ? -std::log(u) / chance : std::numeric_limits<double>::infinity();
      }
      inside[this->Types[m]].push_back({ p, random, static_cast<std::uint32_t>(m) });
    }
  }
  RemovalOrder order;
  order.molecule_count = count;
  for (auto& [type, keys] : inside)
  {
    std::sort(keys.begin(), keys.end());
    std::vector<std::uint32_t>& molecules = order.by_type[type];
    molecules.reserve(keys.size());
    for (const Key& key : keys)
    {
      molecules.push_back(key.molecule);
    }
  }
  return order;
}

std::vector<std::uint8_t> StructuredCutaway::visibility(const RemovalOrder& order,
                                                        const CutawayParams& settings) const
{
  require_fractions(settings);
  if (order.molecule_count != this->molecule_count())
  {
    throw InvalidInput("the removal order is for " + std::to_string(order.molecule_count) +
                       " molecules, not " + std::to_string(this->molecule_count()));
  }
  std::vector<std::uint8_t> visible(order.molecule_count, 1);
  for (const auto& [type, molecules] : order.by_type)
  {
    const auto found = settings.fraction_by_type.find(type);
    const double fraction =
      found != settings.fraction_by_type.end() ? found->second : settings.fraction_hidden;
    const auto hidden = static_cast<std::size_t>(std::llround(fraction * double(molecules.size())));
    for (std::size_t i = 0; i < hidden && i < molecules.size(); ++i)
    {
      visible[molecules[i]] = 0;
    }
  }
  return visible;
}

std::size_t RemovalOrder::in_cut() const
{
  std::size_t count = 0;
  for (const auto& [type, molecules] : this->by_type)
  {
    count += molecules.size();
  }
  return count;
}

} // namespace mesolens
