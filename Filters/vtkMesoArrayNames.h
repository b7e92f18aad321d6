// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * @file    vtkMesoArrayNames.h
 * @brief   The names of the arrays MesoLens's readers and filters write, in one place.
 *
 * Readers and filters write these arrays, and what comes downstream (other filters, the atom
 * mapper) finds them by these names: C++ code uses the constants, never the text.
 */
#ifndef vtkMesoArrayNames_h
#define vtkMesoArrayNames_h

namespace vtkMesoArrayNames {
// Atoms: point data of the structure and trajectory readers (vtkMesoStructureReader.h lists them).
constexpr const char* AtomName = "AtomName";
constexpr const char* Element = "Element";
constexpr const char* ResidueName = "ResidueName";
constexpr const char* ResidueNumber = "ResidueNumber";
constexpr const char* ResidueIndex = "ResidueIndex";
constexpr const char* InsertionCode = "InsertionCode";
constexpr const char* ChainId = "ChainId";
constexpr const char* ChainIndex = "ChainIndex";
constexpr const char* MoleculeId = "MoleculeId";
constexpr const char* SerialNumber = "SerialNumber";
constexpr const char* AltLoc = "AltLoc";
constexpr const char* Occupancy = "Occupancy";
constexpr const char* BFactor = "BFactor";
constexpr const char* FormalCharge = "FormalCharge";
constexpr const char* IsHetAtm = "IsHetAtm";
constexpr const char* AtomicNumber = "AtomicNumber";
constexpr const char* SecondaryStructure = "SecondaryStructure";
constexpr const char* SecondaryStructureId = "SecondaryStructureId";
// vtkMesoStructureReader with an Assembly: the copy of the asymmetric unit an atom belongs to.
constexpr const char* AssemblyCopy = "AssemblyCopy";
// vtkMesoStructureReader's output 1: the copies of an assembly (vtkMesoAssemblyInstances.h).
constexpr const char* AssemblyAtomSet = "AssemblyAtomSet";
constexpr const char* AssemblyMatrix = "AssemblyMatrix";
constexpr const char* AssemblyOrientation = "AssemblyOrientation";
constexpr const char* AssemblyBoundingSphere = "AssemblyBoundingSphere";
constexpr const char* AssemblyAtomSetOffsets = "AssemblyAtomSetOffsets";
constexpr const char* AssemblyAtomSetAtoms = "AssemblyAtomSetAtoms";
constexpr const char* AssemblyAtomSetWhole = "AssemblyAtomSetWhole";

// Atoms: field data of the readers (PeriodicBoxVectors: 9 values, the box vectors a, b, c row by
// row).
constexpr const char* PeriodicBoxVectors = "PeriodicBoxVectors";
constexpr const char* CoarseGrained = "CoarseGrained";
constexpr const char* Title = "Title";
constexpr const char* ModelIndex = "ModelIndex";
constexpr const char* TimePs = "TimePs";
constexpr const char* Step = "Step";
constexpr const char* FrameIndex = "FrameIndex";
constexpr const char* RefinedFrameIndex = "RefinedFrameIndex";

// vtkMesoAtomProperties.
constexpr const char* VanDerWaalsRadius = "VanDerWaalsRadius";
constexpr const char* CovalentRadius = "CovalentRadius";

// vtkMesoSecondaryStructure.
constexpr const char* ResidueSecondaryStructure = "ResidueSecondaryStructure";
constexpr const char* ResidueIndexOfAssignment = "ResidueIndexOfAssignment";
constexpr const char* HydrogenBonds = "HydrogenBonds";
constexpr const char* DSSP = "DSSP";

// vtkMesoRibbons (and vtkMesoRibbonLevelOfDetail, which reads the segments).
constexpr const char* SegmentBounds = "SegmentBounds";
constexpr const char* SegmentResidueCounts = "SegmentResidueCounts";
constexpr const char* AtomId = "AtomId";
constexpr const char* Normals = "Normals";

// vtkMesoMolecularSurface and vtkMesoSurfaceArea.
constexpr const char* PatchType = "PatchType";
constexpr const char* Area = "Area";
constexpr const char* Volume = "Volume";
constexpr const char* ConvexArea = "ConvexArea";
constexpr const char* ConcaveArea = "ConcaveArea";
constexpr const char* ToroidalArea = "ToroidalArea";
constexpr const char* GridSpacing = "GridSpacing";
constexpr const char* CavityCount = "CavityCount";
constexpr const char* ComponentCount = "ComponentCount";
constexpr const char* SingularPatchCount = "SingularPatchCount";
constexpr const char* DegenerateVertexCount = "DegenerateVertexCount";
constexpr const char* AccessibleArea = "AccessibleArea";
constexpr const char* TotalArea = "TotalArea";

// vtkMesoMeshReport.
constexpr const char* DegenerateTriangle = "DegenerateTriangle";
constexpr const char* NonManifoldVertex = "NonManifoldVertex";
constexpr const char* EulerCharacteristic = "EulerCharacteristic";
constexpr const char* NumberOfBoundaryEdges = "NumberOfBoundaryEdges";
constexpr const char* NumberOfBoundaryLoops = "NumberOfBoundaryLoops";
constexpr const char* NumberOfComponents = "NumberOfComponents";
constexpr const char* NumberOfDegenerateTriangles = "NumberOfDegenerateTriangles";
constexpr const char* NumberOfInconsistentlyOrientedEdges = "NumberOfInconsistentlyOrientedEdges";
constexpr const char* NumberOfNonManifoldEdges = "NumberOfNonManifoldEdges";
constexpr const char* NumberOfNonManifoldVertices = "NumberOfNonManifoldVertices";
constexpr const char* NumberOfUnreferencedVertices = "NumberOfUnreferencedVertices";

// vtkMesoGeodesicDisk and vtkMesoDiskParameterization (GeodesicRadius and RefinementLevels below).
constexpr const char* GeodesicDistance = "GeodesicDistance";
constexpr const char* OriginalPointId = "OriginalPointId";
constexpr const char* SeedTriangle = "SeedTriangle";
constexpr const char* SeedPosition = "SeedPosition";
constexpr const char* SeedBarycentric = "SeedBarycentric";
constexpr const char* HolesClosed = "HolesClosed";
constexpr const char* ParameterizationRadius = "ParameterizationRadius";
constexpr const char* TextureCoordinates = "TextureCoordinates";
constexpr const char* AngleDistortion = "AngleDistortion";
constexpr const char* AreaDistortion = "AreaDistortion";
constexpr const char* FlippedTriangles = "FlippedTriangles";
constexpr const char* Bijective = "Bijective";

// vtkMesoStructuredCutaway: the cut atoms, and the quality of the structure mesh (output 1).
constexpr const char* RemovalPriority = "RemovalPriority";
constexpr const char* MoleculeRemovalPriority = "MoleculeRemovalPriority";
constexpr const char* MoleculeVisible = "MoleculeVisible";
constexpr const char* Visible = "Visible";
constexpr const char* MoleculesInCut = "MoleculesInCut";
constexpr const char* MoleculesHidden = "MoleculesHidden";
constexpr const char* MinAngle = "MinAngle";
constexpr const char* MaxAngle = "MaxAngle";
constexpr const char* MeanEdge = "MeanEdge";
constexpr const char* EdgeSpread = "EdgeSpread";
constexpr const char* BoundaryEdges = "BoundaryEdges";
constexpr const char* BoundaryLoops = "BoundaryLoops";
constexpr const char* Components = "Components";

// vtkMesoMembraneMapping: the mapped atoms (output 0).
constexpr const char* TileId = "TileId";
constexpr const char* BondLengthChange = "BondLengthChange";

// The membrane warp (vtkMesoMembraneWarp: field data of vtkMesoMembraneMapping output 0; Tiles
// repeats TilesMapped; MappingNote is a string array).
constexpr const char* MappingMethod = "MappingMethod";
constexpr const char* Tiles = "Tiles";
constexpr const char* TilesRequested = "TilesRequested";
constexpr const char* TilesMapped = "TilesMapped";
constexpr const char* CutToDisk = "CutToDisk";
constexpr const char* MappingNote = "MappingNote";
constexpr const char* MembraneToMeshScale = "MembraneToMeshScale";
constexpr const char* PatchOrigin = "PatchOrigin";
constexpr const char* PatchCellA = "PatchCellA";
constexpr const char* PatchCellB = "PatchCellB";
constexpr const char* PatchCentreHeight = "PatchCentreHeight";
constexpr const char* LayerHalfThickness = "LayerHalfThickness";
constexpr const char* GeodesicRadius = "GeodesicRadius";
constexpr const char* SeedUV = "SeedUV";
constexpr const char* SeedNormal = "SeedNormal";
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
