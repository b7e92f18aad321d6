// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * @file    vtkMesoArrayNames.h
 * @brief   The names of the arrays MesoLens's readers and filters write, in one place.
 *
 * Readers and filters write these arrays and others (the mapper, the filters downstream) find
 * them by these names; code in C++ uses the constants, never the text.
 */
#ifndef vtkMesoArrayNames_h
#define vtkMesoArrayNames_h

namespace vtkMesoArrayNames {
// Atoms (point data of the atom readers' outputs, see vtkMesoAtomReader).
constexpr const char* AtomicNumber = "AtomicNumber";
constexpr const char* MoleculeId = "MoleculeId";
// Field data of the atom readers: 9 values, the periodic box's vectors a, b, c (row by row).
constexpr const char* PeriodicBoxVectors = "PeriodicBoxVectors";

// The membrane mapping's atoms (vtkMesoMembraneMapping output 0).
constexpr const char* TileId = "TileId";                     ///< point data, int
constexpr const char* BondLengthChange = "BondLengthChange"; ///< cell data, float

// The membrane warp (vtkMesoMembraneWarp: field data of vtkMesoMembraneMapping output 0).
constexpr const char* MappingMethod = "MappingMethod";
constexpr const char* Tiles = "Tiles"; ///< the tiles mapped (as TilesMapped)
constexpr const char* TilesRequested = "TilesRequested";
constexpr const char* TilesMapped = "TilesMapped";
constexpr const char* CutToDisk = "CutToDisk";
constexpr const char* MappingNote = "MappingNote"; ///< a string array
constexpr const char* MembraneToMeshScale = "MembraneToMeshScale";
constexpr const char* PatchOrigin = "PatchOrigin";
constexpr const char* PatchCellA = "PatchCellA";
constexpr const char* PatchCellB = "PatchCellB";
constexpr const char* PatchCentreHeight = "PatchCentreHeight";
constexpr const char* LayerHalfThickness = "LayerHalfThickness";
constexpr const char* GeodesicRadius = "GeodesicRadius";
constexpr const char* SeedUV = "SeedUV";
constexpr const char* RefinementLevels = "RefinementLevels";
constexpr const char* PolynomialCoefficients = "PolynomialCoefficients";
constexpr const char* PolynomialSplits = "PolynomialSplits";
constexpr const char* PolynomialResidualRMS = "PolynomialResidualRMS";
constexpr const char* PolynomialResidualMax = "PolynomialResidualMax";
constexpr const char* PolynomialFallbackTiles = "PolynomialFallbackTiles";
constexpr const char* InstanceMatrices = "InstanceMatrices";
constexpr const char* InstanceMoleculeId = "InstanceMoleculeId";
constexpr const char* InstanceTileId = "InstanceTileId";
}

#endif
// VTK-HeaderTest-Exclude: vtkMesoArrayNames.h
