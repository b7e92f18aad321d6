// SPDX-License-Identifier: GPL-3.0-or-later
// Trajectory refinement in time by 4-point interpolatory subdivision (Membrane Mapping,
// Waltemate, Sommer and Botsch, VCBM 2014): x(t+1/2) = (-x(t-1) + 9x(t) + 9x(t+1) - x(t+2))/16.
#pragma once

#include "mesolens/common/parallel_for.h"
#include "mesolens/common/point_span.h"
#include "mesolens/molecules/molecule_groups.h"
#include "mesolens/molecules/periodic_box.h"

#include <cstddef>
#include <vector>

namespace mesolens {

/// Largest number of refinement levels the functions below accept (2^10 - 1 = 1023 frames
/// between two key frames).
constexpr unsigned max_subdivision_levels = 10;

/// Number of frames after `levels` rounds of subdivision of `key_frame_count` key frames:
/// (K - 1)·2^L + 1; 1 for K = 1. Refined frame j·2^L is key frame j.
/// Throws InvalidInput when K = 0, when levels > max_subdivision_levels, or on overflow.
std::size_t refined_frame_count(std::size_t key_frame_count, unsigned levels);

/// The times of the refined frames: linear between consecutive key times, so the refined
/// time of frame j·2^L + r (0 <= r < 2^L) is t_j + r/2^L·(t_{j+1} - t_j). Key times are kept
/// exactly and the times stay increasing even for unevenly spaced key frames; for evenly
/// spaced key times this equals refining the times themselves with the 4-point scheme (which
/// reproduces linear data). key_times: increasing, finite (any unit). Throws InvalidInput when
/// empty, not strictly increasing, not finite, or levels > max_subdivision_levels.
std::vector<double> refined_times(const std::vector<double>& key_times, unsigned levels);

/// The refined frame shown at `time`: the latest one whose time is not after `time` (with a
/// relative slack of 1e-6, so a time read back from the list maps to its own frame), clamped to
/// the first and last frames; NaN gives frame 0. times: increasing, not empty (throws
/// InvalidInput when empty).
std::size_t frame_at_time(const std::vector<double>& times, double time);

/// A refined frame as a fixed linear combination of a few key frames: value = Σ weights[i]·
/// key frame key_frames[i]. key_frames are increasing, weights are non-zero and sum to 1.
/// A key frame gives itself with weight 1; any other frame uses at most 6 key frames (the
/// 4-point basis function has support (-3, 3) in key-frame units).
struct SubdivisionStencil
{
  std::vector<std::size_t> key_frames; ///< key-frame indices, increasing
  std::vector<double> weights;         ///< one per key frame, Σ = 1
  std::size_t nearest_key_frame = 0;   ///< key frame closest in time (ties: the earlier one);
                                       ///< always in key_frames, with a positive weight
};

/// The key frames and weights giving refined frame `refined_index` after `levels` rounds of the
/// 4-point scheme, computed exactly by a memoized recursive evaluation of the scheme (as if it
/// were run on unit impulses), in O(levels) work; a caller reads only these few key frames.
///
/// End rule: the scheme needs x(t-1) and x(t+2); beyond the ends of the sequence being refined
/// (at every level) it uses the reflected linear extrapolations x(-1) = 2x(0) - x(1) and
/// x(n) = 2x(n-1) - x(n-2). Linear motion is therefore reproduced exactly everywhere; cubic
/// motion is reproduced exactly wherever the stencil uses neither the first nor the last key
/// frame (where the extrapolations fold in), e.g. for all refined times in [3, K-4] (key-frame
/// units). With K = 1 every refined frame is that key frame; with K = 2 the refinement is linear
/// interpolation.
///
/// Preconditions (else InvalidInput): key_frame_count >= 1, levels <= max_subdivision_levels,
/// refined_index < refined_frame_count(key_frame_count, levels).
SubdivisionStencil subdivision_stencil(std::size_t key_frame_count, unsigned levels,
                                       std::size_t refined_index);

/// output[v] = Σ_f weights[f]·frames[f][v] for v in [0, value_count), summed in double and
/// rounded to float once (for xyz positions value_count = 3·atoms). A frame with weight 1 alone
/// is copied exactly. `output` may not alias a frame. Throws InvalidInput when frames and
/// weights differ in size, are empty, or a frame or output is null while value_count > 0.
void combine_frames(const std::vector<const float*>& frames, const std::vector<double>& weights,
                    std::size_t value_count, float* output, const ParallelFor& parallel_for = {});

/// Moves atoms of `positions` by whole box vectors to the periodic image closest to the same
/// atoms in `reference`, so an atom that crossed the box between two frames does not jump
/// across it. Without `molecules` each atom moves by the minimum image of its own displacement
/// positions - reference; with them (group_molecules() of the atoms) all atoms of a molecule
/// move by the box vectors that bring the mean displacement of the molecule to its minimum
/// image, so molecules that are whole in both frames stay whole. Correct while atoms
/// (molecules) moved less than half the shortest box height between the two frames.
/// Coordinates not moved stay bit-identical; no-op when the box is not set. positions,
/// reference: one per atom (same length unit as the box, e.g. Å). Throws InvalidInput when
/// they differ in length or `molecules` groups another number of atoms.
void unwrap_to_reference(PointSpan<float> positions, PointSpan<const float> reference,
                         const PeriodicBox& box, const MoleculeGroups* molecules = nullptr,
                         const ParallelFor& parallel_for = {});

} // namespace mesolens
