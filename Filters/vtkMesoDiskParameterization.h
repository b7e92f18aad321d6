// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * @class   vtkMesoDiskParameterization
 * @brief   Maps a disk-shaped mesh onto the planar disk of radius r (mean-value coordinates).
 *
 * The membrane-mapping paper's second step: the boundary loop goes onto the circle of radius r
 * by arc length, the interior by Floater's mean-value weights (a sparse solve with Eigen). The
 * output is the input with texture coordinates `TextureCoordinates` (u, v in the units of r,
 * the active TCoords), cell data `AngleDistortion` (ratio of the map's singular values, 1 =
 * conformal) and `AreaDistortion` (area ratio over the disk's mean, 1 = equiareal), and field
 * data `ParameterizationRadius`, `FlippedTriangles` and `Bijective` (1 when no triangle flipped).
 *
 * Radius <= 0 takes the input's field data `GeodesicRadius` (from vtkMesoGeodesicDisk). A mesh
 * that is not a topological disk, or has no radius, is an error: vtkErrorMacro, empty output,
 * failed update.
 */
#ifndef vtkMesoDiskParameterization_h
#define vtkMesoDiskParameterization_h

#include "MesoLensFiltersModule.h"
#include "vtkPolyDataAlgorithm.h"

class MESOLENSFILTERS_EXPORT vtkMesoDiskParameterization : public vtkPolyDataAlgorithm
{
public:
  static vtkMesoDiskParameterization* New();
  vtkTypeMacro(vtkMesoDiskParameterization, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Radius of the target disk (units of the texture coordinates); <= 0: the input's
  /// GeodesicRadius. Default 0.
  vtkSetMacro(Radius, double);
  vtkGetMacro(Radius, double);
  ///@}

protected:
  vtkMesoDiskParameterization() = default;
  ~vtkMesoDiskParameterization() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double Radius = 0;

private:
  vtkMesoDiskParameterization(const vtkMesoDiskParameterization&) = delete;
  void operator=(const vtkMesoDiskParameterization&) = delete;
};

#endif
