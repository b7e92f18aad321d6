// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/io/file_names.h"

#include <algorithm>
#include <cctype>

namespace mesolens {

std::string file_extension(const std::string& path, bool skip_compression)
{
  const auto slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  auto dot = name.find_last_of('.');
  if (skip_compression && dot != std::string::npos && name.substr(dot) == ".gz")
  {
    name.resize(dot);
    dot = name.find_last_of('.');
  }
  return dot == std::string::npos ? std::string() : name.substr(dot + 1);
}

} // namespace mesolens
