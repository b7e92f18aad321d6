// SPDX-License-Identifier: GPL-3.0-or-later
// What the trajectory fuzz targets check of the frames they read.
#pragma once

#include "fuzz_input.h"

#include "mesolens/io/trajectory_file.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>

namespace mesolens_fuzz {

/// Opens `path` and reads at most `most` frames, last to first (random access must not depend
/// on the frames before): each of the indexed atom count, every coordinate finite. Throws what
/// TrajectoryFile throws.
inline void read_frames(const std::string& path, bool skip_incomplete, std::size_t most)
{
  mesolens::TrajectoryFile frames(path,
                                  skip_incomplete
                                    ? mesolens::TrajectoryFile::IncompleteFrames::Skip
                                    : mesolens::TrajectoryFile::IncompleteFrames::Reject);
  require(frames.frame_times().size() == frames.frame_count());
  for (std::size_t index = std::min(frames.frame_count(), most); index-- > 0;)
  {
    const mesolens::TrajectoryFrame frame = frames.read_frame(index);
    require(frame.positions.size() == 3 * frames.atom_count());
    for (const float coordinate : frame.positions)
    {
      require(std::isfinite(coordinate));
    }
  }
}

} // namespace mesolens_fuzz
