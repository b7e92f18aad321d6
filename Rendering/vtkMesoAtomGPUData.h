// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * @class   vtkMesoAtomGPUData
 * @brief   What vtkMesoAtomMapper puts on the GPU, computed from its inputs on the CPU.
 *
 * Per atom: the position (3 floats), 2 type bytes (element for the radius table, index into the
 * colour table) and, for molecule instancing, a 2-byte molecule slot. Per bond: 2 atom indices.
 * Tables: 128 radii (scene units, by element), 256 RGBA colours (elements 0..127, or 255 steps
 * of a lookup table plus its NaN colour at 255). Warp: the per-tile polynomial (10 texels per
 * tile) or the per-molecule rigid motions (3 texels each) and the patch frame uniforms.
 *
 * A visibility mask (a point array, 0 = hidden; e.g. vtkMesoStructuredCutaway's `Visible`)
 * hides atoms by giving them the element HiddenElement, whose radius is 0 (the bond pass skips
 * bonds to them): a new mask changes the type bytes only, never the positions or the bonds.
 *
 * For occlusion culling the atoms may be grouped into spatial cells (GroupIntoCells): then
 * every per-atom buffer and the bond indices are in "slot" order, the atoms of each cell
 * adjacent (mesolens::AtomCells), and CellBoxes holds each cell's box of atom centres. With a
 * warp, the cells are the patch's and WarpedAtoms carries them into every tile.
 */
#ifndef vtkMesoAtomGPUData_h
#define vtkMesoAtomGPUData_h

#include "mesolens/mapping/membrane_warp.h"
#include "mesolens/mapping/warped_cells.h"
#include "mesolens/render/atom_cells.h"

#include <vtkType.h>

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

class vtkDataArray;
class vtkMapper;
class vtkScalarsToColors;
class vtkPolyData;

class vtkMesoAtomGPUData
{
public:
  /// WarpMethod without a warp (otherwise a mesolens::MappingMethod's value).
  static constexpr int NoWarp = -1;

  /// The mapper's radius settings (see vtkMesoAtomMapper).
  struct Style
  {
    int Style = 0;
    double RadiusScale = 1;
    double BallScale = 0.25;
    double BondRadius = 0.2;
  };

  /// Recomputes everything from the atoms, the optional warp input and the mapper's colouring
  /// settings. With `atoms_per_cell` > 0, the atoms (the patch's, with a warp) are grouped into
  /// cells of about that many atoms (kept for new positions of the same atoms while the cells stay
  /// compact). Returns false, with an error reported on `mapper` and AtomCount 0, for inputs it
  /// cannot draw.
  bool Update(vtkPolyData* atoms, vtkPolyData* warp, const Style& style, vtkMapper* mapper,
              std::size_t atoms_per_cell = 0, const char* mask_name = nullptr);

  /// The type byte of hidden atoms: an element of radius 0 (input elements are clamped below).
  static constexpr unsigned char HiddenElement = 127;

  /// Bounds of what is drawn (warped tiles in warp mode), padded by `pad`. Leaves `bounds` as
  /// it is when there is nothing to draw.
  static void PaddedBounds(vtkPolyData* atoms, vtkPolyData* warp, double pad, double bounds[6]);

  /// The largest radius of the elements present among the atoms, scene units.
  static double LargestRadius(vtkPolyData* atoms, const Style& style);

  /// Radius per element (index 0..127) for a style, scene units; 1.0 x scale for element 0.
  static std::vector<float> StyleRadii(const Style& style);

  vtkIdType AtomCount = 0;
  vtkIdType TileCount = 1;
  const float* PositionData = nullptr;   ///< 3 per atom (the input's, or PositionStorage)
  mesolens::AtomCells Cells;             ///< empty: not grouped, slot = input index
  std::vector<std::uint32_t> SlotOfAtom; ///< input index -> slot (grouped only)
  std::vector<float> CellBoxes;          ///< 6 per cell: box of the atom centres
  /// Warp and cells: the cells' atoms in every tile (tile-major) and their boxes, for
  /// culling (valid until the next Update); null when the tiles hold 2^32 atoms or more.
  std::unique_ptr<mesolens::WarpedCellAtoms> WarpedAtoms;
  unsigned long CellsVersion = 0;   ///< counts groupings (SlotOfAtom changes)
  float LargestPresentRadius = 0;   ///< of the elements present, scene units
  std::vector<unsigned char> Types; ///< 2 per atom
  /// 1 per atom (slot order): its molecule's index among the patch's (first appearance, which is
  /// also the order of an instancing warp's instances); with a warp whose patch has molecules
  std::vector<unsigned short> MoleculeSlots;
  unsigned long MoleculeSlotsVersion = 0; ///< counts recomputations of MoleculeSlots
  std::vector<unsigned int> Bonds;
  unsigned long TypesVersion = 0;     ///< counts recomputations of Types and ColorTable
  unsigned long PositionsVersion = 0; ///< counts changes of the positions (PositionData)
  vtkIdType HiddenAtoms = 0;          ///< atoms hidden by the mask
  unsigned long BondsVersion = 0;     ///< counts recomputations of Bonds           ///< 2 per bond
  std::vector<float> Radii;           ///< 128
  float BondRadius = 0;               ///< scene units
  std::vector<float> ColorTable;      ///< 256 RGBA

  int WarpMethod = NoWarp;     ///< static_cast<int>(mesolens::MappingMethod) of the warp, or NoWarp
  mesolens::MembraneWarp Warp; ///< the warp input's (drawable when WarpMethod is set)
  std::vector<float> WarpTexels; ///< RGBA texels
  unsigned long WarpVersion = 0; ///< counts readings of the warp (WarpTexels, MoleculeSlots)
  float PatchOrigin[2] = { 0, 0 };
  float PatchToFractional[4] = { 1, 0, 0, 1 }; ///< column-major 2 x 2
  float PatchCentreHeight = 0;
  float InverseLayerHalfThickness = 1;
  int TileCountForHeader = 0; ///< polynomial: header texels (one per tile) before the pieces
  int MoleculesPerTile = 0;   ///< the patch's molecules (with MoleculeSlots)
  /// Warp: a bit per molecule and tile (tile t's molecule m is bit t MoleculesPerTile + m),
  /// set where the warp input's point array of the mask's name is 0 (vtkMesoStructuredCutaway's
  /// `Visible` of the mapping's molecule centres); empty: no such mask.
  std::vector<std::uint32_t> MoleculeMask;
  unsigned long MoleculeMaskVersion = 0; ///< counts readings of MoleculeMask
  vtkIdType HiddenInTiles = 0;           ///< atoms of all tiles hidden by MoleculeMask
  /// The warp input is an assembly's copies (a tile per copy, a molecule per atom class; the
  /// mask hides the classes a copy leaves out) rather than a membrane mapping.
  bool AssemblyCopies = false;

  /// Whether the GPU needs MoleculeSlots: instancing, or a molecule mask.
  bool UsesMoleculeSlots() const
  {
    return !this->MoleculeSlots.empty() &&
      (this->WarpMethod == static_cast<int>(mesolens::MappingMethod::MoleculeInstancing) ||
       !this->MoleculeMask.empty());
  }

private:
  /// What the types (bonds) were computed from; equal keys mean nothing to recompute.
  struct ArrayKey
  {
    const void* Array = nullptr;
    vtkMTimeType ArrayTime = 0;
    const void* Scalars = nullptr;
    vtkMTimeType ScalarsTime = 0;
    vtkMTimeType MapperTime = 0;
    vtkIdType Atoms = 0;
    bool operator==(const ArrayKey& other) const
    {
      return this->Array == other.Array && this->ArrayTime == other.ArrayTime &&
        this->Scalars == other.Scalars && this->ScalarsTime == other.ScalarsTime &&
        this->MapperTime == other.MapperTime && this->Atoms == other.Atoms;
    }
  };

  /// Where atom `atom` of the input is in the buffers.
  std::size_t SlotOf(vtkIdType atom) const
  {
    return this->SlotOfAtom.empty() ? static_cast<std::size_t>(atom)
                                    : this->SlotOfAtom[static_cast<std::size_t>(atom)];
  }
  bool UpdatePositions(vtkPolyData* atoms, vtkMapper* mapper, std::size_t atoms_per_cell);
  void UpdateTypes(vtkPolyData* atoms, vtkMapper* mapper, vtkDataArray* mask);
  bool UpdateBonds(vtkPolyData* atoms, vtkMapper* mapper);
  /// UnmaskedTypes and ColorTable from the element numbers and the colour array.
  void ComputeTypes(vtkMapper* mapper, vtkDataArray* numbers, vtkDataArray* scalars,
                    vtkScalarsToColors* table);
  bool ReadWarp(vtkPolyData* atoms, vtkPolyData* warp, vtkMapper* mapper);
  /// MoleculeSlots, MoleculesPerTile and MoleculeSizes from the patch's MoleculeId.
  bool ReadPatchMolecules(vtkPolyData* atoms, const mesolens::MembraneWarp& warp,
                          vtkMapper* mapper);
  /// MoleculeMask from the warp input's points (one per molecule and tile, or none).
  bool ReadMoleculeMask(vtkPolyData* warp, vtkMapper* mapper, const char* mask_name);
  /// MoleculeSlots (slot order), PatchMolecules and MoleculeSizes from each input atom's
  /// molecule index (< MoleculesPerTile, set first).
  void SetMoleculeSlots(const std::vector<unsigned short>& slot_of_atom);
  /// The warp, the molecule slots (atom classes) and the mask of an assembly's copies.
  bool ReadAssembly(vtkPolyData* atoms, vtkPolyData* copies, vtkMapper* mapper);
  /// WarpedAtoms from the cells and the warp just read (none without cells).
  bool CarryCellsIntoTiles(vtkMapper* mapper);
  void ClearWarp();
  void Clear();

  std::vector<float> PositionStorage;
  std::vector<unsigned char> UnmaskedTypes; ///< Types before the mask
  ArrayKey MaskKey;                         ///< the mask that Types has
  ArrayKey PositionsKey;                    ///< coordinates array, time, count, cell size
  std::vector<bool> ElementPresent;
  double GroupedDiagonal = 0; ///< total_cell_diagonal when the cells were made
  ArrayKey TypesKey;
  ArrayKey BondsKey;
  /// What the warp was read from: its field arrays, the patch's molecules and cells.
  std::vector<std::pair<const void*, vtkMTimeType>> WarpKey;
  vtkIdType PatchMolecules = 0;         ///< molecules per tile, 0: none known
  std::vector<vtkIdType> MoleculeSizes; ///< atoms per molecule
  ArrayKey MoleculeMaskKey;
};

#endif
