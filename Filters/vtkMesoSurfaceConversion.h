// SPDX-License-Identifier: GPL-3.0-or-later
// Conversions between vtkPolyData triangle meshes and Core's TriangleMesh, and the cached
// geodesic solver the surface filters share (private to MesoLensFilters).
#ifndef vtkMesoSurfaceConversion_h
#define vtkMesoSurfaceConversion_h

#include "mesolens/geodesic_disk.h"
#include "mesolens/harmonic_parameterization.h"
#include "mesolens/triangle_mesh.h"

#include <vtkType.h>

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

class vtkPolyData;

namespace vtkMesoSurfaceConversion {

/// The triangles of `surface` (its polygons, which must all be triangles). Throws
/// mesolens::InvalidInput naming the problem (no triangles, polygons with more corners, strips).
mesolens::TriangleMesh ToTriangleMesh(vtkPolyData* surface);

/// Fills `output` with the points (double) and triangles of `mesh`.
void FromTriangleMesh(const mesolens::TriangleMesh& mesh, vtkPolyData* output);

/// Sets the polygons of `output` to `triangles` (3 vertex indices each), written in parallel
/// straight into the cell array's memory: meshes can have millions of triangles.
void SetTriangles(const std::vector<std::int64_t>& triangles, vtkPolyData* output);

/// A geodesic solver for the surface of one filter, rebuilt only when the surface changes, and
/// the disk grown from a seed given as a 3D point.
class GeodesicDiskBuilder
{
public:
  /// Builds (or reuses) the solver for `surface`, whose content last changed at `surfaceTime`.
  void SetSurface(vtkPolyData* surface, vtkMTimeType surfaceTime);

  /// The disk around the surface point closest to `seed` (mesh units). `seedTolerance` > 0 is
  /// how far the seed may be from the surface; <= 0 allows 2 % of the surface's bounding-box
  /// diagonal. Throws mesolens::InvalidInput for a seed too far from the surface.
  mesolens::GeodesicDisk Disk(const double seed[3], double seedTolerance,
                              const mesolens::GeodesicDiskParams& params) const;

private:
  std::shared_ptr<mesolens::GeodesicSolver> Solver;
  vtkMTimeType SolverTime = 0;
  double Diagonal = 0;
};

/// Adds the disk's arrays to an output made by FromTriangleMesh: point data GeodesicDistance
/// and OriginalPointId; field data GeodesicRadius, RefinementLevels, HolesClosed, SeedTriangle,
/// SeedBarycentric (3) and SeedPosition (3).
void AddDiskArrays(const mesolens::GeodesicDisk& disk, double radius, vtkPolyData* output);

/// Adds a parameterization to a disk output: TCoords `TextureCoordinates`, cell data
/// `AngleDistortion` and `AreaDistortion`, field data `ParameterizationRadius`,
/// `FlippedTriangles` and `Bijective`.
void AddParameterizationArrays(const mesolens::DiskParameterization& map, double radius,
                               vtkPolyData* output);

/// The seed stored by AddDiskArrays (triangle -1 when absent).
mesolens::SurfacePoint SeedOf(vtkPolyData* disk);

}

#endif
