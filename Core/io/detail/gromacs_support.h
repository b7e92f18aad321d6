// SPDX-License-Identifier: GPL-3.0-or-later
// Private glue to libgromacs (never installed).
#pragma once

#include <cstdint>
#include <string>

struct t_fileio;

// libgromacs 2022 exports these functions but does not install the headers that declare them
// (gromacs/fileio/gmxfio.h, gromacs/utility/fatalerror.h). The CMake configuration checks that
// they link, so a GROMACS that drops them fails at configure time, not at run time.
std::int64_t gmx_fio_ftell(t_fileio* fio);
int gmx_fio_seek(t_fileio* fio, std::int64_t offset);
void gmx_set_error_handler(void (*handler)(const char* title, const std::string& message,
                                           const char* file, int line));

namespace mesolens {
namespace detail {

/// GROMACS ends the process on a fatal error (bad magic number, malformed line). This installs,
/// once per process, a handler that throws mesolens::FileError instead, so a bad file becomes
/// an error message. It replaces GROMACS' default handler for the whole process.
void install_gromacs_error_handler();

} // namespace detail
} // namespace mesolens
