// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * @class   vtkMesoAtomMapper
 * @brief   Draws atoms as ray-cast sphere impostors and bonds as ray-cast cylinder impostors,
 *          with exact per-pixel depth and normals; optionally warped onto a cell surface on
 *          the GPU.
 *
 * Input: atoms as points (from vtkMesoStructureReader, vtkMesoTrajectoryReader or
 * vtkMesoMembraneMapping), bonds as 2-point lines, the `AtomicNumber` point array for radii and
 * element colours. Per atom the GPU holds its position (3 floats) and 2 bytes of type (the
 * element, for the radius, and a colour index), 14 bytes in all (16 with molecule instancing);
 * bonds are index pairs into the same positions. Atoms are drawn without a geometry stage: the
 * vertex stage reads each atom from those buffers (as texture buffers) for the three corners of
 * one triangle facing the eye around its silhouette; a geometry shader expands each bond into a
 * quad. The fragment shader intersects the view ray with the sphere (cylinder) and writes the
 * true depth and normal, so atoms and bonds intersect each other and other
 * geometry correctly and VTK's render passes (vtkSSAOPass, vtkShadowMapPass, depth peeling) and
 * hardware picking see real spheres and cylinders. Radius and colour come from tables on the GPU
 * indexed by the type. For an animation (a new time step with the same atoms and bonds) only
 * the positions are uploaded again.
 *
 * Styles (radii in Å, times RadiusScale):
 * - SPACE_FILLING: atoms at their van der Waals radius (Bondi 1964 / Alvarez 2013), no bonds;
 * - BALL_AND_STICK: atoms at BallScale x the van der Waals radius, bonds of BondRadius;
 * - STICKS: atoms and bonds at BondRadius (licorice).
 * Atoms without an `AtomicNumber` array (coarse-grained beads) have radius 1.0 and grey.
 *
 * Colours: Jmol/CPK element colours (vtkMesoElementLookupTable); or, with ScalarVisibility on,
 * ScalarMode USE_POINT_FIELD_DATA and a colour array selected (SelectColorArray), that point
 * array (its first component) through the LookupTable over the ScalarRange (or the table's own
 * range with UseLookupTableScalarRange), in 255 steps; NaN takes the table's NaN colour. Bonds
 * are split at the middle in the colours of their two atoms. The actor's colour multiplies the
 * atom colours (white by default) and its opacity applies (translucent atoms show their back
 * halves first).
 *
 * Membrane warp on the GPU: connect the output 0 of a vtkMesoMembraneMapping that ran with
 * OutputAtoms off to the warp input (SetWarpConnection) and the membrane patch it mapped (the
 * same input 1 of the mapping filter) to this mapper's input. The vertex stage then maps every
 * patch atom and bond end itself, once per tile, and all k x k tiles come from the same patch
 * buffers in one instanced draw call per pass:
 * - POLYNOMIAL: x(s, t, h) from `PolynomialCoefficients` (30 per tile);
 * - MOLECULE_INSTANCING: the rigid motion of the atom's molecule (`InstanceMatrices`, 16 per
 *   molecule and tile), the molecule known by the patch's `MoleculeId` point array.
 * DISPLACEMENT has no GPU form: map the atoms on the CPU (OutputAtoms on) and draw its output.
 * Radii stay in RadiusScale x Å: set RadiusScale to the mapping's MembraneToMeshScale.
 * The warp input's points, when it has any, are the mapping's molecule centres (one per molecule
 * and tile, OutputAtoms off); where their VisibilityArrayName array is 0 (a
 * vtkMesoStructuredCutaway of them between the mapping and this mapper) that molecule is hidden
 * in that tile: the GPU holds a bit per molecule and tile, and a new cut uploads those bits only.
 *
 * Assemblies (SetAssemblyConnection): the input is an asymmetric unit and the assembly input
 * lists its copies (a matrix and an atom set each, vtkMesoAssemblyInstances.h). Every copy is
 * drawn from the same buffers in one instanced draw call per pass, as the tiles of a
 * MOLECULE_INSTANCING warp: a tile per copy, and per tile one motion (the copy's matrix) for
 * each class of atoms that the same atom sets hold (one class when every copy takes every
 * chain); a copy whose set leaves a class out hides it through the per-tile molecule bits. The
 * GPU holds the unit's atoms once (16 bytes each) and 48 bytes per class and copy, plus, as for
 * any input, 4 bytes per atom drawn in the draw lists of culling: for 1m4x's 1680 copies of 9693
 * atoms, 12-13 MB against 240 MB for its 16.3 million atoms expanded (BenchmarkAssemblyDrawing).
 * Culling carries the unit's cells into every copy. Colours, masks and selections apply to the
 * unit, so every copy shows them. Picking reports the unit's atom ids (not the copy).
 *
 * Occlusion culling (OcclusionCulling, on by default; for inputs of at least 8192 atoms, or any
 * input when AtomsPerCell is set; for a warped patch of 256 atoms or more), after Grottel et al.,
 * EuroVis 2010: the atoms are grouped once into compact spatial cells of about AtomsPerCell atoms
 * (their buffers are kept in cell order; a warped patch's cells, about 32 per patch, are carried
 * into every tile: their boxes bounded through the warp in each tile's frame, their atoms warped on
 * the CPU only when tested, mesolens::WarpedCellAtoms). Each frame, per camera:
 * 1. the atoms that were visible in this camera's last frame are drawn (cells out of view are
 *    skipped; a first frame draws the cells that make the nearest surface of what is in view,
 *    mesolens::first_occluders);
 * 2. the depth buffer is read back and reduced to a pyramid of farthest depths, and every atom
 *    of the cells in view is tested against it on the CPU (whole cells first, by their boxes):
 *    the exact outline of its sphere and the depth of its nearest point against the pixels that
 *    outline covers;
 * 3. the atoms that may show and were not drawn in 1 are drawn; what showed is remembered.
 * The picture does not change: an atom left out has no pixel in front of what is drawn. Atoms
 * are drawn from lists of their slots (4 bytes per drawn atom, GetLastDrawListBytesPerAtom; for
 * a warp, entries t n + slot for the atom in that slot of tile t, so tiles x atoms must stay
 * below 2^32, beyond which every atom is drawn). Translucent atoms, picking and multisampled
 * framebuffers (whose depth cannot be read back as it is) draw every atom in view. For a new time
 * step the cells stay while the atoms stay near them (they are regrouped when the boxes have grown
 * by half). Picking draws the atoms in input order through a table of their cell-order slots (4
 * bytes per atom, uploaded for the pick and released at the next plain frame).
 *
 * VTK 9.1's vtkSSAOPass draws black in a renderer whose viewport does not start at the window's
 * origin (with any mapper, VTK's sphere mapper too): give ambient occlusion to the renderer at
 * the lower left, or to a renderer that fills the window.
 *
 * Visibility mask: atoms whose point array VisibilityArrayName (default `Visible`, as
 * vtkMesoStructuredCutaway writes it) is 0 are not drawn, nor their bonds, nor picked. A new mask
 * uploads the 2 type bytes per atom again, not the positions (which go up only when the points
 * change), so a cutaway slider stays cheap.
 *
 * Picking (vtkHardwareSelector, cells): atom i is cell i (its vertex), bond j is the cell of
 * its line, as in the input; in warp mode these are the patch's ids (the tile is not reported).
 *
 * Errors (a warp input without usable coefficients, a patch whose atom count or molecules do
 * not match) are reported with vtkErrorMacro and nothing is drawn.
 */
#ifndef vtkMesoAtomMapper_h
#define vtkMesoAtomMapper_h

#include "MesoLensRenderingModule.h"
#include "vtkOpenGLPolyDataMapper.h"

#include <memory>
#include <string>
#include <vector>

namespace mesolens {
class CellAtoms;
}

class MESOLENSRENDERING_EXPORT vtkMesoAtomMapper : public vtkOpenGLPolyDataMapper
{
public:
  static vtkMesoAtomMapper* New();
  vtkTypeMacro(vtkMesoAtomMapper, vtkOpenGLPolyDataMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Styles
  {
    SPACE_FILLING = 0,
    BALL_AND_STICK = 1,
    STICKS = 2
  };

  ///@{
  /// How atoms are drawn. Default SPACE_FILLING.
  vtkSetClampMacro(Style, int, SPACE_FILLING, STICKS);
  vtkGetMacro(Style, int);
  void SetStyleToSpaceFilling()
  {
    this->SetStyle(SPACE_FILLING);
  }
  void SetStyleToBallAndStick()
  {
    this->SetStyle(BALL_AND_STICK);
  }
  void SetStyleToSticks()
  {
    this->SetStyle(STICKS);
  }
  ///@}

  ///@{
  /// Factor on all radii: scene length units per Å (1e-4 for a scene in µm). Range
  /// [1e-12, 1e12]; default 1.
  vtkSetClampMacro(RadiusScale, double, 1e-12, 1e12);
  vtkGetMacro(RadiusScale, double);
  ///@}

  ///@{
  /// BALL_AND_STICK: atom radius as a fraction of the van der Waals radius. Range [1e-3, 1];
  /// default 0.25.
  vtkSetClampMacro(BallScale, double, 1e-3, 1.0);
  vtkGetMacro(BallScale, double);
  ///@}

  ///@{
  /// Bond radius (and the atom radius of STICKS), Å times RadiusScale. Range [1e-3, 10];
  /// default 0.2.
  vtkSetClampMacro(BondRadius, double, 1e-3, 10.0);
  vtkGetMacro(BondRadius, double);
  ///@}

  /// The warp input: output 0 of a vtkMesoMembraneMapping (POLYNOMIAL or MOLECULE_INSTANCING).
  /// nullptr: draw the input's atoms where they are (default).
  void SetWarpConnection(vtkAlgorithmOutput* output);

  /// The copies of a biological assembly to draw the input in: output 1 of a
  /// vtkMesoStructureReader with an Assembly chosen and ExpandAssembly off, whose output 0 (the
  /// asymmetric unit) is this mapper's input (see Assemblies above). The same input port as
  /// the warp: one or the other. nullptr: draw the input once (default).
  void SetAssemblyConnection(vtkAlgorithmOutput* output);

  ///@{
  /// Skip cells of atoms that are out of view or hidden (see above). Default on.
  vtkSetMacro(OcclusionCulling, bool);
  vtkGetMacro(OcclusionCulling, bool);
  vtkBooleanMacro(OcclusionCulling, bool);
  ///@}

  ///@{
  /// Atoms per culling cell; 0 (default): automatic, n / 1024 clamped to [256, 2048], and only
  /// for inputs of 8192 atoms or more; for a warped patch, n / 32 clamped to [64, 2048], for
  /// patches of 256 atoms or more. Range [0, 1e6].
  vtkSetClampMacro(AtomsPerCell, int, 0, 1000000);
  vtkGetMacro(AtomsPerCell, int);
  ///@}

  ///@{
  /// Factor on how far culling grows its cells' boxes: by the largest atom radius (and, for a
  /// warped patch, the GPU's rounding of the warp). Range [0, 10]; default 1, what keeps the
  /// picture exact. Below 1 the boxes no longer hold the atoms' spheres and atoms at their edges
  /// may be culled wrongly: for checking that a test notices.
  vtkSetClampMacro(CellPaddingFactor, double, 0.0, 10.0);
  vtkGetMacro(CellPaddingFactor, double);
  ///@}

  ///@{
  /// The point array whose zeros hide atoms (any numeric type, first component). Default
  /// "Visible"; nullptr or "": no mask. An input without the array draws every atom.
  vtkSetStringMacro(VisibilityArrayName);
  vtkGetStringMacro(VisibilityArrayName);
  ///@}

  ///@{
  /// Draw only the atoms this selection matches (the language of
  /// mesolens/molecules/atom_selection.h, e.g. "not water and not hydrogen", "within 8 of resname
  /// LIG"), on top of the VisibilityArrayName mask; evaluated on the input (its coordinates,
  /// Å for MesoLens readers) whenever the input or the text changes, so a trajectory is selected
  /// frame by frame. Default "": every atom. A bad expression is an error naming the character,
  /// and then no atom is drawn. Like the mask, a new selection uploads the type bytes only.
  vtkSetStdStringFromCharMacro(AtomSelection);
  vtkGetCharFromStdStringMacro(AtomSelection);
  ///@}

  /// Atoms hidden by the visibility masks at the last buffer update (in all tiles of a warp:
  /// the patch's hidden atoms times the tiles, plus the atoms of the molecules hidden per tile).
  vtkIdType GetHiddenAtomCount() const;

  /// Atoms drawn by the last render (times the tiles in warp mode): fewer than the input's when
  /// culling skipped cells.
  vtkIdType GetLastDrawnAtomCount() const;

  /// Bytes per input atom (of the patch, for a warp) of the draw lists of the last culled
  /// render (4 per drawn atom); 0 without culling.
  double GetLastDrawListBytesPerAtom() const;

  /// Bytes of GPU buffer per atom of the input (positions, types and, for instancing or a
  /// molecule mask, the molecule; after a render), 0 before.
  double GetBufferBytesPerAtom() const;

  /// Bytes of GPU buffer of the warp or the assembly's copies (after a render): 48 per motion
  /// (molecule and tile, or atom class and copy) or 160 per polynomial piece and 16 per tile,
  /// and 1 bit per molecule and tile of a mask. 0 without a warp.
  vtkIdType GetWarpBufferBytes() const;

  /// Bytes uploaded by the last buffer update: the positions alone for a new time step of the
  /// same atoms.
  vtkIdType GetLastUploadBytes() const;

  /// Model-coordinate bounds of what is drawn, padded by the largest radius (the warped tiles
  /// in warp mode).
  void ComputeBounds() override;

  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkMesoAtomMapper();
  ~vtkMesoAtomMapper() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;

  void Render(vtkRenderer* ren, vtkActor* act) override;
  void RenderPieceDraw(vtkRenderer* ren, vtkActor* act) override;
  void RenderPieceFinish(vtkRenderer* ren, vtkActor* act) override;
  void BuildBufferObjects(vtkRenderer* ren, vtkActor* act) override;
  bool GetNeedToRebuildBufferObjects(vtkRenderer* ren, vtkActor* act) override;
  void GetShaderTemplate(std::map<vtkShader::Type, vtkShader*> shaders, vtkRenderer* ren,
                         vtkActor* act) override;
  void ReplaceShaderValues(std::map<vtkShader::Type, vtkShader*> shaders, vtkRenderer* ren,
                           vtkActor* act) override;
  bool GetNeedToRebuildShaders(vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act) override;
  void SetCameraShaderParameters(vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act) override;
  void SetMapperShaderParameters(vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act) override;

  int Style = SPACE_FILLING;
  double RadiusScale = 1;
  double BallScale = 0.25;
  double BondRadius = 0.2;
  bool OcclusionCulling = true;
  int AtomsPerCell = 0;
  double CellPaddingFactor = 1;
  char* VisibilityArrayName = nullptr;
  std::string AtomSelection;

private:
  vtkMesoAtomMapper(const vtkMesoAtomMapper&) = delete;
  void operator=(const vtkMesoAtomMapper&) = delete;

  /// The warp input's data, nullptr when none is connected.
  vtkPolyData* WarpInput();

  /// Draws the atoms that may be visible with the sphere program `spheres` (bound): see
  /// Occlusion culling.
  void DrawVisibleCells(vtkRenderer* ren, vtkActor* act, vtkShaderProgram* spheres);
  /// The same for a warped patch: the patch's cells in every tile.
  void DrawVisibleWarpedCells(vtkRenderer* ren, vtkActor* act, vtkShaderProgram* spheres);
  /// The two passes of culling over `atoms`, whose cells have `boxes` (grown by `padding`).
  void DrawVisibleAtoms(vtkRenderer* ren, vtkActor* act, vtkShaderProgram* spheres,
                        const mesolens::CellAtoms& atoms, const std::vector<float>& boxes,
                        double padding);

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
