// SPDX-License-Identifier: GPL-3.0-or-later
// Reading Stanford PLY meshes (ascii, binary little and big endian) strictly: a header that
// claims more than the file holds, a list longer than the bytes left, an index beyond the
// vertices or a number that does not parse is an error naming the place, never a crash or an
// allocation the file cannot justify (VTK's and CGAL's PLY readers trust the header's counts).
#pragma once

#include "mesolens/io/polygon_soup.h"

#include <string>
#include <vector>

namespace mesolens {

/// Reads the `vertex` element's x, y, z (and nx, ny, nz when all three are there) and the
/// `face` element's `vertex_indices` (or `vertex_index`) lists of a PLY file; other elements and
/// properties are read past. Property types: char/int8, uchar/uint8, short/int16,
/// ushort/uint16, int/int32, uint/uint32, float/float32, double/float64. Every count in the
/// header is checked against the bytes left in the file before anything is allocated for it.
/// Throws FileError, saying where, for a missing or empty file, a malformed header, a body
/// shorter than its header claims, a list count larger than the file could hold, a face of
/// fewer than 3 vertices or with an index outside the vertices, a non-finite coordinate, or a
/// file without vertices or faces.
MeshFileContents read_ply(const std::string& path);

/// The same for a PLY file's bytes held in memory (`name` says which in messages).
MeshFileContents read_ply_bytes(const std::string& bytes, const std::string& name);

} // namespace mesolens
