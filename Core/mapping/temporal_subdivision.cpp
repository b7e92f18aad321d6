// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/mapping/temporal_subdivision.h"

#include "mesolens/common/errors.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <utility>

namespace mesolens {

namespace {
void check_levels(unsigned levels)
{
  if (levels > max_subdivision_levels)
  {
    throw InvalidInput("temporal subdivision: " + std::to_string(levels) +
                       " refinement levels requested; at most " +
                       std::to_string(max_subdivision_levels) + " are supported");
  }
}

/// Key-frame weights of one value of the sequence at some subdivision level.
using Weights = std::map<std::size_t, double>;

void add_scaled(Weights& sum, const Weights& term, double scale)
{
  for (const auto& entry : term)
  {
    sum[entry.first] += scale * entry.second;
  }
}

/// Evaluates the 4-point scheme symbolically: the value at (level, index) as weights of the key
/// frames. Each level needs only a few indices near the refined frame, so memoizing them makes
/// the cost O(levels) instead of O(4^levels).
class StencilEvaluator
{
public:
  explicit StencilEvaluator(std::size_t key_frame_count)
    : KeyFrameCount(key_frame_count)
  {
  }

  /// index in [-1, n] where n is the number of values at `level`; -1 and n are the reflected
  /// linear extrapolations 2x(0) - x(1) and 2x(n-1) - x(n-2).
  Weights value(unsigned level, std::int64_t index)
  {
    const auto key = std::make_pair(level, index);
    const auto found = this->Memo.find(key);
    if (found != this->Memo.end())
    {
      return found->second;
    }
    Weights result;
    const std::int64_t count = std::int64_t(refined_frame_count(this->KeyFrameCount, level));
    if (index == -1 || index == count)
    {
      const std::int64_t edge = index == -1 ? 0 : count - 1;
      const std::int64_t inner = index == -1 ? 1 : count - 2;
      add_scaled(result, this->value(level, edge), 2.0);
      add_scaled(result, this->value(level, inner), -1.0);
    }
    else if (level == 0)
    {
      result[std::size_t(index)] = 1.0;
    }
    else if (index % 2 == 0)
    {
      result = this->value(level - 1, index / 2);
    }
    else
    {
      const std::int64_t m = (index - 1) / 2;
      const std::array<double, 4> taps = { -1.0 / 16, 9.0 / 16, 9.0 / 16, -1.0 / 16 };
      for (std::int64_t k = 0; k < 4; ++k)
      {
        add_scaled(result, this->value(level - 1, m - 1 + k), taps[std::size_t(k)]);
      }
    }
    this->Memo.emplace(key, result);
    return result;
  }

private:
  std::size_t KeyFrameCount;
  std::map<std::pair<unsigned, std::int64_t>, Weights> Memo;
};
} // namespace

std::size_t refined_frame_count(std::size_t key_frame_count, unsigned levels)
{
  check_levels(levels);
  if (key_frame_count == 0)
  {
    throw InvalidInput("temporal subdivision needs at least one key frame");
  }
  const std::size_t intervals = key_frame_count - 1;
  const std::size_t factor = std::size_t(1) << levels;
  if (intervals > (std::numeric_limits<std::size_t>::max() - 1) / factor ||
      intervals * factor > std::size_t(std::numeric_limits<std::int64_t>::max() - 1))
  {
    throw InvalidInput("temporal subdivision: too many key frames for " + std::to_string(levels) +
                       " refinement levels");
  }
  return intervals * factor + 1;
}

std::vector<double> refined_times(const std::vector<double>& key_times, unsigned levels)
{
  const std::size_t count = refined_frame_count(key_times.size(), levels);
  for (std::size_t k = 0; k < key_times.size(); ++k)
  {
    if (!std::isfinite(key_times[k]) || (k > 0 && !(key_times[k] > key_times[k - 1])))
    {
      throw InvalidInput("temporal subdivision: key time " + std::to_string(k) +
                         " is not finite or not after the previous one");
    }
  }
  const std::size_t factor = std::size_t(1) << levels;
  std::vector<double> times(count);
  for (std::size_t j = 0; j < count; ++j)
  {
    const std::size_t key = j / factor;
    const std::size_t remainder = j % factor;
    times[j] = remainder == 0
      ? key_times[key]
      : key_times[key] + double(remainder) / double(factor) * (key_times[key + 1] - key_times[key]);
  }
  return times;
}

std::size_t frame_at_time(const std::vector<double>& times, double time)
{
  if (times.empty())
  {
    throw InvalidInput("frame_at_time: no time steps");
  }
  if (!std::isfinite(time))
  {
    return std::isnan(time) || time < 0 ? 0 : times.size() - 1;
  }
  const double slack = 1e-6 * std::max(1.0, std::abs(time));
  const auto after = std::upper_bound(times.begin(), times.end(), time + slack);
  return after == times.begin() ? 0 : std::size_t(after - times.begin() - 1);
}

SubdivisionStencil subdivision_stencil(std::size_t key_frame_count, unsigned levels,
                                       std::size_t refined_index)
{
  const std::size_t count = refined_frame_count(key_frame_count, levels);
  if (refined_index >= count)
  {
    throw InvalidInput("temporal subdivision: refined frame " + std::to_string(refined_index) +
                       " requested, but " + std::to_string(key_frame_count) + " key frames and " +
                       std::to_string(levels) + " levels give " + std::to_string(count) +
                       " frames");
  }
  StencilEvaluator evaluator(key_frame_count);
  const Weights weights = evaluator.value(levels, std::int64_t(refined_index));
  SubdivisionStencil stencil;
  for (const auto& entry : weights)
  {
    if (entry.second != 0.0) // the dyadic weights cancel exactly where they cancel at all
    {
      stencil.key_frames.push_back(entry.first);
      stencil.weights.push_back(entry.second);
    }
  }
  const std::size_t factor = std::size_t(1) << levels;
  const std::size_t remainder = refined_index % factor;
  stencil.nearest_key_frame = refined_index / factor + (2 * remainder > factor ? 1 : 0);
  return stencil;
}

void combine_frames(const std::vector<const float*>& frames, const std::vector<double>& weights,
                    std::size_t value_count, float* output, const ParallelFor& parallel_for)
{
  if (frames.empty() || frames.size() != weights.size())
  {
    throw InvalidInput("combine_frames: " + std::to_string(frames.size()) + " frames and " +
                       std::to_string(weights.size()) + " weights");
  }
  if (value_count == 0)
  {
    return;
  }
  if (!output || std::find(frames.begin(), frames.end(), nullptr) != frames.end())
  {
    throw InvalidInput("combine_frames: null frame or output");
  }
  run_parallel(parallel_for, value_count, [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v)
    {
      double sum = 0.0;
      for (std::size_t f = 0; f < frames.size(); ++f)
      {
        sum += weights[f] * double(frames[f][v]);
      }
      output[v] = float(sum);
    }
  });
}

void unwrap_to_reference(PointSpan<float> positions, PointSpan<const float> reference,
                         const PeriodicBox& box, const MoleculeGroups* molecules,
                         const ParallelFor& parallel_for)
{
  const std::size_t atom_count = positions.size();
  if (reference.size() != atom_count)
  {
    throw InvalidInput("unwrap_to_reference: " + std::to_string(atom_count) + " positions but " +
                       std::to_string(reference.size()) + " reference positions");
  }
  if (!box.is_set() || atom_count == 0)
  {
    return;
  }
  const MinimumImage minimum_image(box);
  auto displacement = [&](std::size_t i) {
    const float* p = positions[i];
    const float* r = reference[i];
    return std::array<double, 3>{ double(p[0]) - r[0], double(p[1]) - r[1], double(p[2]) - r[2] };
  };
  auto shift_of = [&](const std::array<double, 3>& d) {
    const std::array<double, 3> image = minimum_image(d);
    return std::array<double, 3>{ image[0] - d[0], image[1] - d[1], image[2] - d[2] };
  };
  auto move = [&](std::size_t i, const std::array<double, 3>& shift) {
    if (shift != std::array<double, 3>{ 0, 0, 0 }) // a box vector; otherwise leave bits alone
    {
      for (std::size_t k = 0; k < 3; ++k)
      {
        positions[i][k] = float(double(positions[i][k]) + shift[k]);
      }
    }
  };
  if (!molecules)
  {
    run_parallel(parallel_for, atom_count, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i)
      {
        move(i, shift_of(displacement(i)));
      }
    });
    return;
  }
  if (molecules->of_atom.size() != atom_count)
  {
    throw InvalidInput("unwrap_to_reference: the molecules group " +
                       std::to_string(molecules->of_atom.size()) + " atoms, not " +
                       std::to_string(atom_count));
  }
  // Mean displacement of each molecule (its atoms summed in atom order), one shift per molecule.
  std::vector<std::array<double, 3>> shifts(molecules->count(), { 0, 0, 0 });
  for (std::size_t m = 0; m < molecules->count(); ++m)
  {
    std::array<double, 3> sum{ 0, 0, 0 };
    for (const std::uint32_t i : molecules->atoms_of(m))
    {
      const std::array<double, 3> d = displacement(i);
      sum = { sum[0] + d[0], sum[1] + d[1], sum[2] + d[2] };
    }
    const double n = double(molecules->size_of(m));
    shifts[m] = shift_of({ sum[0] / n, sum[1] / n, sum[2] / n });
  }
  run_parallel(parallel_for, atom_count, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
    {
      move(i, shifts[molecules->of_atom[i]]);
    }
  });
}

} // namespace mesolens
