// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: XTC and TRR trajectories through mesolens::TrajectoryFile: the frame check
// (every header scanned before GROMACS decodes anything, which ends the process on malformed
// input) and the decoder, frames read out of order. The first byte chooses: bit 0 TRR (else
// XTC), bit 1 incomplete frames skipped (else refused); the rest is the file. Every input must
// give frames or a mesolens::Error.
#include "fuzz_input.h"

#include "mesolens/common/errors.h"
#include "mesolens/io/trajectory_file.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  using mesolens_fuzz::require;
  static const mesolens_fuzz::ScratchFile xtc(".xtc"), trr(".trr");
  mesolens_fuzz::FuzzInput input(data, size);
  const std::uint8_t options = input.byte();
  const std::string& path = ((options & 1) ? trr : xtc).write(input.rest());
  try
  {
    mesolens::TrajectoryFile frames(path,
                                    (options & 2)
                                      ? mesolens::TrajectoryFile::IncompleteFrames::Skip
                                      : mesolens::TrajectoryFile::IncompleteFrames::Reject);
    require(frames.frame_times().size() == frames.frame_count());
    const std::size_t count = std::min<std::size_t>(frames.frame_count(), 6);
    // Last to first: random access must not depend on the frames before.
    for (std::size_t index = count; index-- > 0;)
    {
      const mesolens::TrajectoryFrame frame = frames.read_frame(index);
      require(frame.positions.size() == 3 * frames.atom_count());
      for (const float coordinate : frame.positions)
      {
        require(std::isfinite(coordinate));
      }
    }
  }
  catch (const mesolens::Error&)
  {
  }
  return 0;
}
