// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * @class   vtkMesoStructuredCutaway
 * @brief   Cuts a dense membrane open and keeps its structure: where a cut applies, molecules
 *          are hidden so that what remains follows a wireframe of a structure mesh.
 *
 * The SirTom thesis' structured cutaway (mesolens::StructuredCutaway). Input 0: atoms (a
 * MesoLens reader's output or any polydata of points), grouped into molecules by the
 * `MoleculeId` point array (without it, every atom is a molecule). Input 1
 * (SetStructureConnection, optional): the structure's triangle mesh in the atoms' units. Without
 * it the structure is made from the centres of the membrane's molecules (mesolens::structure_mesh:
 * one sheet through the middle of the bilayer, its leaflets paired along the local normal, of
 * about StructureVertices vertices, every triangle's angles within 30-120°): water and ions (by
 * residue name, or molecules of fewer than 4 atoms), proteins and nucleic acids, and strays far
 * from the membrane are left out (mesolens::structure_molecules). A flat membrane spanning its
 * periodic box (field data `PeriodicBoxVectors`) gives an open sheet over the box's cell, a
 * vesicle a closed one. It is output 1 either way, a made one with its quality in field data
 * `MinAngle`, `MaxAngle` (degrees), `MeanEdge`, `EdgeSpread`, `BoundaryEdges`, `BoundaryLoops`
 * and `Components`.
 *
 * Every molecule is assigned once to its nearest triangle (exact closest point); its removal
 * priority comes from the smallest barycentric coordinate x of that point, (f(6 x - 1, K) + 1)
 * / 2 with f Dino Dini's normalized tunable sigmoid: 1 at triangle centres, 0 on edges. The
 * assignment is kept while the structure, the molecules and their count stay, so changing K,
 * FractionHidden, Inverted, RandomOrder, Seed or the cut only reorders (a slider stays fast).
 *
 * The cut is CutFunction (any vtkImplicitFunction: vtkPlane, vtkSphere, vtkBox, or a
 * vtkImplicitBoolean union of them); a molecule is in the cut when the function is <= 0 at its
 * centre (inside a sphere or box; for a plane, the side its normal points away from). Of the
 * molecules in the cut, round(FractionHidden x count) are hidden, highest priority first
 * (lowest when Inverted; with ProbabilisticOrder, in a seeded random order weighted by the
 * priorities; by a seeded random key alone with RandomOrder, the Visibility Equalizer's
 * removal), ties broken by the seeded key: the same settings give the same mask every frame.
 * Without a CutFunction nothing is hidden.
 *
 * Molecule types: with a `ResidueName` point array, a molecule's type is the residue name of
 * its first atom (DPPC, CHOL, ...); the fraction applies per type (round(f x count) of each type
 * in the cut), and SetFractionHiddenOfResidue gives a type its own fraction.
 *
 * Output 0: the atoms (shallow copy; with ExtractVisibleAtoms, the visible atoms only, their
 * bonds among them kept) with point arrays `Visible` (unsigned char, 1 visible; vtkMesoAtomMapper
 * hides the others without uploading positions again) and `RemovalPriority` (float, the atom's
 * molecule's), and field data `MoleculesInCut`, `MoleculesHidden`, and per molecule (in order of
 * first appearance) `MoleculeVisible` and `MoleculeRemovalPriority`.
 *
 * What is kept between updates: the molecules and their centres while the input points stay;
 * the assignment while the structure and the molecules stay; the removal order while the cut,
 * K, Inverted, RandomOrder, Seed and the centres stay. A new FractionHidden then costs O(atoms),
 * and the output keeps the same points object, so a mapper uploads nothing but the mask.
 *
 * Errors (a structure without triangles, molecules whose centres describe no surface or no
 * mesh within the angle bound, a non-finite atom) are reported with vtkErrorMacro and give empty
 * outputs.
 */
#ifndef vtkMesoStructuredCutaway_h
#define vtkMesoStructuredCutaway_h

#include "MesoLensFiltersModule.h"
#include "vtkPolyDataAlgorithm.h"

#include <memory>
#include <string>

class vtkImplicitFunction;

class MESOLENSFILTERS_EXPORT vtkMesoStructuredCutaway : public vtkPolyDataAlgorithm
{
public:
  static vtkMesoStructuredCutaway* New();
  vtkTypeMacro(vtkMesoStructuredCutaway, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The structure's triangle mesh (input 1).
  void SetStructureConnection(vtkAlgorithmOutput* output)
  {
    this->SetInputConnection(1, output);
  }

  ///@{
  /// Where the cut applies (function <= 0). nullptr (default): nowhere.
  void SetCutFunction(vtkImplicitFunction* function);
  vtkGetObjectMacro(CutFunction, vtkImplicitFunction);
  ///@}

  ///@{
  /// The removal priority's sigmoid k; see mesolens::CutawayParams::k (the filter takes
  /// [-0.99, 0.99]).
  vtkSetClampMacro(K, double, -0.99, 0.99);
  vtkGetMacro(K, double);
  ///@}

  ///@{
  /// Fraction of the molecules in the cut that are hidden; see
  /// mesolens::CutawayParams::fraction_hidden.
  vtkSetClampMacro(FractionHidden, double, 0.0, 1.0);
  vtkGetMacro(FractionHidden, double);
  ///@}

  ///@{
  /// Hide molecules on the mesh's edges first (patches instead of a wireframe); see
  /// mesolens::CutawayParams::inverted.
  vtkSetMacro(Inverted, bool);
  vtkGetMacro(Inverted, bool);
  vtkBooleanMacro(Inverted, bool);
  ///@}

  ///@{
  /// Use the priorities as probabilities (a seeded weighted random order): K then blends from
  /// two classes (towards -1) through 3x (0) to nearly random (towards 1). Off: the strict
  /// order by priority, the crispest wireframe, the same for every K. See
  /// mesolens::CutawayParams::probabilistic.
  vtkSetMacro(ProbabilisticOrder, bool);
  vtkGetMacro(ProbabilisticOrder, bool);
  vtkBooleanMacro(ProbabilisticOrder, bool);
  ///@}

  ///@{
  /// Random removal (the Visibility Equalizer's), for comparison; see
  /// mesolens::CutawayParams::random.
  vtkSetMacro(RandomOrder, bool);
  vtkGetMacro(RandomOrder, bool);
  vtkBooleanMacro(RandomOrder, bool);
  ///@}

  ///@{
  /// Seed of the per-molecule random keys; see mesolens::CutawayParams::seed.
  vtkSetMacro(Seed, int);
  vtkGetMacro(Seed, int);
  ///@}

  ///@{
  /// With a periodic box (field data `PeriodicBoxVectors`, as the trajectory reader gives),
  /// move whole molecules by box vectors so that the assembly (a vesicle split by the box's
  /// faces) is in one piece around its periodic mean (mesolens::assembly_shifts); the output
  /// atoms are moved too. Default on.
  vtkSetMacro(MakeAssemblyWhole, bool);
  vtkGetMacro(MakeAssemblyWhole, bool);
  vtkBooleanMacro(MakeAssemblyWhole, bool);
  ///@}

  ///@{
  /// Vertices of the structure mesh made from the molecules when no structure is connected;
  /// see mesolens::StructureMeshParams::vertices.
  vtkSetClampMacro(StructureVertices, int, 4, 1000000);
  vtkGetMacro(StructureVertices, int);
  ///@}

  ///@{
  /// How far along the local normal the made structure looks for a bilayer's other leaflet
  /// when it pairs the leaflets onto their middle sheet; see
  /// mesolens::StructureMeshParams::mid_surface_radius (the filter takes [0, 1e6]).
  vtkSetClampMacro(StructureMidSurfaceRadius, double, 0.0, 1e6);
  vtkGetMacro(StructureMidSurfaceRadius, double);
  ///@}

  ///@{
  /// Output only the visible atoms (and the bonds between them) instead of all atoms with the
  /// `Visible` mask. Default off (the mask suits vtkMesoAtomMapper best: no new positions).
  vtkSetMacro(ExtractVisibleAtoms, bool);
  vtkGetMacro(ExtractVisibleAtoms, bool);
  vtkBooleanMacro(ExtractVisibleAtoms, bool);
  ///@}

  ///@{
  /// Which molecules may be hidden: those whose every atom this selection matches (the language
  /// of mesolens/molecules/atom_selection.h, e.g. "lipid and not resname CHOL"; coordinates in
  /// the input's units); the others always show, and the fractions apply to the molecules that
  /// may be hidden. Needs a MesoLens reader's atom arrays (`AtomName`, `ResidueIndex`). Default
  /// "": every molecule. A bad expression is an error and empties the outputs.
  vtkSetStdStringFromCharMacro(HideableSelection);
  vtkGetCharFromStdStringMacro(HideableSelection);
  ///@}

  /// Molecules whose first atom has residue name `residue` (e.g. "CHOL") get their own
  /// fraction hidden, [0, 1] (clamped), instead of FractionHidden.
  void SetFractionHiddenOfResidue(const char* residue, double fraction);
  /// Forgets every per-residue fraction.
  void RemoveAllResidueFractions();

  /// How many times molecules were assigned to the structure (each costs a closest-point
  /// search per molecule): once for a structure and a set of molecules.
  int GetNumberOfAssignments() const;

  /// How many times the removal order was made (a sort of the molecules in the cut): once per
  /// cut, K, inversion, mode, seed and frame; a new FractionHidden reuses it.
  int GetNumberOfOrderings() const;

  vtkMTimeType GetMTime() override;

protected:
  vtkMesoStructuredCutaway();
  ~vtkMesoStructuredCutaway() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  /// Streaming one process's pieces: every piece computes on the whole input (see
  /// vtkMesoAtomPieces::GatheredInput).
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector** inputVector,
                          vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
                  vtkInformationVector* outputVector) override;

  // Set by the constructor from mesolens::CutawayParams' and mesolens::StructureMeshParams'
  // defaults.
  double K;
  double FractionHidden;
  bool Inverted;
  bool RandomOrder;
  bool ProbabilisticOrder;
  int Seed;
  int StructureVertices;
  double StructureMidSurfaceRadius;
  // The filter's own.
  vtkImplicitFunction* CutFunction = nullptr;
  bool MakeAssemblyWhole = true;
  bool ExtractVisibleAtoms = false;
  std::string HideableSelection;

private:
  vtkMesoStructuredCutaway(const vtkMesoStructuredCutaway&) = delete;
  void operator=(const vtkMesoStructuredCutaway&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
