// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoMeshReport.h"

#include "vtkMesoArrayNames.h"

#include "mesolens/mesh/mesh_report.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>

#include <vector>

vtkStandardNewMacro(vtkMesoMeshReport);

bool vtkMesoMeshReport::Analyze(vtkPolyData* mesh)
{
  const vtkIdType point_count = mesh && mesh->GetPoints() ? mesh->GetNumberOfPoints() : 0;
  std::vector<double> points(3 * static_cast<std::size_t>(point_count));
  for (vtkIdType i = 0; i < point_count; ++i)
  {
    mesh->GetPoint(i, points.data() + 3 * i);
  }
  // Triangles of the mesh, and for each cell (verts, lines, polys, strips in VTK's cell order)
  // the triangle it is, if any.
  std::vector<std::int64_t> triangles;
  std::vector<std::int64_t> triangle_of_cell;
  this->NumberOfNonTriangleCells = 0;
  if (mesh)
  {
    const vtkIdType leading_cells = mesh->GetNumberOfVerts() + mesh->GetNumberOfLines();
    triangle_of_cell.assign(static_cast<std::size_t>(mesh->GetNumberOfCells()), -1);
    this->NumberOfNonTriangleCells = leading_cells + mesh->GetNumberOfStrips();
    auto iterator = vtk::TakeSmartPointer(mesh->GetPolys()->NewIterator());
    vtkIdType cell = leading_cells;
    for (iterator->GoToFirstCell(); !iterator->IsDoneWithTraversal();
         iterator->GoToNextCell(), ++cell)
    {
      vtkIdType size = 0;
      const vtkIdType* ids = nullptr;
      iterator->GetCurrentCell(size, ids);
      if (size != 3)
      {
        ++this->NumberOfNonTriangleCells;
        continue;
      }
      triangle_of_cell[static_cast<std::size_t>(cell)] =
        static_cast<std::int64_t>(triangles.size() / 3);
      triangles.insert(triangles.end(), { ids[0], ids[1], ids[2] });
    }
  }
  mesolens::TriangleMeshView view;
  view.points = points;
  view.triangles = triangles.data();
  view.triangle_count = triangles.size() / 3;
  const mesolens::MeshReport report = mesolens::mesh_report(view);

  this->NumberOfPoints = point_count;
  this->NumberOfTriangles = static_cast<vtkIdType>(report.triangles);
  this->NumberOfEdges = static_cast<vtkIdType>(report.edges);
  this->NumberOfBoundaryEdges = static_cast<vtkIdType>(report.boundary_edges);
  this->NumberOfBoundaryLoops = static_cast<vtkIdType>(report.boundary_loops);
  this->NumberOfNonManifoldEdges = static_cast<vtkIdType>(report.non_manifold_edges);
  this->NumberOfNonManifoldVertices = static_cast<vtkIdType>(report.non_manifold_vertices);
  this->NumberOfInconsistentlyOrientedEdges =
    static_cast<vtkIdType>(report.inconsistently_oriented_edges);
  this->NumberOfDegenerateTriangles =
    static_cast<vtkIdType>(report.degenerate_triangles + report.invalid_triangles);
  this->NumberOfUnreferencedVertices = static_cast<vtkIdType>(report.unreferenced_vertices);
  this->NumberOfComponents = static_cast<vtkIdType>(report.components);
  this->EulerCharacteristic = static_cast<vtkIdType>(report.euler_characteristic);
  this->IsManifold = report.is_manifold();
  this->IsClosedManifold = report.is_closed_manifold();
  this->DefectsDescription = report.describe_defects();
  if (this->NumberOfNonTriangleCells > 0)
  {
    this->DefectsDescription +=
      std::to_string(this->NumberOfNonTriangleCells) + " cells that are not triangles\n";
  }
  this->DegenerateFlags.assign(triangle_of_cell.size(), 0);
  for (std::size_t c = 0; c < triangle_of_cell.size(); ++c)
  {
    if (triangle_of_cell[c] >= 0)
    {
      this->DegenerateFlags[c] =
        report.triangle_is_degenerate[static_cast<std::size_t>(triangle_of_cell[c])];
    }
  }
  this->NonManifoldFlags = report.vertex_is_non_manifold;
  return this->IsManifold;
}

void vtkMesoMeshReport::AddResultsTo(vtkPolyData* output) const
{
  vtkNew<vtkUnsignedCharArray> degenerate;
  degenerate->SetName(vtkMesoArrayNames::DegenerateTriangle);
  degenerate->SetNumberOfValues(static_cast<vtkIdType>(this->DegenerateFlags.size()));
  for (std::size_t c = 0; c < this->DegenerateFlags.size(); ++c)
  {
    degenerate->SetValue(static_cast<vtkIdType>(c), this->DegenerateFlags[c]);
  }
  output->GetCellData()->AddArray(degenerate);
  vtkNew<vtkUnsignedCharArray> non_manifold;
  non_manifold->SetName(vtkMesoArrayNames::NonManifoldVertex);
  non_manifold->SetNumberOfValues(static_cast<vtkIdType>(this->NonManifoldFlags.size()));
  for (std::size_t p = 0; p < this->NonManifoldFlags.size(); ++p)
  {
    non_manifold->SetValue(static_cast<vtkIdType>(p), this->NonManifoldFlags[p]);
  }
  output->GetPointData()->AddArray(non_manifold);
  const std::pair<const char*, vtkIdType> counts[] = {
    { vtkMesoArrayNames::NumberOfBoundaryEdges, this->NumberOfBoundaryEdges },
    { vtkMesoArrayNames::NumberOfBoundaryLoops, this->NumberOfBoundaryLoops },
    { vtkMesoArrayNames::NumberOfNonManifoldEdges, this->NumberOfNonManifoldEdges },
    { vtkMesoArrayNames::NumberOfNonManifoldVertices, this->NumberOfNonManifoldVertices },
    { vtkMesoArrayNames::NumberOfInconsistentlyOrientedEdges,
      this->NumberOfInconsistentlyOrientedEdges },
    { vtkMesoArrayNames::NumberOfDegenerateTriangles, this->NumberOfDegenerateTriangles },
    { vtkMesoArrayNames::NumberOfUnreferencedVertices, this->NumberOfUnreferencedVertices },
    { vtkMesoArrayNames::NumberOfComponents, this->NumberOfComponents },
    { vtkMesoArrayNames::EulerCharacteristic, this->EulerCharacteristic },
  };
  for (const auto& count : counts)
  {
    vtkNew<vtkDoubleArray> value;
    value->SetName(count.first);
    value->InsertNextValue(static_cast<double>(count.second));
    output->GetFieldData()->RemoveArray(count.first);
    output->GetFieldData()->AddArray(value);
  }
}

int vtkMesoMeshReport::RequestData(vtkInformation*, vtkInformationVector** inputVector,
                                   vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  output->ShallowCopy(input);
  this->Analyze(input);
  this->AddResultsTo(output);
  return 1;
}

void vtkMesoMeshReport::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfPoints: " << this->NumberOfPoints << "\n";
  os << indent << "NumberOfTriangles: " << this->NumberOfTriangles << "\n";
  os << indent << "NumberOfNonTriangleCells: " << this->NumberOfNonTriangleCells << "\n";
  os << indent << "NumberOfEdges: " << this->NumberOfEdges << "\n";
  os << indent << "NumberOfBoundaryEdges: " << this->NumberOfBoundaryEdges << "\n";
  os << indent << "NumberOfBoundaryLoops: " << this->NumberOfBoundaryLoops << "\n";
  os << indent << "NumberOfNonManifoldEdges: " << this->NumberOfNonManifoldEdges << "\n";
  os << indent << "NumberOfNonManifoldVertices: " << this->NumberOfNonManifoldVertices << "\n";
  os << indent
     << "NumberOfInconsistentlyOrientedEdges: " << this->NumberOfInconsistentlyOrientedEdges
     << "\n";
  os << indent << "NumberOfDegenerateTriangles: " << this->NumberOfDegenerateTriangles << "\n";
  os << indent << "NumberOfUnreferencedVertices: " << this->NumberOfUnreferencedVertices << "\n";
  os << indent << "NumberOfComponents: " << this->NumberOfComponents << "\n";
  os << indent << "EulerCharacteristic: " << this->EulerCharacteristic << "\n";
  os << indent << "IsManifold: " << this->IsManifold << "\n";
  os << indent << "IsClosedManifold: " << this->IsClosedManifold << "\n";
}
