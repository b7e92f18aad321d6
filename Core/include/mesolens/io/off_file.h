// SPDX-License-Identifier: GPL-3.0-or-later
// Reading Object File Format (.off) polygon soups with CGAL, defects and all.
#pragma once

#include "mesolens/io/polygon_soup.h"

#include <string>

namespace mesolens {

/// Reads an OFF file as a polygon soup with CGAL::IO::read_OFF (non-manifold, inconsistently
/// oriented and degenerate faces are kept, so mesh_report() can describe them).
/// Throws FileError for a missing, empty or malformed file.
PolygonSoup read_off(const std::string& path);

} // namespace mesolens
