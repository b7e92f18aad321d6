// SPDX-License-Identifier: GPL-3.0-or-later
// File-name helpers shared by the readers.
#pragma once

#include <string>

namespace mesolens {

/// The extension of `path` in lower case, without the dot ("mito.OBJ" -> "obj"); "" when the
/// file name has none. With skip_compression, a trailing ".gz" is looked through
/// ("1abc.pdb.gz" -> "pdb").
std::string file_extension(const std::string& path, bool skip_compression = false);

/// The topology that lies beside a trajectory, as GROMACS users keep them: the file with the
/// trajectory's name and a topology extension (.gro, .pdb, .cif, .mmcif, .ent, each plain or
/// .gz, tried in that order: "run/md.xtc" -> "run/md.gro"), else the only topology file in the
/// trajectory's folder; "" when there is none or several.
std::string topology_beside(const std::string& trajectory);

} // namespace mesolens
