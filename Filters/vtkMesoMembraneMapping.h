// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * @class   vtkMesoMembraneMapping
 * @brief   Places a membrane patch, tiled k x k, in the shell around a picked region of a cell
 *          surface (Waltemate, Sommer and Botsch, VCBM 2014).
 *
 * Input 0: the cell-component surface (triangles, mesh units, e.g. µm). Input 1: the membrane
 * patch from vtkMesoStructureReader or vtkMesoTrajectoryReader (atoms as vertices, bonds as
 * lines, `MoleculeId`, `AtomicNumber`, field data `PeriodicBoxVectors`), bilayer normal along z.
 *
 * The patch's cell (a, b from PeriodicBoxVectors, or the atoms' x-y bounding box when there is
 * none) is repeated k x k times (Tiles); the tiled region is d x d with d = k x the cell width,
 * scaled by MembraneToMeshScale (mesh units per membrane unit: 1e-4 for Å onto µm). Around the
 * surface point closest to SeedPoint a geodesic disk of radius r = RadiusFactor x d (the paper
 * uses 2) is grown (see vtkMesoGeodesicDisk; coarse regions are refined on the smooth surface
 * through the input's vertices, which every mapped point lies on) and parameterized onto the
 * planar disk of radius r (vtkMesoDiskParameterization); the patch goes
 * to (u, v) = the seed's plus the atom's (x, y) offset, its heights (z minus the bilayer centre,
 * the mean z) along the normal, by one of three methods (MappingMethod):
 * - DISPLACEMENT: every atom at x0 + w n(x0);
 * - MOLECULE_INSTANCING: one rigid motion per molecule (MoleculeId), its centre of mass mapped,
 *   its x, y, z axes taken to the u tangent, v tangent and normal;
 * - POLYNOMIAL: one quadratic x(s, t, h) per tile, fitted by least squares (Cholesky) to the
 *   displacement map on PolynomialSamples^2 samples in 3 layers (h = -e, 0, +e with e =
 *   LayerHalfThickness). A tile whose largest residual exceeds MaximumPolynomialResidual is
 *   split into 2 x 2 (then 4 x 4) pieces with a polynomial each; a tile still above it has its
 *   atoms mapped by displacement (`PolynomialFallbackTiles`).
 *
 * Every click maps what fits (MapWhatFits): when the asked k x k tiles do not fit (their disk
 * wraps a handle, meets the mesh's boundary or covers the whole component, the tiles leave it,
 * or flattening it would stretch them more than MaximumStretch), the largest k that fits is
 * mapped, and if not even one tile fits, one tile cut to the largest disk there is (molecules
 * leaving it are dropped). A warning, field data `TilesRequested`, `TilesMapped`, `CutToDisk`
 * and the text `MappingNote` say what was mapped.
 *
 * Output 0, the mapped atoms (unless OutputAtoms is off: then the molecules' warped centres,
 * see SetOutputAtoms): k^2 copies of the patch (tile t = j k + i
 * holds atoms [t n, (t+1) n), less those a cut tile drops), one vertex per atom and the patch's
 * bonds in every tile; the patch's point arrays repeated, plus `TileId`, with `MoleculeId` made
 * unique over the tiles (t (largest id + 1) + id); cell data `BondLengthChange` (mapped length /
 * scaled patch length - 1 for bond lines, 0 for atom vertices: the paper's intra-molecular
 * distortion). Field data: `GeodesicRadius`, `Tiles` (= TilesMapped), `MappingMethod`,
 * `MembraneToMeshScale`, `PatchOrigin` (2), `PatchCellA` (2), `PatchCellB` (2),
 * `PatchCentreHeight`, `LayerHalfThickness`, `SeedUV` (2), `RefinementLevels`; POLYNOMIAL adds
 * `PolynomialCoefficients` (30 per piece, m x m pieces per tile, m = `PolynomialSplits`; x, y, z in
 * the monomial order 1, s, t, h, s², st, sh, t², th, h² of mesolens::quadratic_monomials, with (s,
 * t) = 2 f - 1 from the atom's fractional coordinates f in its piece and h = (z - centre) / e; see
 * mesolens::evaluate_tile_polynomial), `PolynomialResidualRMS`, `PolynomialResidualMax` (per tile,
 * mesh units) and `PolynomialFallbackTiles` (per tile, 1 = displaced); MOLECULE_INSTANCING adds
 * `InstanceMatrices` (16 per instance, row-major), `InstanceMoleculeId`, `InstanceTileId`; and
 * `SeedNormal` (3), the surface's normal at the seed, where the patch's +z goes. These arrays
 * are the mesolens::MembraneWarp of vtkMesoMembraneWarp. Output 1: the parameterized disk
 * (TextureCoordinates, GeodesicDistance, distortions). Output 2, when LatticeEdge > 0: a
 * regular triangle lattice of that edge laid on the disk (mesolens::chart_lattice), the
 * structure to cut the mapped membrane along with vtkMesoStructuredCutaway.
 *
 * Pieces (pvbatch or pvserver on N MPI ranks): every piece gathers the whole surface and
 * patch from the pieces its inputs hold and grows the same disk; piece p of N maps the atoms of
 * tiles [k^2 p / N, k^2 (p + 1) / N) (TileId and MoleculeId as on one process), so the ranks share
 * the mapping's work and output. With OutputAtoms off (the warp for the GPU) and for outputs 1 and
 * 2, piece 0 gives everything and the other pieces are empty.
 *
 * The surface's preparation and the most recent disks and parameterizations
 * (mesolens::MembraneMapper) are kept while the surface stays the same, so a new trajectory
 * frame (the membrane input's time steps are passed downstream) only re-maps atoms. Outputs are
 * bitwise identical run to run and for any number of threads. Errors (seed far from the
 * surface, k < 1, not even one molecule's footprint fitting, or with MapWhatFits off a disk
 * that meets the mesh boundary or wraps a handle; a non-manifold surface, no MoleculeId for
 * instancing, NaN) are reported with vtkErrorMacro; the outputs are then empty and the update
 * fails.
 */
#ifndef vtkMesoMembraneMapping_h
#define vtkMesoMembraneMapping_h

#include "MesoLensFiltersModule.h"
#include "vtkPolyDataAlgorithm.h"

#include "mesolens/mapping/mapping_method.h"

#include <memory>

class MESOLENSFILTERS_EXPORT vtkMesoMembraneMapping : public vtkPolyDataAlgorithm
{
public:
  static vtkMesoMembraneMapping* New();
  vtkTypeMacro(vtkMesoMembraneMapping, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Connect the cell surface (input 0) and the membrane patch (input 1).
  void SetSurfaceConnection(vtkAlgorithmOutput* output)
  {
    this->SetInputConnection(0, output);
  }
  void SetMembraneConnection(vtkAlgorithmOutput* output)
  {
    this->SetInputConnection(1, output);
  }

  /// mesolens::MappingMethod's values (Core/include/mesolens/mapping/mapping_method.h).
  enum MappingMethods
  {
    DISPLACEMENT = int(mesolens::MappingMethod::Displacement),
    MOLECULE_INSTANCING = int(mesolens::MappingMethod::MoleculeInstancing),
    POLYNOMIAL = int(mesolens::MappingMethod::Polynomial)
  };

  ///@{
  /// How atoms are carried onto the surface; see mesolens::MappingParams::method.
  vtkSetClampMacro(MappingMethod, int, DISPLACEMENT, POLYNOMIAL);
  vtkGetMacro(MappingMethod, int);
  void SetMappingMethodToDisplacement()
  {
    this->SetMappingMethod(DISPLACEMENT);
  }
  void SetMappingMethodToMoleculeInstancing()
  {
    this->SetMappingMethod(MOLECULE_INSTANCING);
  }
  void SetMappingMethodToPolynomial()
  {
    this->SetMappingMethod(POLYNOMIAL);
  }
  ///@}

  ///@{
  /// The picked point on the surface (mesh units); the patch is centred at the closest surface
  /// point. Default (0, 0, 0).
  vtkSetVector3Macro(SeedPoint, double);
  vtkGetVector3Macro(SeedPoint, double);
  ///@}

  ///@{
  /// How far SeedPoint may be from the surface (mesh units); <= 0: 2 % of the surface's
  /// bounding-box diagonal (mesolens::MembraneMapper::seed_near). Default 0.
  vtkSetMacro(SeedTolerance, double);
  vtkGetMacro(SeedTolerance, double);
  ///@}

  ///@{
  /// k: the patch is repeated k x k times; see mesolens::MappingParams::tiles.
  vtkSetMacro(Tiles, int);
  vtkGetMacro(Tiles, int);
  ///@}

  ///@{
  /// Mesh units per membrane unit; see mesolens::MappingParams::scale.
  vtkSetMacro(MembraneToMeshScale, double);
  vtkGetMacro(MembraneToMeshScale, double);
  ///@}

  ///@{
  /// The geodesic disk's radius over the tiled width d; see mesolens::MapRequest::radius_factor.
  vtkSetClampMacro(RadiusFactor, double, 0.8, 10.0);
  vtkGetMacro(RadiusFactor, double);
  ///@}

  ///@{
  /// POLYNOMIAL: half the distance between the outer sample layers; see
  /// mesolens::MappingParams::layer_half_thickness.
  vtkSetMacro(LayerHalfThickness, double);
  vtkGetMacro(LayerHalfThickness, double);
  ///@}

  ///@{
  /// POLYNOMIAL: samples per tile edge; see mesolens::MappingParams::samples (the filter takes
  /// at most 32).
  vtkSetClampMacro(PolynomialSamples, int, 3, 32);
  vtkGetMacro(PolynomialSamples, int);
  ///@}

  ///@{
  /// The edge of the lattice of output 2, mesh units; 0 (default): no lattice. A tenth of the
  /// disk's radius or more keeps it to a few hundred triangles.
  vtkSetClampMacro(LatticeEdge, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(LatticeEdge, double);
  ///@}

  ///@{
  /// Map every atom into output 0 (on), or (off) leave output 0 without atoms and bonds: for
  /// POLYNOMIAL and MOLECULE_INSTANCING, whose coefficients or matrices vtkMesoAtomMapper
  /// evaluates on the GPU (its warp input). Output 0 then holds the field data and one vertex
  /// per molecule and tile (with a patch MoleculeId), at the molecule's centre as the renderer
  /// warps it (mesolens::warped_molecule_centres, equal to the centre of its mapped atoms),
  /// tile-major, the molecules in the patch's order; point arrays MoleculeId (unique over the
  /// tiles, as the mapped atoms'), TileId and ResidueName (of its first atom): what a
  /// vtkMesoStructuredCutaway cuts (give it the structure, output 2: one point per molecule is
  /// too few to make one) for the mapper to hide molecules tile by tile. DISPLACEMENT always
  /// maps the atoms. See mesolens::MappingParams::map_atoms.
  vtkSetMacro(OutputAtoms, bool);
  vtkGetMacro(OutputAtoms, bool);
  vtkBooleanMacro(OutputAtoms, bool);
  ///@}

  ///@{
  /// POLYNOMIAL: the largest fit residual accepted in a tile; beyond it the tile is split,
  /// then displaced. See mesolens::MappingParams::max_polynomial_residual.
  vtkSetMacro(MaximumPolynomialResidual, double);
  vtkGetMacro(MaximumPolynomialResidual, double);
  ///@}

  ///@{
  /// Refine coarse surface triangles (on the smooth surface through the input's vertices) so
  /// that the disk holds at least about this many; see mesolens::MapRequest::min_disk_triangles.
  vtkSetClampMacro(MinimumDiskTriangles, int, 0, VTK_INT_MAX);
  vtkGetMacro(MinimumDiskTriangles, int);
  ///@}

  ///@{
  /// On meshes of more than 16 000 triangles, a disk over more than this many of them is grown
  /// on a coarser copy of the mesh and its points are placed on the input (fast re-maps on fine
  /// meshes); see mesolens::MapRequest::max_disk_triangles.
  vtkSetClampMacro(MaximumDiskTriangles, int, 0, VTK_INT_MAX);
  vtkGetMacro(MaximumDiskTriangles, int);
  ///@}

  ///@{
  /// The largest factor by which the flattened disk may stretch or shrink lengths where the
  /// tiles lie; a disk that distorts them more does not fit (fewer tiles are mapped). See
  /// mesolens::MapRequest::max_stretch (the filter takes [1.01, 100]).
  vtkSetClampMacro(MaximumStretch, double, 1.01, 100.0);
  vtkGetMacro(MaximumStretch, double);
  ///@}

  ///@{
  /// Map the largest k x k (or one tile cut to a disk) that fits when the asked tiles do not
  /// (on), or fail (off); see mesolens::MapRequest::fit_what_fits.
  vtkSetMacro(MapWhatFits, bool);
  vtkGetMacro(MapWhatFits, bool);
  vtkBooleanMacro(MapWhatFits, bool);
  ///@}

protected:
  vtkMesoMembraneMapping();
  ~vtkMesoMembraneMapping() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// Streaming one process's pieces: every piece computes on the whole input (see
  /// vtkMesoAtomPieces::GatheredInput).
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector** inputVector,
                          vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  // Set by the constructor from mesolens::MapRequest's defaults.
  int MappingMethod;
  int Tiles;
  double MembraneToMeshScale;
  double RadiusFactor;
  double LayerHalfThickness;
  int PolynomialSamples;
  double MaximumPolynomialResidual;
  int MinimumDiskTriangles;
  int MaximumDiskTriangles;
  double MaximumStretch;
  bool MapWhatFits;
  bool OutputAtoms;
  // The filter's own.
  double SeedPoint[3] = { 0, 0, 0 };
  double SeedTolerance = 0;
  double LatticeEdge = 0;

private:
  vtkMesoMembraneMapping(const vtkMesoMembraneMapping&) = delete;
  void operator=(const vtkMesoMembraneMapping&) = delete;

  struct State;
  std::unique_ptr<State> Internal;
};

#endif
