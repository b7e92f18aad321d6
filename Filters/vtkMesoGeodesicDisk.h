// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * @class   vtkMesoGeodesicDisk
 * @brief   The geodesic disk of radius r around a picked point of a surface mesh.
 *
 * The membrane-mapping paper's first step. Fast marching (Kimmel-Sethian, with obtuse corners
 * unfolded) from the surface point closest to SeedPoint measures geodesic distances; the mesh is
 * cut exactly on the isoline d = Radius. The output is a topological disk (one boundary loop,
 * Euler characteristic 1): small holes left by the front are closed; a disk that reaches a
 * boundary of the mesh, wraps a handle or covers a whole closed component is an error. Only the
 * triangles within Radius of the seed are visited. Where they are coarser than the disk needs
 * to hold about MinimumTriangles triangles (cell meshes are coarse next to a membrane patch),
 * they are bisected, longest edge first, with the new points on the smooth surface through the
 * input's vertices (curved PN triangles, mesolens::SmoothSurface): the input's vertices stay
 * put. Field data RefinementLevels is the most times an input triangle was halved.
 *
 * Input: a triangle mesh (vtkPolyData polygons, all triangles; a clean 2-manifold). The solver
 * set up for it is kept, so changing only the seed or the radius re-marches without rebuilding.
 * Output: the disk (double points, triangles) with point data `GeodesicDistance` (mesh units)
 * and `OriginalPointId` (input point id, -1 for points made by the cut or the refinement), and
 * field data `GeodesicRadius`, `RefinementLevels`, `HolesClosed`, `SeedTriangle`,
 * `SeedBarycentric` (3) and `SeedPosition` (3).
 *
 * Errors (a seed farther than SeedTolerance from the surface, a radius <= 0 or too large, a
 * non-manifold or degenerate mesh, NaN) are reported with vtkErrorMacro, the output is empty and
 * the update fails.
 */
#ifndef vtkMesoGeodesicDisk_h
#define vtkMesoGeodesicDisk_h

#include "MesoLensFiltersModule.h"
#include "vtkPolyDataAlgorithm.h"

#include <memory>

class MESOLENSFILTERS_EXPORT vtkMesoGeodesicDisk : public vtkPolyDataAlgorithm
{
public:
  static vtkMesoGeodesicDisk* New();
  vtkTypeMacro(vtkMesoGeodesicDisk, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The picked point (mesh units); the disk grows from the closest surface point.
  /// Default (0, 0, 0).
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
  /// Geodesic radius r (mesh units); must be > 0 (mesolens::GeodesicDiskParams::radius, which
  /// has no default). Default 1.
  vtkSetMacro(Radius, double);
  vtkGetMacro(Radius, double);
  ///@}

  ///@{
  /// Refine coarse triangles so that the disk holds at least about this many; see
  /// mesolens::GeodesicDiskParams::min_triangles.
  vtkSetClampMacro(MinimumTriangles, int, 0, VTK_INT_MAX);
  vtkGetMacro(MinimumTriangles, int);
  ///@}

  ///@{
  /// On meshes of more than 16 000 triangles, a disk over more than this many of them is grown
  /// on a coarser copy of the mesh (its vertices are input vertices; OriginalPointId says
  /// which); see mesolens::GeodesicDiskParams::max_triangles.
  vtkSetClampMacro(MaximumTriangles, int, 0, VTK_INT_MAX);
  vtkGetMacro(MaximumTriangles, int);
  ///@}

protected:
  vtkMesoGeodesicDisk();
  ~vtkMesoGeodesicDisk() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  // Set by the constructor from mesolens::GeodesicDiskParams' defaults.
  int MinimumTriangles;
  int MaximumTriangles;
  // The filter's own.
  double SeedPoint[3] = { 0, 0, 0 };
  double SeedTolerance = 0;
  double Radius = 1;

private:
  vtkMesoGeodesicDisk(const vtkMesoGeodesicDisk&) = delete;
  void operator=(const vtkMesoGeodesicDisk&) = delete;

  struct Cache;
  std::unique_ptr<Cache> Solver;
};

#endif
