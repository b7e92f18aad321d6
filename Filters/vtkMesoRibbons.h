// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * @class   vtkMesoRibbons
 * @brief   Protein and nucleic-acid cartoons: B-spline ribbons through the Cα (and P) atoms,
 *          helices as wide ribbons or cylinders, strands as arrows, coil as tubes.
 *
 * Input: atoms as the MesoLens readers give them, best after vtkMesoSecondaryStructure (its
 * `SecondaryStructure` array chooses each residue's shape; without it every residue is coil).
 * Amino acids are traced through their CA atoms and oriented by their carbonyl O (Cα-only
 * chains by the curve); nucleotides through their P atoms as tubes. The geometry is
 * mesolens::ribbon_mesh: an interpolating cubic spline per continuous piece of chain (broken
 * where Cα are more than 4.2 Å apart, or P more than 8 Å, and between chains), strand frames
 * without flips, arrowheads at every strand end, smooth changes between shapes, closed pieces
 * with per-vertex normals.
 *
 * Output: triangles with point normals and, per vertex, `AtomId` (the input row of its
 * residue's CA or P atom), `ResidueIndex`, `SecondaryStructure` (its residue's code),
 * `ChainIndex` (0-based, in order), and a copy of every numeric point array of the input taken
 * from that atom (`BFactor`, `ResidueNumber`, `MoleculeId`, ...): any of them colours the
 * ribbon through a vtkPolyDataMapper.
 *
 * Level of detail: Subdivisions samples per residue (2 coarse, 12 for figures), or per piece
 * of chain from SetSegmentSubdivisions (one count per piece, in the order of the output's field
 * data `SegmentBounds`, 6 values per piece, and `SegmentResidueCounts`):
 * vtkMesoRibbonLevelOfDetail (rendering module) sets them from each piece's size on screen and
 * the frame time, as BioBrowser did.
 *
 * Errors (atoms without `AtomName` or `ResidueIndex`, a non-finite coordinate) are reported
 * with vtkErrorMacro and give an empty output; input without amino acids or nucleotides gives
 * an empty output without an error.
 */
#ifndef vtkMesoRibbons_h
#define vtkMesoRibbons_h

#include "MesoLensFiltersModule.h"
#include "vtkPolyDataAlgorithm.h"

#include <memory>

class vtkIntArray;

class MESOLENSFILTERS_EXPORT vtkMesoRibbons : public vtkPolyDataAlgorithm
{
public:
  static vtkMesoRibbons* New();
  vtkTypeMacro(vtkMesoRibbons, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Spline samples per residue; see mesolens::RibbonParams::subdivisions (the filter takes at
  /// most 32).
  vtkSetClampMacro(Subdivisions, int, 1, 32);
  vtkGetMacro(Subdivisions, int);
  ///@}

  ///@{
  /// Vertices around each cross-section; see mesolens::RibbonParams::tube_sides (the filter
  /// takes at most 64).
  vtkSetClampMacro(TubeSides, int, 3, 64);
  vtkGetMacro(TubeSides, int);
  ///@}

  ///@{
  /// Helices of 4 or more residues as straight cylinders instead of wide ribbons; see
  /// mesolens::RibbonParams::helix_as_cylinder.
  vtkSetMacro(HelixAsCylinder, bool);
  vtkGetMacro(HelixAsCylinder, bool);
  vtkBooleanMacro(HelixAsCylinder, bool);
  ///@}

  ///@{
  /// Shape: helix and strand ribbon widths, ribbon thickness, coil tube radius, nucleic-acid
  /// tube radius, helix cylinder radius and the arrowhead's width over the strand width; see
  /// mesolens::RibbonParams' helix_width, strand_width, ribbon_thickness, coil_radius,
  /// nucleic_radius, cylinder_radius and arrow_width_factor (the filter takes lengths in
  /// [0.01, 20] and arrowheads up to 4).
  vtkSetClampMacro(HelixWidth, double, 0.01, 20.0);
  vtkGetMacro(HelixWidth, double);
  vtkSetClampMacro(StrandWidth, double, 0.01, 20.0);
  vtkGetMacro(StrandWidth, double);
  vtkSetClampMacro(RibbonThickness, double, 0.01, 20.0);
  vtkGetMacro(RibbonThickness, double);
  vtkSetClampMacro(CoilRadius, double, 0.01, 20.0);
  vtkGetMacro(CoilRadius, double);
  vtkSetClampMacro(NucleicRadius, double, 0.01, 20.0);
  vtkGetMacro(NucleicRadius, double);
  vtkSetClampMacro(CylinderRadius, double, 0.01, 20.0);
  vtkGetMacro(CylinderRadius, double);
  vtkSetClampMacro(ArrowWidthFactor, double, 1.0, 4.0);
  vtkGetMacro(ArrowWidthFactor, double);
  ///@}

  ///@{
  /// Samples per residue for each piece of chain (values clamped to [1, 32]), in the order of
  /// `SegmentBounds`; nullptr (default), or a count that no longer matches the pieces: Subdivisions
  /// everywhere.
  void SetSegmentSubdivisions(vtkIntArray* subdivisions);
  vtkGetObjectMacro(SegmentSubdivisions, vtkIntArray);
  ///@}

  vtkMTimeType GetMTime() override;

protected:
  vtkMesoRibbons();
  ~vtkMesoRibbons() override;

  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
                  vtkInformationVector* outputVector) override;

  // Set by the constructor from mesolens::RibbonParams' defaults.
  int Subdivisions;
  int TubeSides;
  bool HelixAsCylinder;
  double HelixWidth;
  double StrandWidth;
  double RibbonThickness;
  double CoilRadius;
  double NucleicRadius;
  double CylinderRadius;
  double ArrowWidthFactor;
  // The filter's own.
  vtkIntArray* SegmentSubdivisions = nullptr;

private:
  vtkMesoRibbons(const vtkMesoRibbons&) = delete;
  void operator=(const vtkMesoRibbons&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
