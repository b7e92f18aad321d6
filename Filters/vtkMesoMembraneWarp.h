// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * @file    vtkMesoMembraneWarp.h
 * @brief   The membrane warp (mesolens::MembraneWarp) in VTK field data: the one pair of
 *          functions that the mapping filter writes it with and the atom mapper reads it with.
 *
 * Arrays (vtkMesoArrayNames): MappingMethod, Tiles, TilesRequested, TilesMapped, CutToDisk,
 * MappingNote (string), MembraneToMeshScale, PatchOrigin (2), PatchCellA (2), PatchCellB (2),
 * PatchCentreHeight, LayerHalfThickness, GeodesicRadius, SeedUV (2), SeedNormal (3),
 * RefinementLevels; with
 * the polynomial method PolynomialCoefficients (30 per piece), PolynomialSplits,
 * PolynomialResidualRMS, PolynomialResidualMax, PolynomialFallbackTiles (per tile); with
 * molecule instancing InstanceMatrices (16 per instance), InstanceMoleculeId, InstanceTileId.
 * Numbers are double arrays of one tuple unless said.
 */
#ifndef vtkMesoMembraneWarp_h
#define vtkMesoMembraneWarp_h

#include "MesoLensFiltersModule.h"

#include "mesolens/mapping/membrane_warp.h"

#include <vector>

class vtkAbstractArray;
class vtkFieldData;

namespace vtkMesoMembraneWarp {
/// Adds the warp's arrays to `fields` (replacing arrays of the same names).
MESOLENSFILTERS_EXPORT void Write(const mesolens::MembraneWarp& warp, vtkFieldData* fields);

/// Reads a warp written by Write(); false when `fields` is null or lacks one of the patch
/// frame's arrays, the tiles or the method (not the output of a vtkMesoMembraneMapping). Does
/// not check that the warp can be drawn (mesolens::check_drawable does).
MESOLENSFILTERS_EXPORT bool Read(vtkFieldData* fields, mesolens::MembraneWarp& warp);

/// The warp's arrays in `fields` (those Write adds, nullptr where absent), in a fixed order:
/// while they are the same objects, unmodified, Read would read the same warp (a filter that
/// passes the warp on and adds arrays of its own, as vtkMesoStructuredCutaway, keeps them).
MESOLENSFILTERS_EXPORT std::vector<vtkAbstractArray*> Arrays(vtkFieldData* fields);
}

#endif
// VTK-HeaderTest-Exclude: vtkMesoMembraneWarp.h
