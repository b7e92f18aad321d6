// SPDX-License-Identifier: GPL-3.0-or-later
// Frame indexes of GROMACS trajectory files, built from the frame headers alone (private).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace mesolens {
namespace detail {

/// Byte offset, time and atom count of every complete frame, plus what ended the scan.
struct FrameIndex
{
  std::vector<std::int64_t> offsets;
  std::vector<double> times_ps;
  std::int64_t atom_count = -1;
  /// Empty when the file ended cleanly after the last frame; otherwise why the scan stopped
  /// (an incomplete last frame).
  std::string incomplete_tail;
};

/// Scans an XTC file. Throws FileError for a bad magic number or frames whose atom counts differ.
FrameIndex index_xtc(const std::string& path);
/// Scans a TRR file (single or double precision). Same errors as index_xtc().
FrameIndex index_trr(const std::string& path);
/// Scans a (possibly multi-frame) GRO file by lines, checking every atom and box line as
/// GROMACS' reader needs them (it overruns its buffers or ends the process otherwise). Same
/// errors as index_xtc(), and FileError naming the line for one GROMACS could not read.
/// `frame_limit` > 0 stops after that many complete frames.
FrameIndex index_gro(const std::string& path, std::size_t frame_limit = 0);

} // namespace detail
} // namespace mesolens
