// SPDX-License-Identifier: GPL-3.0-or-later
// Reading Object File Format (.off) polygon soups strictly, defects and all.
#pragma once

#include "mesolens/io/polygon_soup.h"

#include <string>

namespace mesolens {

/// Reads an OFF file (OFF, COFF, NOFF, CNOFF, STOFF headers; counts on the header line or the
/// next; colours, normals and texture coordinates after a vertex's 3 coordinates and colours
/// after a face's indices are read past; `#` starts a comment) as a polygon soup:
/// non-manifold, inconsistently oriented and degenerate faces are kept, so mesh_report() can
/// describe them. Throws FileError, naming the line, for a missing or empty file, a bad header,
/// counts the file cannot hold (6 bytes per vertex, 8 per face at least), a coordinate that is
/// not a finite number, a face of fewer than 3 corners or an index outside the vertices, a file
/// that ends early, or one without faces. (CGAL's OFF scanner converted negative indices to
/// unsigned, undefined behaviour.)
PolygonSoup read_off(const std::string& path);

} // namespace mesolens
