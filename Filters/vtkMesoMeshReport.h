// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * @class   vtkMesoMeshReport
 * @brief   Checks a triangle mesh: boundary loops, non-manifold edges and vertices,
 *          inconsistent orientation, degenerate triangles, components, Euler characteristic.
 *
 * A pass-through filter: the output is the input plus
 * - cell array `DegenerateTriangle` (unsigned char, 1 = zero area, repeated vertex, index out of
 *   range or non-finite vertex), point array `NonManifoldVertex` (unsigned char);
 * - field data with one value each: `NumberOfBoundaryEdges`, `NumberOfBoundaryLoops`,
 *   `NumberOfNonManifoldEdges`, `NumberOfNonManifoldVertices`,
 *   `NumberOfInconsistentlyOrientedEdges`, `NumberOfDegenerateTriangles`,
 *   `NumberOfUnreferencedVertices`, `NumberOfComponents`, `EulerCharacteristic`.
 * The same numbers are available from the getters after an update, or from Analyze() without a
 * pipeline; GetDefectsDescription() lists the defects in words, for filters that refuse bad
 * input. Only triangles are analysed; other cells are counted in NumberOfNonTriangleCells.
 */
#ifndef vtkMesoMeshReport_h
#define vtkMesoMeshReport_h

#include "MesoLensFiltersModule.h"
#include "vtkPolyDataAlgorithm.h"

#include <string>
#include <vector>

class MESOLENSFILTERS_EXPORT vtkMesoMeshReport : public vtkPolyDataAlgorithm
{
public:
  static vtkMesoMeshReport* New();
  vtkTypeMacro(vtkMesoMeshReport, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Analyses `mesh` and stores the results in this object (no pipeline update).
  /// Returns true when the mesh is a manifold without degenerate triangles.
  bool Analyze(vtkPolyData* mesh);

  ///@{
  /// Results of the last analysis.
  vtkGetMacro(NumberOfPoints, vtkIdType);
  vtkGetMacro(NumberOfTriangles, vtkIdType);
  vtkGetMacro(NumberOfNonTriangleCells, vtkIdType);
  vtkGetMacro(NumberOfEdges, vtkIdType);
  vtkGetMacro(NumberOfBoundaryEdges, vtkIdType);
  vtkGetMacro(NumberOfBoundaryLoops, vtkIdType);
  vtkGetMacro(NumberOfNonManifoldEdges, vtkIdType);
  vtkGetMacro(NumberOfNonManifoldVertices, vtkIdType);
  vtkGetMacro(NumberOfInconsistentlyOrientedEdges, vtkIdType);
  vtkGetMacro(NumberOfDegenerateTriangles, vtkIdType);
  vtkGetMacro(NumberOfUnreferencedVertices, vtkIdType);
  vtkGetMacro(NumberOfComponents, vtkIdType);
  vtkGetMacro(EulerCharacteristic, vtkIdType);
  ///@}

  /// True when the last mesh was a manifold (boundary allowed) without degenerate triangles.
  vtkGetMacro(IsManifold, bool);
  /// True when, in addition, it was closed and consistently oriented.
  vtkGetMacro(IsClosedManifold, bool);

  /// The defects of the last mesh, one per line ("4 boundary edges in 1 loops"); "" if clean.
  const char* GetDefectsDescription()
  {
    return this->DefectsDescription.c_str();
  }

protected:
  vtkMesoMeshReport() = default;
  ~vtkMesoMeshReport() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkMesoMeshReport(const vtkMesoMeshReport&) = delete;
  void operator=(const vtkMesoMeshReport&) = delete;

  void AddResultsTo(vtkPolyData* output) const;

  vtkIdType NumberOfPoints = 0;
  vtkIdType NumberOfTriangles = 0;
  vtkIdType NumberOfNonTriangleCells = 0;
  vtkIdType NumberOfEdges = 0;
  vtkIdType NumberOfBoundaryEdges = 0;
  vtkIdType NumberOfBoundaryLoops = 0;
  vtkIdType NumberOfNonManifoldEdges = 0;
  vtkIdType NumberOfNonManifoldVertices = 0;
  vtkIdType NumberOfInconsistentlyOrientedEdges = 0;
  vtkIdType NumberOfDegenerateTriangles = 0;
  vtkIdType NumberOfUnreferencedVertices = 0;
  vtkIdType NumberOfComponents = 0;
  vtkIdType EulerCharacteristic = 0;
  bool IsManifold = false;
  bool IsClosedManifold = false;
  std::string DefectsDescription;
  std::vector<unsigned char> DegenerateFlags;  // per cell of the analysed mesh
  std::vector<unsigned char> NonManifoldFlags; // per point
};

#endif
