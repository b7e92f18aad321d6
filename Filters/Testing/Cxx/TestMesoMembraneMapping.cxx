// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoArrayNames.h"
#include "vtkMesoDiskParameterization.h"
#include "vtkMesoGeodesicDisk.h"
#include "vtkMesoMembraneMapping.h"
#include "vtkMesoMeshReader.h"
#include "vtkMesoMeshReport.h"
#include "vtkMesoTrajectoryReader.h"

#include "mesolens_test_data.h"
#include "mesolens_vtk_test_utilities.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSphereSource.h>
#include <vtkStaticCellLocator.h>
#include <vtkStringArray.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <vector>

using mesolens_test::data_file;

namespace {
double field(vtkPolyData* data, const char* name, int component = 0)
{
  vtkDataArray* array = data->GetFieldData()->GetArray(name);
  return array ? array->GetComponent(0, component) : std::nan("");
}

/// A point of the mitochondrion's outer membrane (µm).
void outer_membrane_point(vtkMesoMeshReader* mesh, double point[3])
{
  mesh->Update();
  mesh->GetOutput()->GetPoint(1000, point);
}

/// The DPPC patch (waters removed) mapped onto the mitochondrion's outer membrane at its vertex
/// 1000, in µm.
struct MitochondrionMapping
{
  vtkNew<vtkMesoMeshReader> Mesh;
  vtkNew<vtkMesoTrajectoryReader> Membrane;
  vtkNew<vtkMesoMembraneMapping> Mapping;

  MitochondrionMapping()
  {
    this->Mesh->SetFileName(data_file("meshes/mito5_outer_membrane.obj").c_str());
    double seed[3];
    outer_membrane_point(this->Mesh, seed);
    this->Membrane->SetTopologyFileName(data_file("membranes/dppc128_slipids_323K.gro").c_str());
    this->Membrane->RemoveWatersOn();
    this->Mapping->SetSurfaceConnection(this->Mesh->GetOutputPort());
    this->Mapping->SetMembraneConnection(this->Membrane->GetOutputPort());
    this->Mapping->SetSeedPoint(seed);
  }
};

double largest_abs(vtkDataArray* values, vtkIdType first)
{
  double largest = 0;
  for (vtkIdType i = first; i < values->GetNumberOfTuples(); ++i)
  {
    largest = std::max(largest, std::abs(values->GetComponent(i, 0)));
  }
  return largest;
}
} // namespace

TEST(vtkMesoGeodesicDisk, DiskAndParameterizationOnTheMitochondrion)
{
  vtkNew<vtkMesoMeshReader> mesh;
  mesh->SetFileName(data_file("meshes/mito5_outer_membrane.obj").c_str());
  double seed[3];
  outer_membrane_point(mesh, seed);
  vtkNew<vtkMesoGeodesicDisk> disk;
  disk->SetInputConnection(mesh->GetOutputPort());
  disk->SetSeedPoint(seed);
  disk->SetRadius(0.05); // µm
  disk->SetMinimumTriangles(1000);
  vtkNew<vtkMesoDiskParameterization> map;
  map->SetInputConnection(disk->GetOutputPort());
  ASSERT_EQ(map->GetExecutive()->Update(), 1);
  vtkPolyData* out = map->GetOutput();
  EXPECT_GE(out->GetNumberOfPolys(), 1000);
  EXPECT_GE(field(out, vtkMesoArrayNames::RefinementLevels), 1.0); // edges of tens of nm: refined
  EXPECT_EQ(field(out, vtkMesoArrayNames::Bijective), 1.0);
  ASSERT_NE(out->GetPointData()->GetTCoords(), nullptr);
  ASSERT_NE(out->GetPointData()->GetArray(vtkMesoArrayNames::GeodesicDistance), nullptr);
  EXPECT_LE(out->GetPointData()->GetArray(vtkMesoArrayNames::GeodesicDistance)->GetRange()[1],
            0.05 + 1e-12);
  vtkNew<vtkMesoMeshReport> report;
  report->Analyze(out);
  EXPECT_EQ(report->GetEulerCharacteristic(), 1);
  EXPECT_EQ(report->GetNumberOfBoundaryLoops(), 1);
  // The texture coordinates fill the disk of radius 0.05.
  double uv_range[2];
  out->GetPointData()->GetTCoords()->GetRange(uv_range, 0);
  EXPECT_NEAR(uv_range[1], 0.05, 1e-3);
}

TEST(vtkMesoMembraneMapping, ThreeMethodsOnTheMitochondrion)
{
  MitochondrionMapping pipeline;
  vtkMesoMembraneMapping* mapping = pipeline.Mapping;
  mapping->SetTiles(2);
  mapping->SetMembraneToMeshScale(1e-4); // Å onto µm
  std::vector<double> largest_change;
  for (int method :
       { vtkMesoMembraneMapping::DISPLACEMENT, vtkMesoMembraneMapping::MOLECULE_INSTANCING,
         vtkMesoMembraneMapping::POLYNOMIAL })
  {
    SCOPED_TRACE(method);
    mapping->SetMappingMethod(method);
    ASSERT_EQ(mapping->GetExecutive()->Update(), 1);
    vtkPolyData* atoms = mapping->GetOutput();
    EXPECT_EQ(atoms->GetNumberOfPoints(), 4 * 16640);
    EXPECT_EQ(atoms->GetNumberOfVerts(), 4 * 16640);
    EXPECT_EQ(atoms->GetNumberOfLines(), 4 * 16512);
    ASSERT_NE(atoms->GetPointData()->GetArray(vtkMesoArrayNames::TileId), nullptr);
    EXPECT_EQ(atoms->GetPointData()->GetArray(vtkMesoArrayNames::TileId)->GetRange()[1], 3.0);
    ASSERT_NE(atoms->GetPointData()->GetArray(vtkMesoArrayNames::MoleculeId), nullptr);
    ASSERT_NE(atoms->GetPointData()->GetAbstractArray(vtkMesoArrayNames::AtomName), nullptr);
    vtkDataArray* change = atoms->GetCellData()->GetArray(vtkMesoArrayNames::BondLengthChange);
    ASSERT_NE(change, nullptr);
    largest_change.push_back(largest_abs(change, atoms->GetNumberOfVerts()));
    // d = 2 x 64.2 Å = 0.01284 µm, r = 2 d.
    EXPECT_NEAR(field(atoms, vtkMesoArrayNames::GeodesicRadius), 2 * 2 * 64.2 * 1e-4, 2e-5);
    vtkPolyData* disk = vtkPolyData::SafeDownCast(mapping->GetOutputDataObject(1));
    EXPECT_GT(disk->GetNumberOfPolys(), 0);
    // Atoms stay within a bilayer's reach of the surface.
    double bounds[6];
    atoms->GetBounds(bounds);
    EXPECT_LT(bounds[1] - bounds[0], 0.05);
  }
  // Instancing keeps molecules rigid; the other two bend them a little.
  EXPECT_LT(largest_change[1], 1e-6);
  EXPECT_GT(largest_change[0], 1e-3);
  EXPECT_GT(largest_change[2], 1e-3);
  mapping->SetMappingMethodToPolynomial();
  mapping->Update();
  vtkDataArray* coefficients =
    mapping->GetOutput()->GetFieldData()->GetArray(vtkMesoArrayNames::PolynomialCoefficients);
  ASSERT_NE(coefficients, nullptr);
  EXPECT_EQ(coefficients->GetNumberOfComponents(), 30);
  EXPECT_EQ(coefficients->GetNumberOfTuples(), 4);
  mapping->SetMappingMethodToMoleculeInstancing();
  mapping->Update();
  vtkDataArray* matrices =
    mapping->GetOutput()->GetFieldData()->GetArray(vtkMesoArrayNames::InstanceMatrices);
  ASSERT_NE(matrices, nullptr);
  EXPECT_EQ(matrices->GetNumberOfTuples(), 4 * 128);

  // Without atoms: the same warp (for the GPU) and a vertex per molecule and tile at the centre
  // the mapped atoms have, to the bit (a cutaway of either decides the same); displacement
  // still maps.
  for (const bool polynomial : { true, false })
  {
    if (polynomial)
    {
      mapping->SetMappingMethodToPolynomial();
    }
    else
    {
      mapping->SetMappingMethodToMoleculeInstancing();
    }
    mapping->OutputAtomsOn();
    mapping->Update();
    vtkNew<vtkPolyData> atoms;
    atoms->ShallowCopy(mapping->GetOutput());
    std::vector<double> with_atoms(30);
    if (polynomial)
    {
      atoms->GetFieldData()
        ->GetArray(vtkMesoArrayNames::PolynomialCoefficients)
        ->GetTuple(3, with_atoms.data());
    }
    // The mapped atoms' molecule centres, in order of first appearance.
    vtkDataArray* atom_ids = atoms->GetPointData()->GetArray(vtkMesoArrayNames::MoleculeId);
    std::vector<int> order;
    std::map<int, std::array<double, 4>> sums;
    for (vtkIdType a = 0; a < atoms->GetNumberOfPoints(); ++a)
    {
      const int id = static_cast<int>(atom_ids->GetComponent(a, 0));
      if (!sums.count(id))
      {
        order.push_back(id);
        sums[id] = { 0, 0, 0, 0 };
      }
      double p[3];
      atoms->GetPoint(a, p);
      for (int d = 0; d < 3; ++d)
      {
        sums[id][std::size_t(d)] += p[d];
      }
      sums[id][3] += 1;
    }
    mapping->OutputAtomsOff();
    mapping->Update();
    vtkPolyData* centres = mapping->GetOutput();
    EXPECT_EQ(centres->GetNumberOfLines(), 0);
    ASSERT_EQ(centres->GetNumberOfPoints(), 4 * 128);
    EXPECT_EQ(centres->GetNumberOfVerts(), 4 * 128);
    vtkDataArray* ids = centres->GetPointData()->GetArray(vtkMesoArrayNames::MoleculeId);
    vtkDataArray* tiles = centres->GetPointData()->GetArray(vtkMesoArrayNames::TileId);
    vtkAbstractArray* names =
      centres->GetPointData()->GetAbstractArray(vtkMesoArrayNames::ResidueName);
    ASSERT_NE(ids, nullptr);
    ASSERT_NE(tiles, nullptr);
    ASSERT_NE(names, nullptr);
    for (vtkIdType m = 0; m < centres->GetNumberOfPoints(); ++m)
    {
      const int id = order[std::size_t(m)];
      EXPECT_EQ(ids->GetComponent(m, 0), id);
      EXPECT_EQ(tiles->GetComponent(m, 0), double(m / 128));
      double p[3];
      centres->GetPoint(m, p);
      for (int d = 0; d < 3; ++d)
      {
        EXPECT_EQ(p[d], sums[id][std::size_t(d)] / sums[id][3]) << "molecule " << m;
      }
    }
    EXPECT_EQ(names->GetVariantValue(0).ToString(), "DPPC");
    if (polynomial)
    {
      vtkDataArray* coefficients =
        centres->GetFieldData()->GetArray(vtkMesoArrayNames::PolynomialCoefficients);
      ASSERT_NE(coefficients, nullptr);
      for (int c = 0; c < 30; ++c)
      {
        EXPECT_EQ(coefficients->GetComponent(3, c), with_atoms[std::size_t(c)]);
      }
    }
    else
    {
      EXPECT_EQ(
        centres->GetFieldData()->GetArray(vtkMesoArrayNames::InstanceMatrices)->GetNumberOfTuples(),
        4 * 128);
    }
  }
  mapping->SetMappingMethodToDisplacement();
  mapping->Update();
  EXPECT_EQ(mapping->GetOutput()->GetNumberOfPoints(), 4 * 16640);
}

TEST(vtkMesoMembraneMapping, TrajectoryTimeStepsPassThrough)
{
  vtkNew<vtkSphereSource> sphere; // radius 500 Å: a vesicle-sized surface in the membrane's units
  sphere->SetRadius(500);
  sphere->SetThetaResolution(120);
  sphere->SetPhiResolution(120);
  vtkNew<vtkMesoTrajectoryReader> membrane;
  membrane->SetTopologyFileName(data_file("membranes/yiip_popepopg.gro").c_str());
  membrane->SetTrajectoryFileName(data_file("membranes/yiip_popepopg.xtc").c_str());
  vtkNew<vtkMesoMembraneMapping> mapping;
  mapping->SetSurfaceConnection(sphere->GetOutputPort());
  mapping->SetMembraneConnection(membrane->GetOutputPort());
  mapping->SetSeedPoint(0, 0, 500);
  mapping->SetMappingMethodToPolynomial();
  mapping->UpdateInformation();
  vtkInformation* info = mapping->GetOutputInformation(0);
  ASSERT_TRUE(info->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()));
  EXPECT_EQ(info->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS()), 5);
  mapping->UpdateTimeStep(40000);
  double first[3];
  mapping->GetOutput()->GetPoint(0, first);
  mapping->UpdateTimeStep(80000);
  double last[3];
  mapping->GetOutput()->GetPoint(0, last);
  EXPECT_NE(first[0], last[0]);
  EXPECT_EQ(mapping->GetOutput()->GetNumberOfPoints(), 43480);
}

TEST(vtkMesoMembraneMapping, PiecesShareTheTilesAndTogetherGiveTheWhole)
{
  // As a streaming VTK pipeline asks: each piece maps its share of the tiles.
  MitochondrionMapping pipeline;
  vtkMesoMembraneMapping* mapping = pipeline.Mapping;
  mapping->SetTiles(3);
  mapping->SetMembraneToMeshScale(1e-4);
  mapping->SetMappingMethodToPolynomial();
  ASSERT_EQ(mapping->UpdatePiece(0, 1, 0), 1);
  vtkNew<vtkPolyData> whole;
  whole->DeepCopy(mapping->GetOutput());
  ASSERT_EQ(whole->GetNumberOfPoints(), 9 * 16640);
  const char* arrays[] = { vtkMesoArrayNames::TileId, vtkMesoArrayNames::MoleculeId };
  vtkIdType offset = 0;
  for (int piece = 0; piece < 2; ++piece)
  {
    SCOPED_TRACE(piece);
    ASSERT_EQ(mapping->UpdatePiece(piece, 2, 0), 1);
    vtkPolyData* share = mapping->GetOutput();
    // Piece 0 maps tiles 0-3, piece 1 tiles 4-8, with their bonds; the disk is piece 0's.
    EXPECT_EQ(share->GetNumberOfPoints(), (piece == 0 ? 4 : 5) * 16640);
    EXPECT_EQ(share->GetNumberOfLines(), (piece == 0 ? 4 : 5) * 16512);
    EXPECT_EQ(vtkPolyData::SafeDownCast(mapping->GetOutputDataObject(1))->GetNumberOfPolys() > 0,
              piece == 0);
    for (vtkIdType i = 0; i < share->GetNumberOfPoints(); i += 997)
    {
      double here[3], there[3];
      share->GetPoint(i, here);
      whole->GetPoint(offset + i, there);
      ASSERT_EQ(std::vector<double>(here, here + 3), std::vector<double>(there, there + 3)) << i;
      for (const char* name : arrays)
      {
        ASSERT_EQ(share->GetPointData()->GetArray(name)->GetComponent(i, 0),
                  whole->GetPointData()->GetArray(name)->GetComponent(offset + i, 0))
          << name << " " << i;
      }
    }
    offset += share->GetNumberOfPoints();
  }
  EXPECT_EQ(offset, whole->GetNumberOfPoints());
  // The GPU warp is piece 0's alone: other pieces draw nothing twice.
  mapping->OutputAtomsOff();
  ASSERT_EQ(mapping->UpdatePiece(1, 2, 0), 1);
  EXPECT_EQ(mapping->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_EQ(mapping->GetOutput()->GetFieldData()->GetNumberOfArrays(), 0);
}

TEST(vtkMesoMembraneMapping, BadInputsFailCleanly)
{
  vtkNew<vtkMesoTrajectoryReader> membrane;
  membrane->SetTopologyFileName(data_file("membranes/martini_dppc_chol_bilayer.gro").c_str());
  vtkNew<vtkMesoMeshReader> closed;
  closed->SetFileName(data_file("meshes/mito5_outer_membrane.obj").c_str());
  double seed[3];
  outer_membrane_point(closed, seed);
  vtkNew<vtkMesoMeshReader> open;
  open->SetFileName(data_file("meshes/cgal_mesh_with_border.off").c_str());
  vtkNew<vtkMesoMeshReader> degenerate;
  degenerate->SetFileName(data_file("meshes/bad/cgal_degtri_sliding.off").c_str());
  vtkNew<vtkMesoMeshReader> misoriented;
  misoriented->SetFileName(data_file("meshes/bad/cgal_tet-shuffled.off").c_str());
  struct Case
  {
    const char* name;
    vtkMesoMeshReader* surface;
    double seed[3];
    int tiles;
    double scale;
    const char* problem;
  };
  const Case cases[] = {
    { "seed far away", closed, { 100, 100, 100 }, 1, 1e-4, "away from the surface" },
    { "no tiles",
      closed,
      { seed[0], seed[1], seed[2] },
      0,
      1e-4,
      "tiles per side must be at least 1" },
    { "negative scale", closed, { seed[0], seed[1], seed[2] }, 1, -1, "membrane-to-mesh scale" },
    { "disk meets the mesh boundary", open, { 0, 0, 0 }, 3, 1.0, "boundary" },
    { "degenerate triangles", degenerate, { 0, 0, 0 }, 1, 0.001, "degenerate" },
    { "inconsistent orientation", misoriented, { 0, 0, 0 }, 1, 0.001, "oriented" },
  };
  for (const Case& c : cases)
  {
    SCOPED_TRACE(c.name);
    vtkNew<vtkMesoMembraneMapping> mapping;
    mesolens_test::EventRecorder events(mapping);
    mapping->SetSurfaceConnection(c.surface->GetOutputPort());
    mapping->SetMembraneConnection(membrane->GetOutputPort());
    mapping->SetSeedPoint(const_cast<double*>(c.seed));
    mapping->SetTiles(c.tiles);
    mapping->SetMembraneToMeshScale(c.scale);
    if (std::string(c.name) == "disk meets the mesh boundary")
    {
      double point[3];
      c.surface->Update();
      c.surface->GetOutput()->GetPoint(0, point);
      mapping->SetSeedPoint(point);
    }
    EXPECT_EQ(mapping->GetExecutive()->Update(), 0);
    EXPECT_EQ(mapping->GetOutput()->GetNumberOfPoints(), 0);
    EXPECT_NE(events.AllErrors().find(c.problem), std::string::npos) << events.AllErrors();
  }
  // A disk larger than the organelle: the largest k that fits, or with MapWhatFits off an error.
  for (const bool fit : { true, false })
  {
    SCOPED_TRACE(fit ? "map what fits" : "fail");
    vtkNew<vtkMesoMembraneMapping> mapping;
    mesolens_test::EventRecorder events(mapping);
    mapping->SetSurfaceConnection(closed->GetOutputPort());
    mapping->SetMembraneConnection(membrane->GetOutputPort());
    mapping->SetSeedPoint(seed);
    mapping->SetTiles(40);
    mapping->SetMembraneToMeshScale(1e-4);
    mapping->SetMapWhatFits(fit);
    EXPECT_EQ(mapping->GetExecutive()->Update(), fit ? 1 : 0);
    if (fit)
    {
      vtkPolyData* out = mapping->GetOutput();
      const double mapped = field(out, vtkMesoArrayNames::TilesMapped);
      EXPECT_EQ(field(out, vtkMesoArrayNames::TilesRequested), 40.0);
      EXPECT_GE(mapped, 1.0);
      EXPECT_LT(mapped, 40.0);
      EXPECT_EQ(field(out, vtkMesoArrayNames::Tiles), mapped);
      EXPECT_EQ(out->GetNumberOfPoints(),
                vtkIdType(mapped * mapped) * membrane->GetOutput()->GetNumberOfPoints());
      EXPECT_NE(events.AllWarnings().find("instead of 40 x 40"), std::string::npos)
        << events.AllWarnings();
      auto* note = vtkStringArray::SafeDownCast(
        out->GetFieldData()->GetAbstractArray(vtkMesoArrayNames::MappingNote));
      ASSERT_NE(note, nullptr);
      EXPECT_NE(note->GetValue(0).find("instead of 40 x 40"), std::string::npos);
    }
    else
    {
      EXPECT_EQ(mapping->GetOutput()->GetNumberOfPoints(), 0);
      EXPECT_NE(events.AllErrors().find("geodesic disk"), std::string::npos) << events.AllErrors();
    }
  }
  // Molecule instancing without molecule ids: a plain point set.
  vtkNew<vtkSphereSource> points;
  vtkNew<vtkMesoMembraneMapping> mapping;
  mesolens_test::EventRecorder events(mapping);
  mapping->SetSurfaceConnection(closed->GetOutputPort());
  mapping->SetMembraneConnection(points->GetOutputPort());
  mapping->SetSeedPoint(seed);
  mapping->SetMembraneToMeshScale(1e-4);
  mapping->SetMappingMethodToMoleculeInstancing();
  EXPECT_EQ(mapping->GetExecutive()->Update(), 0);
  EXPECT_NE(events.AllErrors().find("molecule ids"), std::string::npos) << events.AllErrors();
  // A radius of zero for the disk filter.
  vtkNew<vtkMesoGeodesicDisk> disk;
  mesolens_test::EventRecorder disk_events(disk);
  disk->SetInputConnection(closed->GetOutputPort());
  disk->SetSeedPoint(seed);
  disk->SetRadius(0);
  EXPECT_EQ(disk->GetExecutive()->Update(), 0);
  EXPECT_NE(disk_events.AllErrors().find("radius"), std::string::npos) << disk_events.AllErrors();
}

TEST(vtkMesoMembraneMapping, RefusesASurfaceOnlyForTheDefectsTheMeshReportFinds)
{
  using mesolens_test::data_file;
  vtkNew<vtkMesoTrajectoryReader> membrane;
  membrane->SetTopologyFileName(data_file("membranes/martini_dppc_chol_bilayer.gro").c_str());
  for (const char* name :
       { "meshes/mito5_outer_membrane.obj", "meshes/hipsc_cell_membrane_1.obj",
         "meshes/celegans_embryo_cell10_T10.ply", "meshes/cgal_mesh_with_border.off",
         "meshes/bad/cgal_cube-ouvert.off", "meshes/bad/cgal_tet-shuffled.off",
         "meshes/bad/cgal_tetra_intersected_by_triangle.off", "meshes/bad/cgal_degtri_sliding.off",
         "meshes/bad/cgal_triangular_hole.off" })
  {
    SCOPED_TRACE(name);
    vtkNew<vtkMesoMeshReader> surface;
    surface->SetFileName(data_file(name).c_str());
    surface->Update();
    vtkNew<vtkMesoMeshReport> report;
    report->SetInputConnection(surface->GetOutputPort());
    report->Update();
    vtkNew<vtkMesoMembraneMapping> mapping;
    mesolens_test::EventRecorder events(mapping);
    mapping->SetSurfaceConnection(surface->GetOutputPort());
    mapping->SetMembraneConnection(membrane->GetOutputPort());
    mapping->SetSeedPoint(surface->GetOutput()->GetPoint(0));
    mapping->SetMembraneToMeshScale(1e-4);
    mapping->SetOutputAtoms(false);
    mapping->GetExecutive()->Update();
    const std::string errors = events.AllErrors();
    const bool usable =
      report->GetIsManifold() && report->GetNumberOfInconsistentlyOrientedEdges() == 0;
    if (usable)
    {
      // Whatever else may go wrong at this point, the surface itself is not refused.
      EXPECT_EQ(errors.find("2-manifold"), std::string::npos) << errors;
    }
    else
    {
      // The reason names the very defects the report lists, in its words.
      EXPECT_NE(errors.find("not a clean 2-manifold"), std::string::npos) << errors;
      EXPECT_NE(errors.find(report->GetDefectsDescription()), std::string::npos)
        << errors << "\nreport: " << report->GetDefectsDescription();
    }
  }
}

TEST(vtkMesoMembraneMapping, CoarseCellMapsOnTheSmoothSurfaceThroughItsVertices)
{
  // A stem cell's membrane whose triangles (edges up to 8 µm) dwarf a 6 nm DPPC patch: the disk
  // is refined on the smooth surface through the mesh's vertices, which stay where they are,
  // and the atoms lie in the shell around that surface.
  using mesolens_test::data_file;
  vtkNew<vtkMesoMeshReader> surface;
  surface->SetFileName(data_file("meshes/hipsc_cell_membrane_1.obj").c_str());
  surface->Update();
  vtkNew<vtkMesoTrajectoryReader> membrane;
  membrane->SetTopologyFileName(data_file("membranes/dppc128_slipids_323K.gro").c_str());
  membrane->RemoveWatersOn();
  membrane->Update();
  for (const vtkIdType vertex : { 0, 500, 1000 })
  {
    for (const int tiles : { 1, 3 })
    {
      SCOPED_TRACE(std::to_string(vertex) + " " + std::to_string(tiles));
      vtkNew<vtkMesoMembraneMapping> mapping;
      mesolens_test::EventRecorder events(mapping);
      mapping->SetSurfaceConnection(surface->GetOutputPort());
      mapping->SetMembraneConnection(membrane->GetOutputPort());
      mapping->SetSeedPoint(surface->GetOutput()->GetPoint(vertex));
      mapping->SetTiles(tiles);
      mapping->SetMembraneToMeshScale(1e-4);
      ASSERT_EQ(mapping->GetExecutive()->Update(), 1) << events.AllErrors();
      vtkPolyData* out = mapping->GetOutput();
      EXPECT_EQ(field(out, vtkMesoArrayNames::TilesMapped), double(tiles));
      EXPECT_GE(field(out, vtkMesoArrayNames::RefinementLevels), 8.0);
      EXPECT_EQ(out->GetNumberOfPoints(),
                vtkIdType(tiles * tiles) * membrane->GetOutput()->GetNumberOfPoints());
      vtkPolyData* disk = mapping->GetOutput(1);
      vtkDataArray* original = disk->GetPointData()->GetArray(vtkMesoArrayNames::OriginalPointId);
      ASSERT_NE(original, nullptr);
      for (vtkIdType p = 0; p < disk->GetNumberOfPoints(); ++p)
      {
        const vtkIdType input = static_cast<vtkIdType>(original->GetTuple1(p));
        if (input >= 0)
        {
          double a[3], b[3];
          disk->GetPoint(p, a);
          surface->GetOutput()->GetPoint(input, b);
          EXPECT_EQ(a[0], b[0]);
          EXPECT_EQ(a[1], b[1]);
          EXPECT_EQ(a[2], b[2]);
        }
      }
      // Every atom within the bilayer's half thickness (about 30 Å here) of the disk.
      vtkNew<vtkStaticCellLocator> locator;
      locator->SetDataSet(disk);
      locator->BuildLocator();
      double worst = 0;
      for (vtkIdType a = 0; a < out->GetNumberOfPoints(); a += 37)
      {
        double x[3], closest[3], distance2 = 0;
        vtkIdType cell = 0;
        int sub = 0;
        out->GetPoint(a, x);
        locator->FindClosestPoint(x, closest, cell, sub, distance2);
        worst = std::max(worst, std::sqrt(distance2));
      }
      EXPECT_LT(worst, 35e-4); // µm: 35 Å
      EXPECT_GT(worst, 15e-4); // the head groups do stand off the surface
    }
  }
}
