// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/detail/gromacs_support.h"

#include "mesolens/common/errors.h"

#include <mutex>

namespace mesolens {
namespace detail {

namespace {
void throw_gromacs_error(const char* title, const std::string& message, const char*, int)
{
  std::string text = message;
  while (!text.empty() && (text.back() == '\n' || text.back() == ' '))
  {
    text.pop_back();
  }
  throw FileError(std::string("GROMACS: ") + (title ? title : "error") + ": " + text);
}
} // namespace

void install_gromacs_error_handler()
{
  static std::once_flag installed;
  std::call_once(installed, [] { gmx_set_error_handler(&throw_gromacs_error); });
}

} // namespace detail
} // namespace mesolens
