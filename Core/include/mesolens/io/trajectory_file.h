// SPDX-License-Identifier: GPL-3.0-or-later
// Random access to the frames of GROMACS trajectories (.xtc, .trr, .gro) through GROMACS'
// own library, with memory O(atoms) however long the file is.
#pragma once

#include "mesolens/molecules/periodic_box.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace mesolens {

/// One decoded frame. Positions are in Å (GROMACS' nm × 10).
struct TrajectoryFrame
{
  std::vector<float> positions; ///< 3 per atom, Å
  PeriodicBox box;              ///< Å; not set when the frame has no box
  double time_ps = 0.0;         ///< simulation time, ps
  std::int64_t step = 0;        ///< MD step
};

/// An open trajectory. Opening scans the frame headers once (without decoding coordinates) to
/// build an offset index and to check that every frame is complete and holds the same number of
/// atoms, so a truncated or corrupt file is reported before any frame is decoded, and GROMACS
/// (which terminates the process on malformed input) only ever sees frames that passed the
/// check. Not thread-safe: one reader per thread.
class TrajectoryFile
{
public:
  /// What to do with an incomplete last frame (a trajectory cut short while being written).
  enum class IncompleteFrames
  {
    Reject, ///< throw FileError naming the frame and the byte offset
    Skip,   ///< index only the complete frames
  };

  /// Opens `path` (.xtc, .trr or .gro, by extension). Throws FileError when the file is missing,
  /// empty, not of that format, truncated (with IncompleteFrames::Reject), or when frames
  /// disagree on the atom count.
  explicit TrajectoryFile(const std::string& path,
                          IncompleteFrames incomplete = IncompleteFrames::Reject);
  ~TrajectoryFile();
  TrajectoryFile(const TrajectoryFile&) = delete;
  TrajectoryFile& operator=(const TrajectoryFile&) = delete;

  const std::string& path() const;
  std::size_t frame_count() const;
  std::size_t atom_count() const;
  /// Time of each frame in ps, read from the headers (no decoding).
  const std::vector<double>& frame_times() const;

  /// Decodes frame `index` (0-based). Throws InvalidInput for an index out of range and
  /// FileError when the frame cannot be decoded or holds non-finite coordinates.
  TrajectoryFrame read_frame(std::size_t index);

  /// True when the path names a format this class reads (.xtc, .trr, .gro).
  static bool has_trajectory_extension(const std::string& path);

private:
  struct Impl;
  std::unique_ptr<Impl> Internal;
};

} // namespace mesolens
