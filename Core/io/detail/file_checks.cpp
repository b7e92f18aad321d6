// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/detail/file_checks.h"

#include "mesolens/common/errors.h"

#include <fstream>
#include <iterator>
#include <sys/stat.h>

namespace mesolens {
namespace detail {

void require_readable_file(const std::string& path)
{
  struct stat info
  {
  };
  if (path.empty())
  {
    throw FileError("no file name was given");
  }
  if (::stat(path.c_str(), &info) != 0)
  {
    throw FileError(path + ": no such file");
  }
  if (!S_ISREG(info.st_mode))
  {
    throw FileError(path + ": not a regular file");
  }
  if (info.st_size == 0)
  {
    throw FileError(path + ": the file is empty");
  }
  std::ifstream probe(path, std::ios::binary);
  if (!probe)
  {
    throw FileError(path + ": cannot be opened for reading");
  }
}

std::string read_file_bytes(const std::string& path)
{
  require_readable_file(path);
  std::ifstream stream(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(stream)), std::istreambuf_iterator<char>());
  if (!stream && !stream.eof())
  {
    throw FileError(path + ": cannot be read");
  }
  return bytes;
}

} // namespace detail
} // namespace mesolens
