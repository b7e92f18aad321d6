// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoArrayNames.h"
#include "vtkMesoRibbons.h"

#include "mesolens_test_data.h"
#include "mesolens_vtk_test_utilities.h"
#include "vtkMesoSecondaryStructure.h"
#include "vtkMesoStructureReader.h"
#include "vtkMesoTrajectoryReader.h"

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkFeatureEdges.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataConnectivityFilter.h>
#include <vtkStringArray.h>

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

namespace {
/// Reader -> DSSP -> ribbons for a file of Data/.
struct Pipeline
{
  vtkNew<vtkMesoStructureReader> Reader;
  vtkNew<vtkMesoSecondaryStructure> Assignment;
  vtkNew<vtkMesoRibbons> Ribbons;

  explicit Pipeline(const std::string& path)
  {
    this->Reader->SetFileName(path.c_str());
    this->Assignment->SetInputConnection(this->Reader->GetOutputPort());
    this->Ribbons->SetInputConnection(this->Assignment->GetOutputPort());
  }
};

/// Edges used by other than two triangles (0 for closed 2-manifold pieces).
vtkIdType open_edges(vtkPolyData* mesh)
{
  vtkNew<vtkFeatureEdges> edges;
  edges->SetInputData(mesh);
  edges->BoundaryEdgesOn();
  edges->NonManifoldEdgesOn();
  edges->FeatureEdgesOff();
  edges->ManifoldEdgesOff();
  edges->Update();
  return edges->GetOutput()->GetNumberOfCells();
}
} // namespace

TEST(vtkMesoRibbons, CartoonOf1tiiIsClosedAndCarriesTheAtomArrays)
{
  Pipeline pipeline(mesolens_test::data_file("proteins/1tii.pdb"));
  mesolens_test::EventRecorder events(pipeline.Ribbons);
  pipeline.Ribbons->Update();
  ASSERT_TRUE(events.Errors.empty()) << events.AllErrors();
  vtkPolyData* ribbons = pipeline.Ribbons->GetOutput();
  EXPECT_GT(ribbons->GetNumberOfPolys(), 30000);
  EXPECT_EQ(open_edges(ribbons), 0);
  ASSERT_NE(ribbons->GetPointData()->GetNormals(), nullptr);
  // Every vertex leads back to a CA atom; helices and strands both present; 7 chains.
  vtkPolyData* atoms = pipeline.Reader->GetOutput();
  auto* names = vtkStringArray::SafeDownCast(
    atoms->GetPointData()->GetAbstractArray(vtkMesoArrayNames::AtomName));
  vtkDataArray* atom_ids = ribbons->GetPointData()->GetArray(vtkMesoArrayNames::AtomId);
  vtkDataArray* classes = ribbons->GetPointData()->GetArray(vtkMesoArrayNames::SecondaryStructure);
  std::set<int> seen_classes;
  for (vtkIdType v = 0; v < ribbons->GetNumberOfPoints(); v += 97)
  {
    EXPECT_EQ(names->GetValue(vtkIdType(atom_ids->GetTuple1(v))), "CA");
    seen_classes.insert(int(classes->GetTuple1(v)));
  }
  EXPECT_TRUE(seen_classes.count(1)); // alpha helix
  EXPECT_TRUE(seen_classes.count(4)); // strand
  EXPECT_EQ(ribbons->GetPointData()->GetArray(vtkMesoArrayNames::ChainIndex)->GetRange()[1], 6.0);
  // A numeric atom array colours the ribbon: B-factors carried from the CA atoms.
  vtkDataArray* b = ribbons->GetPointData()->GetArray(vtkMesoArrayNames::BFactor);
  ASSERT_NE(b, nullptr);
  EXPECT_EQ(b->GetTuple1(0),
            atoms->GetPointData()
              ->GetArray(vtkMesoArrayNames::BFactor)
              ->GetTuple1(vtkIdType(atom_ids->GetTuple1(0))));
  // Per piece of chain: bounds and residue counts.
  vtkDataArray* pieces = ribbons->GetFieldData()->GetArray(vtkMesoArrayNames::SegmentBounds);
  ASSERT_NE(pieces, nullptr);
  EXPECT_GE(pieces->GetNumberOfTuples(), 7);
}

TEST(vtkMesoRibbons, LevelOfDetailAndCylinders)
{
  Pipeline pipeline(mesolens_test::data_file("proteins/1crn.pdb"));
  pipeline.Ribbons->SetSubdivisions(2);
  pipeline.Ribbons->Update();
  const vtkIdType coarse = pipeline.Ribbons->GetOutput()->GetNumberOfPolys();
  pipeline.Ribbons->SetSubdivisions(12);
  pipeline.Ribbons->Update();
  const vtkIdType fine = pipeline.Ribbons->GetOutput()->GetNumberOfPolys();
  EXPECT_GT(fine, 4 * coarse);
  // Per-piece counts: crambin is one piece; 2 samples per residue for it is the coarse mesh.
  vtkNew<vtkIntArray> one;
  one->InsertNextValue(2);
  pipeline.Ribbons->SetSegmentSubdivisions(one);
  pipeline.Ribbons->Update();
  EXPECT_EQ(pipeline.Ribbons->GetOutput()->GetNumberOfPolys(), coarse);
  // A list of another length is ignored.
  one->InsertNextValue(3);
  one->Modified();
  pipeline.Ribbons->Update();
  EXPECT_EQ(pipeline.Ribbons->GetOutput()->GetNumberOfPolys(), fine);
  pipeline.Ribbons->SetSegmentSubdivisions(nullptr);
  // Helices as cylinders: more pieces (each cylinder is its own closed piece), still closed.
  pipeline.Ribbons->HelixAsCylinderOn();
  pipeline.Ribbons->Update();
  vtkNew<vtkPolyDataConnectivityFilter> parts;
  parts->SetInputData(pipeline.Ribbons->GetOutput());
  parts->SetExtractionModeToAllRegions();
  parts->Update();
  EXPECT_GE(parts->GetNumberOfExtractedRegions(), 3); // two helices and the rest
  EXPECT_EQ(open_edges(pipeline.Ribbons->GetOutput()), 0);
}

TEST(vtkMesoRibbons, NucleicAcidsAsTubesThroughPhosphorus)
{
  // B-DNA: two strands of 12 nucleotides traced through their P atoms (no DSSP needed).
  vtkNew<vtkMesoStructureReader> reader;
  reader->SetFileName(mesolens_test::data_file("proteins/1bna.pdb").c_str());
  vtkNew<vtkMesoRibbons> ribbons;
  ribbons->SetInputConnection(reader->GetOutputPort());
  ribbons->Update();
  vtkPolyData* tubes = ribbons->GetOutput();
  EXPECT_GT(tubes->GetNumberOfPolys(), 500);
  EXPECT_EQ(open_edges(tubes), 0);
  EXPECT_EQ(tubes->GetFieldData()->GetArray(vtkMesoArrayNames::SegmentBounds)->GetNumberOfTuples(),
            2);
  auto* names = vtkStringArray::SafeDownCast(
    reader->GetOutput()->GetPointData()->GetAbstractArray(vtkMesoArrayNames::AtomName));
  EXPECT_EQ(names->GetValue(
              vtkIdType(tubes->GetPointData()->GetArray(vtkMesoArrayNames::AtomId)->GetTuple1(0))),
            "P");
}

TEST(vtkMesoRibbons, ProteasomeFromAGroFile)
{
  const std::string path = mesolens_test::shared_file("proteins/3l5q.gro");
  if (!mesolens_test::exists(path))
    GTEST_SKIP() << "needs ../shared/data";
  vtkNew<vtkMesoTrajectoryReader> reader;
  reader->SetTopologyFileName(path.c_str());
  vtkNew<vtkMesoSecondaryStructure> dssp;
  dssp->SetInputConnection(reader->GetOutputPort());
  vtkNew<vtkMesoRibbons> ribbons;
  ribbons->SetInputConnection(dssp->GetOutputPort());
  ribbons->SetSubdivisions(3);
  mesolens_test::EventRecorder events(ribbons);
  ribbons->Update();
  ASSERT_TRUE(events.Errors.empty()) << events.AllErrors();
  EXPECT_GT(ribbons->GetOutput()->GetNumberOfPolys(), 400000);
  EXPECT_GE(ribbons->GetOutput()
              ->GetFieldData()
              ->GetArray(vtkMesoArrayNames::SegmentBounds)
              ->GetNumberOfTuples(),
            28);
}

TEST(vtkMesoRibbons, BadInputs)
{
  vtkNew<vtkMesoRibbons> ribbons;
  mesolens_test::EventRecorder events(ribbons);
  // Points without the reader's arrays.
  vtkNew<vtkPolyData> plain;
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  plain->SetPoints(points);
  ribbons->SetInputData(plain);
  ribbons->Update();
  EXPECT_NE(events.AllErrors().find(vtkMesoArrayNames::AtomName), std::string::npos);
  EXPECT_EQ(ribbons->GetOutput()->GetNumberOfPoints(), 0);
  // No atoms.
  events.Errors.clear();
  vtkNew<vtkPolyData> empty;
  ribbons->SetInputData(empty);
  ribbons->Update();
  EXPECT_FALSE(events.Errors.empty());
  // No backbone at all (a lipid bilayer): an empty ribbon, no error.
  events.Errors.clear();
  vtkNew<vtkMesoTrajectoryReader> lipids;
  lipids->SetTopologyFileName(
    mesolens_test::data_file("membranes/martini_dppc_vesicle.gro").c_str());
  ribbons->SetInputConnection(lipids->GetOutputPort());
  ribbons->Update();
  EXPECT_TRUE(events.Errors.empty()) << events.AllErrors();
  EXPECT_EQ(ribbons->GetOutput()->GetNumberOfPoints(), 0);
  // A chain of one residue: a small closed sphere.
  vtkNew<vtkMesoStructureReader> crambin;
  crambin->SetFileName(mesolens_test::data_file("proteins/1crn.pdb").c_str());
  crambin->Update();
  vtkNew<vtkPolyData> first;
  first->DeepCopy(crambin->GetOutput());
  vtkNew<vtkPoints> moved;
  moved->DeepCopy(first->GetPoints());
  for (vtkIdType a = 8; a < moved->GetNumberOfPoints(); ++a)
  {
    double p[3];
    moved->GetPoint(a, p);
    moved->SetPoint(a, p[0] + 100, p[1], p[2]); // residue 1 far from the rest
  }
  first->SetPoints(moved);
  ribbons->SetInputData(first);
  ribbons->Update();
  EXPECT_TRUE(events.Errors.empty()) << events.AllErrors();
  EXPECT_EQ(open_edges(ribbons->GetOutput()), 0);
  EXPECT_GE(ribbons->GetOutput()
              ->GetFieldData()
              ->GetArray(vtkMesoArrayNames::SegmentBounds)
              ->GetNumberOfTuples(),
            2);
  // A NaN Cα.
  first->GetPoints()->SetPoint(1, std::nan(""), 0, 0);
  first->Modified();
  ribbons->Update();
  EXPECT_NE(events.AllErrors().find("non-finite"), std::string::npos);
  EXPECT_EQ(ribbons->GetOutput()->GetNumberOfPoints(), 0);
}
