// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: the mesh reader (vtkMesoMeshReader) on OBJ, PLY, STL, OFF and VTP files,
// followed by the mesh report (vtkMesoMeshReport), as a user's pipeline opens a mesh. The
// first byte chooses the extension (byte % 5: .obj, .ply, .stl, .off, .vtp); the rest is the
// file. Every input must give a mesh or an empty output with an error; the report must then
// agree with the mesh.
#include "fuzz_input.h"

#include "vtkMesoMeshReader.h"
#include "vtkMesoMeshReport.h"

#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkObject.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <cmath>
#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  using mesolens_fuzz::require;
  static const mesolens_fuzz::ScratchFile files[] = { mesolens_fuzz::ScratchFile(".obj"),
                                                      mesolens_fuzz::ScratchFile(".ply"),
                                                      mesolens_fuzz::ScratchFile(".stl"),
                                                      mesolens_fuzz::ScratchFile(".off"),
                                                      mesolens_fuzz::ScratchFile(".vtp") };
  vtkObject::GlobalWarningDisplayOff(); // every refused input would print its error
  mesolens_fuzz::FuzzInput input(data, size);
  const std::string& path = files[input.byte() % 5].write(input.rest());

  vtkNew<vtkMesoMeshReader> reader;
  reader->SetFileName(path.c_str());
  vtkNew<vtkMesoMeshReport> report;
  report->SetInputConnection(reader->GetOutputPort());
  report->Update();
  vtkPolyData* mesh = reader->GetOutput();
  const vtkIdType points = mesh->GetNumberOfPoints();
  // What the reader promises: finite points, triangles whose indices name them.
  for (vtkIdType point = 0; point < points; ++point)
  {
    double x[3];
    mesh->GetPoint(point, x);
    require(std::isfinite(x[0]) && std::isfinite(x[1]) && std::isfinite(x[2]));
  }
  vtkCellArray* polygons = mesh->GetPolys();
  const vtkIdType* cell = nullptr;
  vtkIdType cell_size = 0;
  for (polygons->InitTraversal(); polygons->GetNextCell(cell_size, cell);)
  {
    require(cell_size == 3);
    for (vtkIdType corner = 0; corner < cell_size; ++corner)
    {
      require(cell[corner] >= 0 && cell[corner] < points);
    }
  }
  require(report->GetNumberOfPoints() == points);
  require(report->GetNumberOfTriangles() == polygons->GetNumberOfCells());
  return 0;
}
