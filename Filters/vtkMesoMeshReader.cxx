// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoMeshReader.h"

#include "vtkMesoXMLPolyDataReader.h"

#include "mesolens/common/errors.h"
#include "mesolens/io/file_names.h"
#include "mesolens/io/off_file.h"
#include "mesolens/io/obj_file.h"
#include "mesolens/io/ply_file.h"

#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkCellData.h>
#include <vtkExecutive.h>
#include <vtkFloatArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSTLReader.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <vector>
#include <fstream>
#include <sys/stat.h>

vtkStandardNewMacro(vtkMesoMeshReader);

vtkMesoMeshReader::vtkMesoMeshReader()
{
  this->SetNumberOfInputPorts(0);
}

namespace {

bool known_extension(const std::string& extension)
{
  return extension == "obj" || extension == "ply" || extension == "stl" || extension == "vtp" ||
    extension == "off";
}

/// Collects error events of an inner VTK reader so they can be reported as ours.
struct ErrorCollector
{
  std::string Message;
  static void Callback(vtkObject*, unsigned long, void* clientData, void* callData)
  {
    auto* self = static_cast<ErrorCollector*>(clientData);
    if (self->Message.empty() && callData)
    {
      self->Message = static_cast<const char*>(callData);
    }
  }
};

/// Many writers repeat a vertex for every face that uses it (STL always does; OBJ and PLY
/// exporters of per-corner normals or texture coordinates, and VTK's own OBJ reader, split
/// them so: the hiPSC membrane has 1216 vertices and 7284 corners). Points with identical
/// coordinates are merged back (the attributes of the first one are kept), so the mesh has its
/// surface's topology.
void weld_identical_points(vtkPolyData* mesh)
{
  const vtkIdType n = mesh->GetNumberOfPoints();
  std::map<std::array<double, 3>, vtkIdType> first_at;
  std::vector<vtkIdType> new_id(static_cast<std::size_t>(n));
  std::vector<vtkIdType> kept;
  for (vtkIdType i = 0; i < n; ++i)
  {
    std::array<double, 3> p{};
    mesh->GetPoint(i, p.data());
    const auto found = first_at.emplace(p, static_cast<vtkIdType>(kept.size()));
    if (found.second)
    {
      kept.push_back(i);
    }
    new_id[static_cast<std::size_t>(i)] = found.first->second;
  }
  if (static_cast<vtkIdType>(kept.size()) == n)
  {
    return;
  }
  vtkNew<vtkPoints> points;
  points->SetDataType(mesh->GetPoints()->GetDataType());
  points->SetNumberOfPoints(static_cast<vtkIdType>(kept.size()));
  vtkNew<vtkPointData> data;
  data->CopyAllocate(mesh->GetPointData(), static_cast<vtkIdType>(kept.size()));
  for (std::size_t k = 0; k < kept.size(); ++k)
  {
    points->SetPoint(static_cast<vtkIdType>(k), mesh->GetPoint(kept[k]));
    data->CopyData(mesh->GetPointData(), kept[k], static_cast<vtkIdType>(k));
  }
  vtkNew<vtkCellArray> polys;
  auto iterator = vtk::TakeSmartPointer(mesh->GetPolys()->NewIterator());
  std::vector<vtkIdType> ids;
  for (iterator->GoToFirstCell(); !iterator->IsDoneWithTraversal(); iterator->GoToNextCell())
  {
    vtkIdType size = 0;
    const vtkIdType* cell = nullptr;
    iterator->GetCurrentCell(size, cell);
    ids.assign(cell, cell + size);
    for (vtkIdType& id : ids)
    {
      id = new_id[static_cast<std::size_t>(id)];
    }
    polys->InsertNextCell(size, ids.data());
  }
  mesh->Initialize();
  mesh->SetPoints(points);
  mesh->GetPointData()->ShallowCopy(data);
  mesh->SetPolys(polys);
}

/// VTK's STL and XML readers pass on what the file says: faces that name vertices the file does
/// not have, and non-finite coordinates. Returns what is wrong with the
/// first such polygon or point, or an empty string when the mesh can be used.
std::string invalid_mesh_data(vtkPolyData* mesh)
{
  const vtkIdType point_count = mesh->GetNumberOfPoints();
  for (vtkIdType i = 0; i < point_count; ++i)
  {
    double p[3];
    mesh->GetPoint(i, p);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
    {
      return "vertex " + std::to_string(i + 1) + " has a non-finite coordinate";
    }
  }
  auto iterator = vtk::TakeSmartPointer(mesh->GetPolys()->NewIterator());
  vtkIdType polygon = 1;
  for (iterator->GoToFirstCell(); !iterator->IsDoneWithTraversal(); iterator->GoToNextCell())
  {
    vtkIdType size = 0;
    const vtkIdType* ids = nullptr;
    iterator->GetCurrentCell(size, ids);
    for (vtkIdType k = 0; k < size; ++k)
    {
      if (ids[k] < 0 || ids[k] >= point_count)
      {
        return "face " + std::to_string(polygon) + " refers to vertex " +
          std::to_string(ids[k] + 1) + ", but the file has " + std::to_string(point_count) +
          " vertices";
      }
    }
    ++polygon;
  }
  return {};
}

/// Keeps polygons only, fan-splitting those with more than three vertices.
void keep_triangles(vtkPolyData* mesh)
{
  vtkNew<vtkCellArray> triangles;
  vtkCellArray* polys = mesh->GetPolys();
  auto iterator = vtk::TakeSmartPointer(polys->NewIterator());
  for (iterator->GoToFirstCell(); !iterator->IsDoneWithTraversal(); iterator->GoToNextCell())
  {
    vtkIdType size = 0;
    const vtkIdType* ids = nullptr;
    iterator->GetCurrentCell(size, ids);
    for (vtkIdType k = 1; k + 1 < size; ++k)
    {
      const vtkIdType triangle[3] = { ids[0], ids[k], ids[k + 1] };
      triangles->InsertNextCell(3, triangle);
    }
  }
  mesh->SetVerts(nullptr);
  mesh->SetLines(nullptr);
  mesh->SetStrips(nullptr);
  mesh->SetPolys(triangles);
  mesh->GetCellData()->Initialize();
}
} // namespace

int vtkMesoMeshReader::CanReadFile(const char* fileName)
{
  if (!fileName || !known_extension(mesolens::file_extension(fileName)))
  {
    return 0;
  }
  std::ifstream probe(fileName);
  return probe ? 1 : 0;
}

std::string vtkMesoMeshReader::DeclaredCountProblem(const std::string& extension) const
{
  std::ifstream file(this->FileName, std::ios::binary);
  std::string head(65536, '\0');
  file.read(&head[0], static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(file.gcount()));
  file.clear();
  file.seekg(0, std::ios::end);
  const auto size = static_cast<unsigned long long>(file.tellg());
  if (extension == "stl")
  {
    // An ascii STL declares no counts; any byte outside text makes VTK read it as binary: an
    // 80-byte header, a triangle count, then 50 bytes per triangle.
    const bool text = std::all_of(head.begin(), head.end(), [](char c) {
      const auto byte = static_cast<unsigned char>(c);
      return byte == '\t' || byte == '\n' || byte == '\r' || (byte >= 0x20 && byte < 0x7f);
    });
    if (text || size < 84)
    {
      return {};
    }
    const auto* count_bytes = reinterpret_cast<const unsigned char*>(head.data() + 80);
    const unsigned long long triangles = count_bytes[0] | (count_bytes[1] << 8) |
      (count_bytes[2] << 16) | (static_cast<unsigned long long>(count_bytes[3]) << 24);
    if (84 + 50 * triangles > size)
    {
      return "the binary STL declares " + std::to_string(triangles) + " triangles (" +
        std::to_string(84 + 50 * triangles) + " bytes) but the file has " + std::to_string(size) +
        " bytes";
    }
    if (static_cast<long long>(triangles) > this->MaximumElements)
    {
      return "the STL declares " + std::to_string(triangles) + " triangles, more than " +
        std::to_string(this->MaximumElements) + " (vtkMesoMeshReader::MaximumElements)";
    }
    return {};
  }
  // VTK XML: every Number...="N" of the pieces.
  for (std::size_t at = head.find("Number"); at != std::string::npos;
       at = head.find("Number", at + 1))
  {
    const std::size_t quote = head.find('"', at);
    const std::size_t equals = head.find('=', at);
    if (quote == std::string::npos || equals == std::string::npos || equals > quote ||
        quote - at > 32)
    {
      continue;
    }
    const std::string name = head.substr(at, equals - at);
    const double count = std::strtod(head.c_str() + quote + 1, nullptr);
    if (name.find("Components") == std::string::npos && name.find("Tuples") == std::string::npos &&
        !(count <= double(this->MaximumElements)))
    {
      return "the VTP declares " + name + "=" + head.substr(quote + 1, 24) + ", more than " +
        std::to_string(this->MaximumElements) + " (vtkMesoMeshReader::MaximumElements)";
    }
  }
  return {};
}

bool vtkMesoMeshReader::ReadWithVTK(const std::string& extension, vtkPolyData* output)
{
  const std::string declared = this->DeclaredCountProblem(extension);
  if (!declared.empty())
  {
    vtkErrorMacro("Cannot read " << this->FileName << ": " << declared);
    return false;
  }
  vtkSmartPointer<vtkAlgorithm> reader;
  if (extension == "stl")
  {
    auto stl = vtkSmartPointer<vtkSTLReader>::New();
    stl->SetFileName(this->FileName.c_str());
    stl->MergingOn();
    reader = stl;
  }
  else
  {
    auto vtp = vtkSmartPointer<vtkMesoXMLPolyDataReader>::New();
    vtp->SetFileName(this->FileName.c_str());
    reader = vtp;
  }
  ErrorCollector errors;
  vtkNew<vtkCallbackCommand> callback;
  callback->SetCallback(&ErrorCollector::Callback);
  callback->SetClientData(&errors);
  reader->AddObserver(vtkCommand::ErrorEvent, callback);
  reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, callback);
  const bool updated = reader->GetExecutive()->Update() != 0;
  if (!updated || !errors.Message.empty())
  {
    vtkErrorMacro(
      "Cannot read " << this->FileName << ": "
                     << (errors.Message.empty() ? "the reader failed" : errors.Message));
    return false;
  }
  output->ShallowCopy(vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0)));
  const std::string invalid = invalid_mesh_data(output);
  if (!invalid.empty())
  {
    vtkErrorMacro("Cannot read " << this->FileName << ": " << invalid);
    output->Initialize();
    return false;
  }
  return true;
}

bool vtkMesoMeshReader::ReadSoup(const std::string& extension, vtkPolyData* output)
{
  mesolens::PolygonSoup soup;
  std::vector<double> normals;
  try
  {
    if (extension == "ply" || extension == "obj")
    {
      mesolens::MeshFileContents mesh = extension == "ply" ? mesolens::read_ply(this->FileName)
                                                           : mesolens::read_obj(this->FileName);
      soup = std::move(mesh.soup);
      normals = std::move(mesh.normals);
    }
    else
    {
      soup = mesolens::read_off(this->FileName);
    }
  }
  catch (const mesolens::Error& e)
  {
    vtkErrorMacro("Cannot read " << e.what()); // the message starts with the path
    return false;
  }
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(soup.points.size() / 3));
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    points->SetPoint(i, soup.points.data() + 3 * i);
  }
  vtkNew<vtkCellArray> polys;
  for (const auto& polygon : soup.polygons)
  {
    polys->InsertNextCell(static_cast<vtkIdType>(polygon.size()));
    for (const std::int64_t id : polygon)
    {
      polys->InsertCellPoint(static_cast<vtkIdType>(id));
    }
  }
  output->SetPoints(points);
  output->SetPolys(polys);
  if (!normals.empty())
  {
    vtkNew<vtkFloatArray> array;
    array->SetName("Normals");
    array->SetNumberOfComponents(3);
    array->SetNumberOfTuples(points->GetNumberOfPoints());
    for (std::size_t v = 0; v < normals.size(); ++v)
    {
      array->SetValue(static_cast<vtkIdType>(v), static_cast<float>(normals[v]));
    }
    output->GetPointData()->SetNormals(array);
  }
  return true;
}

int vtkMesoMeshReader::RequestData(vtkInformation*, vtkInformationVector**,
                                   vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  output->Initialize();
  if (this->FileName.empty())
  {
    vtkErrorMacro("No FileName was set.");
    return 0;
  }
  struct stat info
  {
  };
  if (::stat(this->FileName.c_str(), &info) != 0 || !S_ISREG(info.st_mode))
  {
    vtkErrorMacro("Cannot read " << this->FileName << ": no such file");
    return 0;
  }
  if (info.st_size == 0)
  {
    vtkErrorMacro("Cannot read " << this->FileName << ": the file is empty");
    return 0;
  }
  const std::string extension = mesolens::file_extension(this->FileName);
  if (!known_extension(extension))
  {
    vtkErrorMacro(
      "Cannot read " << this->FileName
                     << ": unknown mesh format (expected .obj, .ply, .stl, .vtp or .off)");
    return 0;
  }
  vtkNew<vtkPolyData> mesh;
  const bool read = extension == "stl" || extension == "vtp" ? this->ReadWithVTK(extension, mesh)
                                                             : this->ReadSoup(extension, mesh);
  if (!read)
  {
    return 0;
  }
  if (mesh->GetNumberOfPolys() == 0)
  {
    vtkErrorMacro("Cannot read " << this->FileName << ": the file holds no polygons");
    return 0;
  }
  keep_triangles(mesh);
  if (extension != "off")
  {
    weld_identical_points(mesh);
  }
  output->ShallowCopy(mesh);
  return 1;
}

void vtkMesoMeshReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName.empty() ? "(none)" : this->FileName) << "\n";
  os << indent << "MaximumElements: " << this->MaximumElements << "\n";
}
