// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/io/file_names.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>
#include <system_error>

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

std::string topology_beside(const std::string& trajectory)
{
  namespace fs = std::filesystem;
  static const std::array<const char*, 5> topology_extensions = { "gro", "pdb", "cif", "mmcif",
                                                                  "ent" };
  const fs::path path(trajectory);
  std::error_code error;
  for (const char* extension : topology_extensions)
  {
    for (const char* compression : { "", ".gz" })
    {
      fs::path candidate = path;
      candidate.replace_extension(std::string(".") + extension + compression);
      if (candidate != path && fs::is_regular_file(candidate, error))
      {
        return candidate.string();
      }
    }
  }
  const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::string only;
  for (fs::directory_iterator entry(folder, error), end; !error && entry != end;
       entry.increment(error))
  {
    const std::string name = entry->path().string();
    const std::string extension = file_extension(name, true);
    const bool topology =
      std::find_if(topology_extensions.begin(), topology_extensions.end(),
                   [&](const char* e) { return extension == e; }) != topology_extensions.end();
    if (topology && name != trajectory && entry->is_regular_file(error))
    {
      if (!only.empty())
      {
        return {};
      }
      only = name;
    }
  }
  return only;
}

} // namespace mesolens
