// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/io/trajectory_file.h"

#include "io/detail/file_checks.h"
#include "io/detail/gromacs_support.h"
#include "mesolens/common/errors.h"
#include "mesolens/io/file_names.h"
#include "io/detail/trajectory_index.h"
#include "io/detail/xtc_frame_check.h"

#include <gromacs/fileio/oenv.h>
#include <gromacs/fileio/trxio.h>
#include <gromacs/trajectory/trajectoryframe.h>

#include <algorithm>
#include <cctype>
#include <cmath>

namespace mesolens {

namespace {
enum class Format
{
  Xtc,
  Trr,
  Gro,
  Unknown,
};

Format format_of(const std::string& path)
{
  const std::string extension = file_extension(path);
  if (extension == "xtc")
  {
    return Format::Xtc;
  }
  if (extension == "trr")
  {
    return Format::Trr;
  }
  if (extension == "gro")
  {
    return Format::Gro;
  }
  return Format::Unknown;
}
} // namespace

struct TrajectoryFile::Impl
{
  std::string Path;
  bool IsXtc = false;
  detail::FrameIndex Index;
  gmx_output_env_t* OutputEnvironment = nullptr;
  t_trxstatus* Status = nullptr;
  t_trxframe Frame{};

  ~Impl()
  {
    this->close();
  }

  void close()
  {
    if (this->Status)
    {
      close_trx(this->Status);
      this->Status = nullptr;
    }
    if (this->Frame.x)
    {
      done_frame(&this->Frame);
      this->Frame = t_trxframe{};
    }
    if (this->OutputEnvironment)
    {
      output_env_done(this->OutputEnvironment);
      this->OutputEnvironment = nullptr;
    }
  }

  void close_after_error()
  {
    try
    {
      this->close();
    }
    catch (const FileError&)
    {
      this->Status = nullptr; // GROMACS refused to close it: give it up
    }
  }

  void open_decoder()
  {
    if (this->Status)
    {
      return;
    }
    output_env_init_default(&this->OutputEnvironment);
    clear_trxframe(&this->Frame, TRUE);
    bool opened = false;
    try
    {
      opened = read_first_frame(this->OutputEnvironment, &this->Status, this->Path.c_str(),
                                &this->Frame, TRX_NEED_X);
    }
    catch (const FileError&)
    {
      this->close_after_error();
      throw;
    }
    if (!opened)
    {
      this->close_after_error();
      throw FileError(this->Path + ": GROMACS could not read the first frame");
    }
  }

  void decode(std::size_t frame_index, TrajectoryFrame& out)
  {
    if (this->IsXtc)
    {
      detail::check_xtc_frame(this->Path, this->Index.offsets[frame_index]);
      if (!this->Status && frame_index != 0)
      {
        // Opening the decoder decodes the first frame too.
        detail::check_xtc_frame(this->Path, this->Index.offsets[0]);
      }
    }
    this->open_decoder();
    if (gmx_fio_seek(trx_get_fileio(this->Status), this->Index.offsets[frame_index]) != 0)
    {
      throw FileError(this->Path + ": cannot seek to frame " + std::to_string(frame_index));
    }
    if (!read_next_frame(this->OutputEnvironment, this->Status, &this->Frame) || !this->Frame.bX ||
        this->Frame.natoms != this->Index.atom_count)
    {
      throw FileError(this->Path + ": frame " + std::to_string(frame_index) +
                      " could not be decoded");
    }
    constexpr float angstrom_per_nm = 10.0f;
    const std::size_t n = std::size_t(this->Frame.natoms);
    out.positions.resize(3 * n);
    for (std::size_t i = 0; i < n; ++i)
    {
      for (int k = 0; k < 3; ++k)
      {
        const float value = this->Frame.x[i][k] * angstrom_per_nm;
        if (!std::isfinite(value))
        {
          throw FileError(this->Path + ": frame " + std::to_string(frame_index) + ", atom " +
                          std::to_string(i + 1) + " has a non-finite coordinate");
        }
        out.positions[3 * i + std::size_t(k)] = value;
      }
    }
    out.box = PeriodicBox{};
    if (this->Frame.bBox)
    {
      for (int r = 0; r < 3; ++r)
      {
        for (int c = 0; c < 3; ++c)
        {
          out.box.vectors[std::size_t(r)][std::size_t(c)] =
            double(this->Frame.box[r][c]) * double(angstrom_per_nm);
        }
      }
    }
    out.time_ps = this->Frame.bTime ? double(this->Frame.time) : this->Index.times_ps[frame_index];
    out.step = this->Frame.bStep ? std::int64_t(this->Frame.step) : 0;
  }
};

TrajectoryFile::TrajectoryFile(const std::string& path, IncompleteFrames incomplete)
  : Internal(std::make_unique<Impl>())
{
  detail::require_readable_file(path);
  this->Internal->Path = path;
  switch (format_of(path))
  {
    case Format::Xtc:
      this->Internal->Index = detail::index_xtc(path);
      this->Internal->IsXtc = true;
      break;
    case Format::Trr:
      this->Internal->Index = detail::index_trr(path);
      break;
    case Format::Gro:
      this->Internal->Index = detail::index_gro(path);
      break;
    case Format::Unknown:
      throw FileError(path + ": unknown trajectory format (expected .xtc, .trr or .gro)");
  }
  const detail::FrameIndex& index = this->Internal->Index;
  if (!index.incomplete_tail.empty() && incomplete == IncompleteFrames::Reject)
  {
    throw FileError(path + ": truncated trajectory: " + index.incomplete_tail + "; " +
                    std::to_string(index.offsets.size()) + " complete frames precede it");
  }
  if (index.offsets.empty())
  {
    throw FileError(path + ": the file holds no complete frame");
  }
  detail::install_gromacs_error_handler();
}

TrajectoryFile::~TrajectoryFile() = default;

const std::string& TrajectoryFile::path() const
{
  return this->Internal->Path;
}

std::size_t TrajectoryFile::frame_count() const
{
  return this->Internal->Index.offsets.size();
}

std::size_t TrajectoryFile::atom_count() const
{
  return std::size_t(this->Internal->Index.atom_count);
}

const std::vector<double>& TrajectoryFile::frame_times() const
{
  return this->Internal->Index.times_ps;
}

TrajectoryFrame TrajectoryFile::read_frame(std::size_t index)
{
  if (index >= this->frame_count())
  {
    throw InvalidInput(this->Internal->Path + ": frame " + std::to_string(index) +
                       " requested, the file has " + std::to_string(this->frame_count()));
  }
  TrajectoryFrame frame;
  this->Internal->decode(index, frame);
  return frame;
}

bool TrajectoryFile::has_trajectory_extension(const std::string& path)
{
  return format_of(path) != Format::Unknown;
}

} // namespace mesolens
