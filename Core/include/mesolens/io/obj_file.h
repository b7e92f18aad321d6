// SPDX-License-Identifier: GPL-3.0-or-later
// Reading Wavefront OBJ meshes strictly: a coordinate or an index that does not parse, a face
// that names a vertex the file does not have, or a non-finite coordinate is an error naming the
// line (VTK's vtkOBJReader reads "nan" and other garbage as 0 and passes on such faces).
#pragma once

#include "mesolens/io/polygon_soup.h"

#include <string>

namespace mesolens {

/// Reads the `v` (x y z, then optional w or r g b) and `f` records of an OBJ file. Face
/// corners are `v`, `v/vt`, `v//vn` or `v/vt/vn`, with 1-based indices or negative ones counted
/// back from the last vertex read; faces may name vertices defined later in the file. Vertex
/// normals are given when every vertex used by a face has one through its `vn` index (the first
/// corner that names one wins). Other records (vt, vn, o, g, s, usemtl, mtllib, l, p, ...) are
/// read past; `#` starts a comment and a trailing backslash continues a line.
/// Throws FileError, naming the line, for a missing or empty file, a number that does not
/// parse, a non-finite coordinate, a face of fewer than 3 corners or with an index of 0 or
/// outside the vertices (or the normals and texture coordinates read before it), or a file
/// without vertices or faces.
MeshFileContents read_obj(const std::string& path);

/// The same for an OBJ file's bytes held in memory (`name` says which in messages).
MeshFileContents read_obj_bytes(const std::string& bytes, const std::string& name);

} // namespace mesolens
