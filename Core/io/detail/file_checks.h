// SPDX-License-Identifier: GPL-3.0-or-later
// Checks shared by the file readers of Core (private).
#pragma once

#include <string>

namespace mesolens {
namespace detail {

/// Throws FileError unless `path` is a readable, non-empty regular file.
void require_readable_file(const std::string& path);

/// The bytes of a readable file (require_readable_file() first); throws FileError when reading
/// fails part-way.
std::string read_file_bytes(const std::string& path);

} // namespace detail
} // namespace mesolens
