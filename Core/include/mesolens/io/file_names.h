// SPDX-License-Identifier: GPL-3.0-or-later
// File-name helpers shared by the readers.
#pragma once

#include <string>

namespace mesolens {

/// The extension of `path` in lower case, without the dot ("mito.OBJ" -> "obj"); "" when the
/// file name has none. With skip_compression, a trailing ".gz" is looked through
/// ("1abc.pdb.gz" -> "pdb").
std::string file_extension(const std::string& path, bool skip_compression = false);

} // namespace mesolens
