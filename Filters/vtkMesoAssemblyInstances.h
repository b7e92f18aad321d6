// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * @file    vtkMesoAssemblyInstances.h
 * @brief   A biological assembly's copies (mesolens::AssemblyInstances) as a vtkPolyData: the
 *          one pair of functions that the structure reader writes them with and instanced
 *          drawing reads them with.
 *
 * One point (and vertex) per copy, at the copy's translation t (Å), in copy order, with point
 * arrays (vtkMesoArrayNames):
 * - `AssemblyCopy` (int), `AssemblyAtomSet` (int: which atoms of the asymmetric unit the copy
 *   is made of);
 * - `AssemblyMatrix` (double, 12: the operator [R | t] row by row);
 * - `AssemblyOrientation` (double, 4: R as a unit quaternion w, x, y, z), only when every R is
 *   a rotation (mesolens::rotation_quaternion): vtkGlyph3DMapper with this array as its
 *   orientation (QUATERNION mode), scaling off, and one copy's geometry (ribbons, a surface) as
 *   its source draws every copy in one instanced call;
 * - `AssemblyBoundingSphere` (double, 4: centre and radius, Å, of the copy's atom centres).
 * Field data: `AssemblyAtomSetOffsets` (sets + 1 values) and `AssemblyAtomSetAtoms` (the rows
 * of the asymmetric unit in each set, increasing), `AssemblyAtomSetWhole` (1 per set that holds
 * every row).
 */
#ifndef vtkMesoAssemblyInstances_h
#define vtkMesoAssemblyInstances_h

#include "MesoLensFiltersModule.h"

#include "mesolens/protein/assembly.h"

class vtkPolyData;

namespace vtkMesoAssemblyInstances {
/// Fills `output` (emptied first) with the copies. Returns false when some R is not a rotation
/// (the copies are written without `AssemblyOrientation`).
MESOLENSFILTERS_EXPORT bool Write(const mesolens::AssemblyInstances& instances,
                                  vtkPolyData* output);

/// Reads copies written by Write() (the atom sets' own bounding spheres are not kept); false
/// when `input` is null, lacks an array Write adds (AssemblyOrientation excepted), or they
/// disagree in length.
MESOLENSFILTERS_EXPORT bool Read(vtkPolyData* input, mesolens::AssemblyInstances& instances);
}

#endif
// VTK-HeaderTest-Exclude: vtkMesoAssemblyInstances.h
