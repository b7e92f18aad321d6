// SPDX-License-Identifier: GPL-3.0-or-later
// Making molecules whole across periodic boundaries, and keeping them continuous in time.
#pragma once

#include "mesolens/common/point_span.h"
#include "mesolens/molecules/molecule_groups.h"
#include "mesolens/molecules/periodic_box.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace mesolens {

/// Moves atoms by box vectors so that every molecule is whole: each atom is placed at the
/// minimum image of its displacement from the previous atom of the same molecule (atoms of a
/// molecule are contiguous or not; order within the molecule is file order; ids any values).
/// Correct whenever consecutive atoms of a molecule are closer than half the shortest box height,
/// which holds for lipids, proteins and nucleic acids in any sensible box. No-op when the box is
/// not set. positions: one per atom, same length unit as the box. molecule_ids: per atom, any
/// values.
void make_molecules_whole(PointSpan<float> positions, const int* molecule_ids,
                          const PeriodicBox& box);

/// The same for molecules already grouped (group_molecules() of the ids, one entry per atom of
/// `positions`): a trajectory groups its atoms once, not per frame.
void make_molecules_whole(PointSpan<float> positions, const MoleculeGroups& molecules,
                          const PeriodicBox& box);

/// Keeps molecules from jumping across the box between frames: the centroid of each molecule
/// in frame k is moved to the periodic image closest to its centroid in frame k-1. Shifts are
/// remembered per frame, so frames can be requested in any order (frames before the requested
/// one are visited once, in order, the first time). Memory: the molecules that changed image in
/// each frame, plus a full shift table every checkpoint_interval frames, so a long trajectory
/// costs O(molecules x frames / 64 + box crossings), not O(molecules x frames).
class MoleculeContinuity
{
public:
  /// molecule_ids: per atom (any values); the tracker is valid while they stay the same.
  explicit MoleculeContinuity(const std::vector<int>& molecule_ids);

  /// Number of frames whose shifts are known.
  std::size_t known_frames() const
  {
    return this->Changes.size();
  }

  /// Records frame `frame` (must equal known_frames()), whose molecules are already whole, and
  /// applies its shifts to `positions` (one per atom) in place. Throws InvalidInput for another
  /// frame or another number of positions.
  void add_frame(std::size_t frame, PointSpan<float> positions, const PeriodicBox& box);

  /// Applies the remembered shifts of a known frame to whole positions in place. Throws
  /// InvalidInput for a frame not added yet or another number of positions.
  void apply(std::size_t frame, PointSpan<float> positions, const PeriodicBox& box) const;

  /// Frames between two full shift tables.
  static constexpr std::size_t checkpoint_interval = 64;

private:
  /// A molecule whose image shift (in multiples of a, b, c) changed in a frame.
  struct Change
  {
    std::int32_t molecule;
    std::array<std::int32_t, 3> shift;
  };
  std::vector<std::int32_t> shifts_of(std::size_t frame) const;
  void require_atom_count(PointSpan<const float> positions) const;
  void shift_atoms(const std::vector<std::int32_t>& shifts, PointSpan<float> positions,
                   const PeriodicBox& box) const;

  MoleculeGroups Molecules;
  std::vector<std::vector<Change>> Changes;           ///< per frame: new shifts
  std::vector<std::vector<std::int32_t>> Checkpoints; ///< full shifts at frames 0, 64, ...
  std::vector<std::int32_t> CurrentShifts;            ///< shifts of the last known frame
  std::vector<double> PreviousCentroids;              ///< shifted centroids, last known frame
};

/// Whole box-vector shifts (Å, one per point) that gather `centres` (Å) into one
/// piece around their periodic (circular) mean in each fractional coordinate of `box`: for an
/// assembly split by the box's faces, such as a vesicle, that spans less than the box in every
/// direction. The largest group of points keeps its place (an assembly already whole does not
/// move); along an axis that the points spread over (mean resultant length below 0.25, e.g. a
/// flat membrane crossing the box) nothing moves. Zero shifts when the box is not set.
std::vector<std::array<double, 3>> assembly_shifts(PointSpan<const double> centres,
                                                   const PeriodicBox& box);

} // namespace mesolens
