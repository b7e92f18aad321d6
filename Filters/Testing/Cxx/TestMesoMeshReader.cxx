// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoArrayNames.h"
#include "vtkMesoMeshReader.h"
#include "vtkMesoMeshReport.h"

#include "mesolens_test_data.h"
#include "mesolens_vtk_test_utilities.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSphereSource.h>
#include <vtkXMLPolyDataWriter.h>

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

using mesolens_test::data_file;

namespace {
struct MeshCase
{
  const char* file;
  vtkIdType points;
  vtkIdType triangles;
  vtkIdType euler; // 2 - 2 genus for closed surfaces
};

// Vertex and face counts and genus from ../shared/data/README.md (checked there independently).
const MeshCase real_meshes[] = {
  { "meshes/mito5_outer_membrane.obj", 4172, 8340, 2 },
  { "meshes/hipsc_cell_membrane_1.obj", 1216, 2428, 2 },
  { "meshes/celegans_embryo_cell10_T10.ply", 727, 1450, 2 },
  { "meshes/celegans_embryo_cell10_T11.ply", 665, 1326, 2 },
};
} // namespace

TEST(vtkMesoMeshReader, RealCellMeshesAreClosedManifolds)
{
  for (const MeshCase& c : real_meshes)
  {
    SCOPED_TRACE(c.file);
    vtkNew<vtkMesoMeshReader> reader;
    reader->SetFileName(data_file(c.file).c_str());
    vtkNew<vtkMesoMeshReport> report;
    report->SetInputConnection(reader->GetOutputPort());
    ASSERT_EQ(report->GetExecutive()->Update(), 1);
    EXPECT_EQ(report->GetNumberOfPoints(), c.points);
    EXPECT_EQ(report->GetNumberOfTriangles(), c.triangles);
    EXPECT_EQ(report->GetEulerCharacteristic(), c.euler);
    EXPECT_TRUE(report->GetIsClosedManifold()) << report->GetDefectsDescription();
    EXPECT_EQ(report->GetNumberOfComponents(), 1);
    vtkPolyData* out = report->GetOutput();
    EXPECT_EQ(out->GetFieldData()->GetArray(vtkMesoArrayNames::NumberOfBoundaryLoops)->GetTuple1(0),
              0.0);
    EXPECT_EQ(out->GetCellData()->GetArray(vtkMesoArrayNames::DegenerateTriangle)->GetRange()[1],
              0.0);
  }
}

TEST(vtkMesoMeshReader, InnerMembraneHasGenusFour)
{
  const std::string path = mesolens_test::shared_file("meshes/mito5_inner_membrane.obj");
  if (!mesolens_test::exists(path))
  {
    GTEST_SKIP() << "shared data not found: " << path;
  }
  vtkNew<vtkMesoMeshReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkNew<vtkMesoMeshReport> report;
  EXPECT_TRUE(report->Analyze(reader->GetOutput()));
  EXPECT_EQ(report->GetNumberOfTriangles(), 20660);
  EXPECT_EQ(report->GetEulerCharacteristic(), 2 - 2 * 4);
}

TEST(vtkMesoMeshReader, DefectiveMeshesAreReadAndDescribed)
{
  vtkNew<vtkMesoMeshReader> reader;
  vtkNew<vtkMesoMeshReport> report;
  reader->SetFileName(data_file("meshes/bad/cgal_cube-ouvert.off").c_str());
  reader->Update();
  EXPECT_FALSE(report->Analyze(reader->GetOutput()) && report->GetIsClosedManifold());
  EXPECT_EQ(report->GetNumberOfBoundaryEdges(), 4);
  EXPECT_EQ(report->GetNumberOfBoundaryLoops(), 1);
  EXPECT_EQ(report->GetNumberOfUnreferencedVertices(), 1);
  EXPECT_NE(std::string(report->GetDefectsDescription()).find("boundary edges"), std::string::npos);

  reader->SetFileName(data_file("meshes/bad/cgal_degtri_sliding.off").c_str());
  reader->Update();
  EXPECT_FALSE(report->Analyze(reader->GetOutput()));
  EXPECT_GT(report->GetNumberOfDegenerateTriangles(), 0);

  reader->SetFileName(data_file("meshes/bad/cgal_tet-shuffled.off").c_str());
  reader->Update();
  report->Analyze(reader->GetOutput());
  EXPECT_GT(report->GetNumberOfInconsistentlyOrientedEdges(), 0);
  EXPECT_FALSE(report->GetIsClosedManifold());
}

TEST(vtkMesoMeshReader, VtpRoundTrip)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(16);
  sphere->SetPhiResolution(16);
  vtkNew<vtkXMLPolyDataWriter> writer;
  const std::string path = mesolens_test::output_file("sphere.vtp");
  writer->SetFileName(path.c_str());
  writer->SetInputConnection(sphere->GetOutputPort());
  writer->Write();
  vtkNew<vtkMesoMeshReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkNew<vtkMesoMeshReport> report;
  EXPECT_TRUE(report->Analyze(reader->GetOutput()));
  EXPECT_TRUE(report->GetIsClosedManifold());
  EXPECT_EQ(report->GetEulerCharacteristic(), 2);
}

namespace {
/// The reader fails on `path` with an error saying `problem`, and leaves its output empty.
void expect_refused(const std::string& path, const char* problem)
{
  SCOPED_TRACE(path);
  vtkNew<vtkMesoMeshReader> reader;
  mesolens_test::EventRecorder events(reader);
  reader->SetFileName(path.c_str());
  EXPECT_EQ(reader->GetExecutive()->Update(), 0);
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_NE(events.AllErrors().find(problem), std::string::npos) << events.AllErrors();
}
} // namespace

TEST(vtkMesoMeshReader, BadFilesFailCleanly)
{
  const struct
  {
    std::string path;
    const char* problem;
  } cases[] = {
    { mesolens_test::output_file("missing.obj"), "no such file" },
    { mesolens_test::write_bytes("empty_mesh.ply", ""), "empty" },
    { mesolens_test::garbage_file("garbage_mesh.ply"), "Cannot read" },
    { mesolens_test::garbage_file("garbage_mesh.off"), "is not an OFF header" },
    { mesolens_test::write_bytes("points_only.obj", "v 0 0 0\nv 1 0 0\n"), "no faces" },
    { data_file("proteins/1crn.pdb"), "unknown mesh format" },
  };
  for (const auto& c : cases)
  {
    expect_refused(c.path, c.problem);
  }
}

TEST(vtkMesoMeshReader, PlyFilesThatCrashedVTKsReaderAreRefused)
{
  // Mutations of PLY files (a byte changed in the format line and a cut header; a cut header
  // claiming 10^11 vertices; a byte changed in the embryo's faces) on which vtkPLYReader
  // crashes or aborts the process; and a lying face count and a cut body made here.
  const std::string hostile = std::string(MESOLENS_SOURCE_DIR) + "/Testing/Data/meshes/";
  std::string lying = mesolens_test::read_bytes(data_file("meshes/celegans_embryo_cell10_T10.ply"));
  lying.replace(lying.find("element face 1450"), 17, "element face 4000000000");
  const struct
  {
    std::string path;
    const char* problem;
  } cases[] = {
    { hostile + "vtk_crash_cut_header.ply", "unknown keyword 'format?binary_little_endian'" },
    { hostile + "vtk_crash_huge_vertex_count.ply", "header line 8: unknown keyword 'prope'" },
    { hostile + "vtk_crash_mutated_embryo.ply", "refers to vertex" },
    { mesolens_test::write_bytes("lying_faces.ply", lying), "claims 4000000000 face items" },
    { mesolens_test::truncated_copy(data_file("meshes/celegans_embryo_cell10_T10.ply"), 20000,
                                    "truncated_embryo.ply"),
      "more than the" },
  };
  for (const auto& c : cases)
  {
    expect_refused(c.path, c.problem);
  }
}

TEST(vtkMesoMeshReader, WhatVTKsReadersPassOnIsChecked)
{
  // vtkOBJReader, vtkSTLReader and vtkXMLPolyDataReader pass on faces naming vertices that the
  // file does not have (found by fuzz_mesh: an OBJ cut short, read as triangles whose indices
  // run past the points) and non-finite coordinates; vtkOBJReader reads "nan" and "x" as 0.
  const std::string hostile = std::string(MESOLENS_SOURCE_DIR) + "/Testing/Data/meshes/";
  std::string stl_with_nan(80, ' ');
  const std::uint32_t one = 1;
  stl_with_nan.append(reinterpret_cast<const char*>(&one), 4);
  const float facet[12] = {
    0, 0, 1, 0, 0, 0, 1, 0, 0, std::numeric_limits<float>::quiet_NaN(), 1, 0
  };
  stl_with_nan.append(reinterpret_cast<const char*>(facet), sizeof facet);
  stl_with_nan.append(2, '\0');
  const std::string vtp_past_the_points =
    "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\">\n<PolyData>\n"
    "<Piece NumberOfPoints=\"3\" NumberOfPolys=\"1\">\n<Points><DataArray type=\"Float32\" "
    "NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 0 0 0 1 0</DataArray></Points>\n"
    "<Polys><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">0 1 7"
    "</DataArray><DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">3</DataArray>"
    "</Polys>\n</Piece>\n</PolyData>\n</VTKFile>\n";
  const struct
  {
    std::string path;
    const char* problem;
  } cases[] = {
    { hostile + "fuzz_obj_faces_past_the_vertices.obj",
      "line 7: the face refers to vertex 5, but the file has 4 vertices" },
    { mesolens_test::write_bytes("nan_vertex.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n"),
      "line 2: non-finite coordinate 'nan'" },
    { mesolens_test::write_bytes("garbage_vertex.obj", "v 0 0 0\nv 1 x 0\nv 0 1 0\nf 1 2 3\n"),
      "line 2: 'x' is not a number" },
    { mesolens_test::write_bytes("nan_vertex.stl", stl_with_nan), "non-finite coordinate" },
    { mesolens_test::write_bytes("past_the_points.vtp", vtp_past_the_points),
      "face 1 refers to vertex 8, but the file has 3 vertices" },
  };
  for (const auto& c : cases)
  {
    expect_refused(c.path, c.problem);
  }
}

TEST(vtkMesoMeshReader, CountsVTKsReadersWouldAllocateAreCheckedFirst)
{
  // Found by fuzz_mesh (out of memory): vtkSTLReader and vtkXMLPolyDataReader allocate what a
  // header declares. A binary STL must hold its triangles; a VTP may declare at most
  // MaximumElements points and cells (compressed zeros would justify any count).
  std::string stl(80, '\x01');
  const std::uint32_t claimed = 1000000000;
  stl.append(reinterpret_cast<const char*>(&claimed), 4);
  stl.append(50, '\0');
  const std::string vtp =
    "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\">\n<PolyData>\n"
    "<Piece NumberOfPoints=\"2000000000\" NumberOfPolys=\"1\">\n</Piece>\n</PolyData>\n"
    "</VTKFile>\n";
  const struct
  {
    std::string path;
    const char* problem;
  } cases[] = {
    { mesolens_test::write_bytes("lying.stl", stl),
      "the binary STL declares 1000000000 triangles (50000000084 bytes) but the file has 134 "
      "bytes" },
    { mesolens_test::write_bytes("huge.vtp", vtp), "the VTP declares NumberOfPoints=2000000000" },
  };
  for (const auto& c : cases)
  {
    expect_refused(c.path, c.problem);
  }
  vtkNew<vtkMesoMeshReader> reader;
  reader->SetMaximumElements(3);
  reader->SetFileName(data_file("meshes/mito5_outer_membrane.obj").c_str()); // OBJ: no limit
  reader->Update();
  EXPECT_GT(reader->GetOutput()->GetNumberOfPolys(), 3);
}

TEST(vtkMesoMeshReader, PlyNormalsAreKept)
{
  vtkNew<vtkMesoMeshReader> reader;
  reader->SetFileName(data_file("meshes/celegans_embryo_cell10_T10.ply").c_str());
  reader->Update();
  vtkDataArray* normals = reader->GetOutput()->GetPointData()->GetNormals();
  ASSERT_NE(normals, nullptr);
  EXPECT_EQ(normals->GetNumberOfTuples(), reader->GetOutput()->GetNumberOfPoints());
  EXPECT_NEAR(vtkMath::Norm(normals->GetTuple3(0)), 1.0, 1e-3);
}

TEST(vtkMesoMeshReport, EmptyInput)
{
  vtkNew<vtkPolyData> empty;
  vtkNew<vtkMesoMeshReport> report;
  EXPECT_FALSE(report->Analyze(empty));
  EXPECT_NE(std::string(report->GetDefectsDescription()).find("no triangles"), std::string::npos);
  report->SetInputData(empty);
  EXPECT_EQ(report->GetExecutive()->Update(), 1);
}
