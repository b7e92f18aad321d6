// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * @class   vtkMesoMolecularSurface
 * @brief   The solvent-excluded (molecular), solvent-accessible or van der Waals surface of a
 *          set of atoms, as a closed triangle mesh with its exact area and volume.
 *
 * The solvent-excluded surface (SES) is what a probe sphere rolled over the atoms cannot
 * reach: convex parts of the atoms, saddles where the probe touches two atoms, concave
 * spherical triangles where it touches three. mesolens::molecular_surface builds it from these
 * analytic patches (Connolly, Sanner's reduced surface): the area and volume come from the
 * patches themselves, and the mesh is tessellated to a chord error (Tolerance), with every
 * vertex on the exact surface: contoured on a grid, then refined where its edges stray from
 * the surface. Singular patches (a probe passing between two atoms, probes
 * overlapping) are cut where they must be; cavities inside the molecule are separate closed
 * components and can be dropped. The solvent-accessible and van der Waals surfaces come from
 * the same machinery.
 *
 * Input: atoms as points (any MesoLens atom reader, or any polydata with points). Radii: the
 * point array RadiusArrayName when set (Å), else the element's van der Waals radius from
 * `AtomicNumber`, and BeadRadius for atoms without an element.
 *
 * Output: triangles, counter-clockwise seen from the solvent, with point arrays `Normals`
 * (float, unit, into the solvent), `AtomId` (vtkIdType: the atom each vertex belongs to, for
 * picking and colouring), `PatchType` (unsigned char: 0 convex, 1 toroidal, 2 concave) and
 * every numeric point array of the atoms carried over through AtomId (e.g. `MoleculeId`,
 * `ResidueIndex`, `AtomicNumber`, `BFactor`), and `ChainIndex` (int, chains numbered in order of
 * first appearance) when the atoms have a string `ChainId`. Field data: `Area` (Å², exact),
 * `Volume` (Å³, exact), `ConvexArea`, `ToroidalArea`, `ConcaveArea`, `SingularPatchCount`,
 * `ComponentCount`, `CavityCount`, `GridSpacing` (Å) and `DegenerateVertexCount` (points where
 * four or more atoms touch one probe position exactly, as in a perfect lattice: a warning says
 * that Area and Volume are then unreliable; the mesh is not affected).
 *
 * Progress events are sent while the mesh is built. Errors (no atoms, a radius or position
 * that is not finite or out of (0, 20] Å, a missing radius array, a tolerance too fine for the
 * molecule's size) are reported with vtkErrorMacro and give an empty output.
 */
#ifndef vtkMesoMolecularSurface_h
#define vtkMesoMolecularSurface_h

#include "MesoLensFiltersModule.h"
#include "vtkPolyDataAlgorithm.h"

class MESOLENSFILTERS_EXPORT vtkMesoMolecularSurface : public vtkPolyDataAlgorithm
{
public:
  static vtkMesoMolecularSurface* New();
  vtkTypeMacro(vtkMesoMolecularSurface, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The surface types, mesolens::SurfaceKind's values.
  enum SurfaceTypes
  {
    SOLVENT_EXCLUDED = 0,
    SOLVENT_ACCESSIBLE = 1,
    VAN_DER_WAALS = 2,
  };

  ///@{
  /// Which surface; see mesolens::MolecularSurfaceParams::kind.
  vtkSetClampMacro(SurfaceType, int, SOLVENT_EXCLUDED, VAN_DER_WAALS);
  vtkGetMacro(SurfaceType, int);
  void SetSurfaceTypeToSolventExcluded()
  {
    this->SetSurfaceType(SOLVENT_EXCLUDED);
  }
  void SetSurfaceTypeToSolventAccessible()
  {
    this->SetSurfaceType(SOLVENT_ACCESSIBLE);
  }
  void SetSurfaceTypeToVanDerWaals()
  {
    this->SetSurfaceType(VAN_DER_WAALS);
  }
  ///@}

  ///@{
  /// Radius of the solvent probe; see mesolens::MolecularSurfaceParams::probe_radius (the
  /// filter takes at least 0.01).
  vtkSetClampMacro(ProbeRadius, double, 0.01, 20.0);
  vtkGetMacro(ProbeRadius, double);
  ///@}

  ///@{
  /// Largest distance between a triangle and the exact surface on its smooth patches (chord
  /// error); see mesolens::MolecularSurfaceParams::tolerance. Where the surface has creases
  /// (the van der Waals and accessible surfaces' seams, the SES's singular cusps and rims) the
  /// error stays within the spacing of the lattice the mesh is refined from (field
  /// GridSpacing).
  vtkSetClampMacro(Tolerance, double, 0.005, 1.0);
  vtkGetMacro(Tolerance, double);
  ///@}

  ///@{
  /// Compute the exact Area and Volume; see mesolens::MolecularSurfaceParams::exact_figures.
  /// Off gives the mesh without the field arrays Area, Volume, ConvexArea, ToroidalArea,
  /// ConcaveArea and SingularPatchCount.
  vtkSetMacro(ComputeExactFigures, bool);
  vtkGetMacro(ComputeExactFigures, bool);
  vtkBooleanMacro(ComputeExactFigures, bool);
  ///@}
  ///@{
  /// Keep the closed surfaces of cavities inside the molecule; see
  /// mesolens::MolecularSurfaceParams::keep_cavities.
  vtkSetMacro(KeepCavities, bool);
  vtkGetMacro(KeepCavities, bool);
  vtkBooleanMacro(KeepCavities, bool);
  ///@}

  ///@{
  /// Point array of the atoms' radii (Å); nullptr or "" (default): radii from the elements.
  vtkSetStringMacro(RadiusArrayName);
  vtkGetStringMacro(RadiusArrayName);
  ///@}

  ///@{
  /// Radius of atoms without an element (AtomicNumber 0: beads), Å, [0.1, 10]; default
  /// mesolens::bead_radius (a Martini bead).
  vtkSetClampMacro(BeadRadius, double, 0.1, 10.0);
  vtkGetMacro(BeadRadius, double);
  ///@}

protected:
  vtkMesoMolecularSurface();
  ~vtkMesoMolecularSurface() override;

  /// Streaming one process's pieces: every piece computes on the whole input (see
  /// vtkMesoAtomPieces::GatheredInput).
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector** inputVector,
                          vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
                  vtkInformationVector* outputVector) override;

  // Set by the constructor from mesolens::MolecularSurfaceParams' defaults.
  int SurfaceType;
  double ProbeRadius;
  double Tolerance;
  bool ComputeExactFigures;
  bool KeepCavities;
  // The filter's own.
  char* RadiusArrayName = nullptr;
  double BeadRadius; // set by the constructor

private:
  vtkMesoMolecularSurface(const vtkMesoMolecularSurface&) = delete;
  void operator=(const vtkMesoMolecularSurface&) = delete;
};

#endif
