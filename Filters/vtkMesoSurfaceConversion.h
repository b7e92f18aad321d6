// SPDX-License-Identifier: GPL-3.0-or-later
// Conversions between vtkPolyData triangle meshes and Core's TriangleMesh, and the cached
// geodesic solver the surface filters share (private to MesoLensFilters).
#ifndef vtkMesoSurfaceConversion_h
#define vtkMesoSurfaceConversion_h

#include "mesolens/mapping/geodesic_disk.h"
#include "mesolens/mapping/harmonic_parameterization.h"
#include "mesolens/mapping/membrane_mapper.h"
#include "mesolens/mesh/triangle_mesh.h"

#include <vtkFloatArray.h>
#include <vtkSmartPointer.h>
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

/// Sets the points of `output` to `points` (3 per vertex) as floats, and returns `normals` (3 per
/// vertex) as a float array named Normals for the caller to attach; both converted in parallel.
vtkSmartPointer<vtkFloatArray> SetFloatPoints(const std::vector<double>& points,
                                              const std::vector<double>& normals,
                                              vtkPolyData* output);

/// Sets the polygons of `output` to `triangles` (3 vertex indices each), written in parallel
/// straight into the cell array's memory: meshes can have millions of triangles.
void SetTriangles(const std::vector<std::int64_t>& triangles, vtkPolyData* output);

/// The mapping chain (mesolens::MembraneMapper) for the surface of one filter, rebuilt only
/// when the surface changes.
class SurfaceMapper
{
public:
  /// The mapper for `surface`, whose content last changed at `surfaceTime`. Throws as
  /// ToTriangleMesh and mesolens::MembraneMapper do.
  const mesolens::MembraneMapper& For(vtkPolyData* surface, vtkMTimeType surfaceTime);

private:
  std::unique_ptr<mesolens::MembraneMapper> Mapper;
  vtkMTimeType Time = 0;
};

/// Adds the disk's arrays to an output made by FromTriangleMesh: point data GeodesicDistance
/// OriginalPointId and Normals; field data GeodesicRadius, RefinementLevels, HolesClosed,
/// SeedTriangle, SeedBarycentric (3) and SeedPosition (3).
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
