// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoSurfaceConversion.h"

#include "vtkMesoArrayNames.h"

#include "mesolens/common/errors.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include "vtkMesoParallelFor.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace vtkMesoSurfaceConversion {

mesolens::TriangleMesh ToTriangleMesh(vtkPolyData* surface)
{
  if (!surface || surface->GetNumberOfPolys() == 0)
  {
    throw mesolens::InvalidInput("the surface has no triangles");
  }
  if (surface->GetNumberOfStrips() > 0)
  {
    throw mesolens::InvalidInput("the surface has triangle strips; apply vtkTriangleFilter first");
  }
  mesolens::TriangleMesh mesh;
  const vtkIdType points = surface->GetNumberOfPoints();
  mesh.points.resize(3 * static_cast<std::size_t>(points));
  for (vtkIdType i = 0; i < points; ++i)
  {
    surface->GetPoint(i, mesh.points.data() + 3 * i);
  }
  mesh.triangles.reserve(3 * static_cast<std::size_t>(surface->GetNumberOfPolys()));
  auto iterator = vtk::TakeSmartPointer(surface->GetPolys()->NewIterator());
  for (iterator->GoToFirstCell(); !iterator->IsDoneWithTraversal(); iterator->GoToNextCell())
  {
    vtkIdType size = 0;
    const vtkIdType* ids = nullptr;
    iterator->GetCurrentCell(size, ids);
    if (size != 3)
    {
      throw mesolens::InvalidInput("the surface has a polygon with " + std::to_string(size) +
                                   " corners; apply vtkTriangleFilter first");
    }
    mesh.triangles.insert(mesh.triangles.end(), { ids[0], ids[1], ids[2] });
  }
  return mesh;
}

void FromTriangleMesh(const mesolens::TriangleMesh& mesh, vtkPolyData* output)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(mesh.vertex_count()));
  for (std::size_t i = 0; i < mesh.vertex_count(); ++i)
  {
    points->SetPoint(static_cast<vtkIdType>(i), mesh.points.data() + 3 * i);
  }
  output->SetPoints(points);
  SetTriangles(mesh.triangles, output);
}

vtkSmartPointer<vtkFloatArray> SetFloatPoints(const std::vector<double>& points,
                                              const std::vector<double>& normals,
                                              vtkPolyData* output)
{
  const auto vertices = static_cast<vtkIdType>(points.size() / 3);
  vtkNew<vtkFloatArray> coordinates;
  coordinates->SetNumberOfComponents(3);
  coordinates->SetNumberOfTuples(vertices);
  auto normal_array = vtkSmartPointer<vtkFloatArray>::New();
  normal_array->SetName(vtkMesoArrayNames::Normals);
  normal_array->SetNumberOfComponents(3);
  normal_array->SetNumberOfTuples(vertices);
  // Straight into the arrays' memory, in parallel: meshes can have millions of vertices.
  float* xyz = coordinates->GetPointer(0);
  float* nxyz = normal_array->GetPointer(0);
  vtkMesoParallelFor::For(0, 3 * vertices, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType i = begin; i < end; ++i)
    {
      xyz[i] = static_cast<float>(points[std::size_t(i)]);
      nxyz[i] = static_cast<float>(normals[std::size_t(i)]);
    }
  });
  vtkNew<vtkPoints> float_points;
  float_points->SetData(coordinates);
  output->SetPoints(float_points);
  return normal_array;
}

void SetTriangles(const std::vector<std::int64_t>& triangles, vtkPolyData* output)
{
  const vtkIdType count = static_cast<vtkIdType>(triangles.size() / 3);
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfValues(count + 1);
  connectivity->SetNumberOfValues(3 * count);
  vtkIdType* offset = offsets->GetPointer(0);
  vtkIdType* corner = connectivity->GetPointer(0);
  vtkMesoParallelFor::For(0, count, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType t = begin; t < end; ++t)
    {
      offset[t] = 3 * t;
      for (int k = 0; k < 3; ++k)
      {
        corner[3 * t + k] = triangles[3 * std::size_t(t) + std::size_t(k)];
      }
    }
  });
  offset[count] = 3 * count;
  vtkNew<vtkCellArray> cells;
  cells->SetData(offsets, connectivity);
  output->SetPolys(cells);
}

const mesolens::MembraneMapper& SurfaceMapper::For(vtkPolyData* surface, vtkMTimeType surfaceTime)
{
  if (!this->Mapper || this->Time != surfaceTime)
  {
    this->Mapper.reset();
    this->Mapper = std::make_unique<mesolens::MembraneMapper>(ToTriangleMesh(surface));
    this->Time = surfaceTime;
  }
  return *this->Mapper;
}

void AddDiskArrays(const mesolens::GeodesicDisk& disk, double radius, vtkPolyData* output)
{
  vtkNew<vtkDoubleArray> distance;
  distance->SetName(vtkMesoArrayNames::GeodesicDistance);
  distance->SetNumberOfValues(static_cast<vtkIdType>(disk.distance.size()));
  vtkNew<vtkIdTypeArray> original;
  original->SetName(vtkMesoArrayNames::OriginalPointId);
  original->SetNumberOfValues(static_cast<vtkIdType>(disk.original_vertex.size()));
  for (std::size_t v = 0; v < disk.distance.size(); ++v)
  {
    distance->SetValue(static_cast<vtkIdType>(v), disk.distance[v]);
    original->SetValue(static_cast<vtkIdType>(v), static_cast<vtkIdType>(disk.original_vertex[v]));
  }
  output->GetPointData()->AddArray(distance);
  output->GetPointData()->AddArray(original);
  vtkNew<vtkDoubleArray> normals;
  normals->SetName(vtkMesoArrayNames::Normals);
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(static_cast<vtkIdType>(disk.normals.size() / 3));
  std::copy(disk.normals.begin(), disk.normals.end(), normals->GetPointer(0));
  output->GetPointData()->SetNormals(normals);
  output->GetPointData()->SetActiveScalars(vtkMesoArrayNames::GeodesicDistance);
  auto add_field = [output](const char* name, std::initializer_list<double> values) {
    vtkNew<vtkDoubleArray> array;
    array->SetName(name);
    array->SetNumberOfComponents(static_cast<int>(values.size()));
    array->SetNumberOfTuples(1);
    int k = 0;
    for (const double value : values)
    {
      array->SetComponent(0, k++, value);
    }
    output->GetFieldData()->AddArray(array);
  };
  add_field(vtkMesoArrayNames::GeodesicRadius, { radius });
  add_field(vtkMesoArrayNames::RefinementLevels, { double(disk.refinement_levels) });
  add_field(vtkMesoArrayNames::HolesClosed, { double(disk.holes_closed) });
  add_field(vtkMesoArrayNames::SeedTriangle, { double(disk.seed.triangle) });
  add_field(vtkMesoArrayNames::SeedBarycentric,
            { disk.seed.barycentric[0], disk.seed.barycentric[1], disk.seed.barycentric[2] });
  add_field(vtkMesoArrayNames::SeedPosition,
            { disk.seed.position[0], disk.seed.position[1], disk.seed.position[2] });
}

void AddParameterizationArrays(const mesolens::DiskParameterization& map, double radius,
                               vtkPolyData* output)
{
  vtkNew<vtkDoubleArray> uv;
  uv->SetName(vtkMesoArrayNames::TextureCoordinates);
  uv->SetNumberOfComponents(2);
  uv->SetNumberOfTuples(static_cast<vtkIdType>(map.uv.size() / 2));
  std::copy(map.uv.begin(), map.uv.end(), uv->GetPointer(0));
  output->GetPointData()->SetTCoords(uv);
  vtkNew<vtkDoubleArray> angle;
  angle->SetName(vtkMesoArrayNames::AngleDistortion);
  vtkNew<vtkDoubleArray> area;
  area->SetName(vtkMesoArrayNames::AreaDistortion);
  angle->SetNumberOfValues(static_cast<vtkIdType>(map.angle_distortion.size()));
  area->SetNumberOfValues(static_cast<vtkIdType>(map.area_distortion.size()));
  for (std::size_t t = 0; t < map.angle_distortion.size(); ++t)
  {
    angle->SetValue(static_cast<vtkIdType>(t), map.angle_distortion[t]);
    area->SetValue(static_cast<vtkIdType>(t), map.area_distortion[t]);
  }
  output->GetCellData()->AddArray(angle);
  output->GetCellData()->AddArray(area);
  for (const auto& entry :
       { std::make_pair(vtkMesoArrayNames::ParameterizationRadius, radius),
         std::make_pair(vtkMesoArrayNames::FlippedTriangles, double(map.flipped_triangles)),
         std::make_pair(vtkMesoArrayNames::Bijective, map.bijective() ? 1.0 : 0.0) })
  {
    vtkNew<vtkDoubleArray> array;
    array->SetName(entry.first);
    array->InsertNextValue(entry.second);
    output->GetFieldData()->AddArray(array);
  }
}

mesolens::SurfacePoint SeedOf(vtkPolyData* disk)
{
  mesolens::SurfacePoint seed;
  vtkDataArray* triangle = disk->GetFieldData()->GetArray(vtkMesoArrayNames::SeedTriangle);
  vtkDataArray* barycentric = disk->GetFieldData()->GetArray(vtkMesoArrayNames::SeedBarycentric);
  vtkDataArray* position = disk->GetFieldData()->GetArray(vtkMesoArrayNames::SeedPosition);
  if (!triangle || !barycentric || !position || barycentric->GetNumberOfComponents() != 3 ||
      position->GetNumberOfComponents() != 3)
  {
    return seed;
  }
  seed.triangle = static_cast<std::int64_t>(triangle->GetComponent(0, 0));
  for (int k = 0; k < 3; ++k)
  {
    seed.barycentric[std::size_t(k)] = barycentric->GetComponent(0, k);
    seed.position[std::size_t(k)] = position->GetComponent(0, k);
  }
  return seed;
}

}
