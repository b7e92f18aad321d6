// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: XTC and TRR trajectories through mesolens::TrajectoryFile: the frame check
// (every header scanned before GROMACS decodes anything, which ends the process on malformed
// input) and the decoder, frames read out of order. The first byte chooses: bit 0 TRR (else
// XTC), bit 1 incomplete frames skipped (else refused); the rest is the file. Every input must
// give frames or a mesolens::Error.
#include "fuzz_frames.h"
#include "fuzz_input.h"

#include "mesolens/common/errors.h"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  static const mesolens_fuzz::ScratchFile xtc(".xtc"), trr(".trr");
  mesolens_fuzz::FuzzInput input(data, size);
  const std::uint8_t options = input.byte();
  const std::string& path = ((options & 1) ? trr : xtc).write(input.rest());
  try
  {
    mesolens_fuzz::read_frames(path, options & 2, 6);
  }
  catch (const mesolens::Error&)
  {
  }
  return 0;
}
