// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoArrayNames.h"
#include "vtkMesoStructuredCutaway.h"

#include "mesolens_test_data.h"
#include "mesolens_vtk_test_utilities.h"
#include "vtkMesoTrajectoryReader.h"

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkInformation.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPlane.h>
#include <vtkPlatonicSolidSource.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSphere.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkStringArray.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace {
/// Two atoms per molecule, the molecules just outside the icosahedron: first the 20 over its
/// triangle centres, then the 30 over its edge midpoints.
vtkSmartPointer<vtkPolyData> molecules_over(vtkPolyData* solid)
{
  std::vector<std::array<double, 3>> directions;
  for (vtkIdType t = 0; t < solid->GetNumberOfCells(); ++t)
  {
    vtkIdType size = 0;
    const vtkIdType* ids = nullptr;
    solid->GetPolys()->GetCellAtId(t, size, ids);
    std::array<double, 3> c{ 0, 0, 0 };
    for (vtkIdType k = 0; k < size; ++k)
    {
      double p[3];
      solid->GetPoint(ids[k], p);
      for (int d = 0; d < 3; ++d)
        c[d] += p[d] / double(size);
    }
    directions.push_back(c);
  }
  std::vector<std::pair<vtkIdType, vtkIdType>> edges;
  for (vtkIdType t = 0; t < solid->GetNumberOfCells(); ++t)
  {
    vtkIdType size = 0;
    const vtkIdType* ids = nullptr;
    solid->GetPolys()->GetCellAtId(t, size, ids);
    for (vtkIdType k = 0; k < size; ++k)
    {
      const vtkIdType a = ids[k];
      const vtkIdType b = ids[(k + 1) % size];
      if (a < b)
        edges.emplace_back(a, b);
    }
  }
  for (const auto& [a, b] : edges)
  {
    double p[3];
    double q[3];
    solid->GetPoint(a, p);
    solid->GetPoint(b, q);
    directions.push_back({ (p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2 });
  }
  auto atoms = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  vtkNew<vtkIntArray> molecule;
  molecule->SetName(vtkMesoArrayNames::MoleculeId);
  for (std::size_t m = 0; m < directions.size(); ++m)
  {
    const auto& d = directions[m];
    const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (double offset : { -0.001, 0.001 })
    {
      points->InsertNextPoint(1.1 * d[0] / length + offset, 1.1 * d[1] / length,
                              1.1 * d[2] / length);
      molecule->InsertNextValue(int(100 + m));
    }
  }
  atoms->SetPoints(points);
  atoms->GetPointData()->AddArray(molecule);
  return atoms;
}

struct Scene
{
  vtkNew<vtkPlatonicSolidSource> Solid;
  vtkSmartPointer<vtkPolyData> Atoms;
  vtkNew<vtkMesoStructuredCutaway> Cutaway;
  vtkNew<vtkSphere> Everything;

  Scene()
  {
    this->Solid->SetSolidTypeToIcosahedron();
    this->Solid->Update();
    this->Atoms = molecules_over(this->Solid->GetOutput());
    this->Cutaway->SetInputData(this->Atoms);
    this->Cutaway->SetStructureConnection(this->Solid->GetOutputPort());
    this->Everything->SetRadius(100);
    this->Cutaway->SetCutFunction(this->Everything);
  }

  /// Visible flag of molecule m (its first atom).
  int Visible(int m)
  {
    return int(this->Cutaway->GetOutput()
                 ->GetPointData()
                 ->GetArray(vtkMesoArrayNames::Visible)
                 ->GetTuple1(2 * m));
  }

  vtkIdType Field(const char* name)
  {
    return vtkIdType(this->Cutaway->GetOutput()->GetFieldData()->GetArray(name)->GetTuple1(0));
  }
};
} // namespace

TEST(vtkMesoStructuredCutaway, CentresFirstEdgesLastWithoutReassigning)
{
  Scene scene;
  scene.Cutaway->SetFractionHidden(0.4);
  scene.Cutaway->Update();
  ASSERT_EQ(scene.Cutaway->GetOutput()->GetNumberOfPoints(), 100);
  for (int m = 0; m < 50; ++m)
    EXPECT_EQ(scene.Visible(m), m < 20 ? 0 : 1) << m;
  EXPECT_EQ(scene.Field(vtkMesoArrayNames::MoleculesInCut), 50);
  EXPECT_EQ(scene.Field(vtkMesoArrayNames::MoleculesHidden), 20);
  vtkDataArray* priority =
    scene.Cutaway->GetOutput()->GetPointData()->GetArray(vtkMesoArrayNames::RemovalPriority);
  EXPECT_NEAR(priority->GetTuple1(0), 1.0, 1e-6);
  EXPECT_NEAR(priority->GetTuple1(40), 0.0, 1e-6);
  // Inverted, another k and fraction, then random order: the assignment stays.
  scene.Cutaway->InvertedOn();
  scene.Cutaway->SetFractionHidden(0.6);
  scene.Cutaway->SetK(-0.5);
  scene.Cutaway->Update();
  for (int m = 0; m < 50; ++m)
    EXPECT_EQ(scene.Visible(m), m < 20 ? 1 : 0) << m;
  scene.Cutaway->RandomOrderOn();
  scene.Cutaway->Update();
  EXPECT_EQ(scene.Field(vtkMesoArrayNames::MoleculesHidden), 30);
  EXPECT_EQ(scene.Cutaway->GetNumberOfAssignments(), 1);
}

TEST(vtkMesoStructuredCutaway, PlaneCutLeavesTheOtherSide)
{
  Scene scene;
  vtkNew<vtkPlane> plane; // the cut: z <= 0
  plane->SetNormal(0, 0, 1);
  scene.Cutaway->SetCutFunction(plane);
  scene.Cutaway->SetFractionHidden(1.0);
  scene.Cutaway->Update();
  vtkPolyData* output = scene.Cutaway->GetOutput();
  vtkDataArray* visible = output->GetPointData()->GetArray(vtkMesoArrayNames::Visible);
  vtkIdType hidden = 0;
  for (vtkIdType a = 0; a < output->GetNumberOfPoints(); a += 2)
  {
    double p[3];
    output->GetPoint(a, p);
    EXPECT_EQ(visible->GetTuple1(a), p[2] > 0.001 ? 1 : 0);
    hidden += visible->GetTuple1(a) == 0;
  }
  EXPECT_EQ(scene.Field(vtkMesoArrayNames::MoleculesHidden), hidden);
  // Moving the plane only reorders.
  plane->SetOrigin(0, 0, 0.5);
  scene.Cutaway->Update();
  EXPECT_GT(scene.Field(vtkMesoArrayNames::MoleculesHidden), hidden);
  EXPECT_EQ(scene.Cutaway->GetNumberOfAssignments(), 1);
  // No cut: nothing hidden.
  scene.Cutaway->SetCutFunction(nullptr);
  scene.Cutaway->Update();
  EXPECT_EQ(scene.Field(vtkMesoArrayNames::MoleculesHidden), 0);
}

TEST(vtkMesoStructuredCutaway, BadInputsGiveAnErrorAndNoOutput)
{
  {
    // Molecules on a line describe no surface to make a structure from.
    vtkNew<vtkPolyData> line;
    vtkNew<vtkPoints> points;
    for (int i = 0; i < 50; ++i)
      points->InsertNextPoint(i, 0, 0);
    line->SetPoints(points);
    vtkNew<vtkMesoStructuredCutaway> alone;
    alone->SetInputData(line);
    mesolens_test::EventRecorder events(alone);
    alone->Update();
    EXPECT_NE(events.AllErrors().find("describe no surface"), std::string::npos)
      << events.AllErrors();
    EXPECT_EQ(alone->GetOutput()->GetNumberOfPoints(), 0);
    EXPECT_EQ(alone->GetOutput(1)->GetNumberOfCells(), 0);
  }
  {
    Scene scene;
    vtkNew<vtkPolyData> lines; // a structure without triangles
    vtkNew<vtkPoints> points;
    points->InsertNextPoint(0, 0, 0);
    points->InsertNextPoint(1, 0, 0);
    lines->SetPoints(points);
    vtkNew<vtkCellArray> cells;
    cells->InsertNextCell({ 0, 1 });
    lines->SetLines(cells);
    scene.Cutaway->SetInputData(1, lines);
    mesolens_test::EventRecorder events(scene.Cutaway);
    scene.Cutaway->Update();
    EXPECT_NE(events.AllErrors().find("Cannot cut the molecules away"), std::string::npos)
      << events.AllErrors();
    EXPECT_EQ(scene.Cutaway->GetOutput()->GetNumberOfPoints(), 0);
  }
  {
    Scene scene;
    scene.Atoms->GetPoints()->SetPoint(7, std::nan(""), 0, 0);
    mesolens_test::EventRecorder events(scene.Cutaway);
    scene.Cutaway->Update();
    EXPECT_NE(events.AllErrors().find("atom 7 has a non-finite position"), std::string::npos)
      << events.AllErrors();
    EXPECT_EQ(scene.Cutaway->GetOutput()->GetNumberOfPoints(), 0);
  }
  {
    // Water alone: nothing to make a structure from.
    vtkNew<vtkPolyData> water;
    vtkNew<vtkPoints> points;
    vtkNew<vtkIntArray> ids;
    ids->SetName(vtkMesoArrayNames::MoleculeId);
    vtkNew<vtkStringArray> names;
    names->SetName(vtkMesoArrayNames::ResidueName);
    for (int i = 0; i < 300; ++i)
    {
      points->InsertNextPoint(i % 10, (i / 10) % 10, i / 100);
      ids->InsertNextValue(i / 3);
      names->InsertNextValue("SOL");
    }
    water->SetPoints(points);
    water->GetPointData()->AddArray(ids);
    water->GetPointData()->AddArray(names);
    vtkNew<vtkMesoStructuredCutaway> alone;
    alone->SetInputData(water);
    mesolens_test::EventRecorder events(alone);
    alone->Update();
    EXPECT_NE(events.AllErrors().find("0 of the 100 molecules are neither water nor ions"),
              std::string::npos)
      << events.AllErrors();
    EXPECT_EQ(alone->GetOutput()->GetNumberOfPoints(), 0);
  }
  {
    vtkNew<vtkMesoStructuredCutaway> cutaway;
    cutaway->SetK(5);
    EXPECT_DOUBLE_EQ(cutaway->GetK(), 0.99);
    cutaway->SetFractionHidden(-1);
    EXPECT_DOUBLE_EQ(cutaway->GetFractionHidden(), 0.0);
  }
}

TEST(vtkMesoStructuredCutaway, MakesTheStructureFromTheMoleculesWhenNoneIsGiven)
{
  // 2000 molecules of one atom on a sphere of radius 30: the structure is made from them.
  vtkNew<vtkPolyData> atoms;
  vtkNew<vtkPoints> points;
  const double golden = 3.14159265358979 * (3 - std::sqrt(5.0));
  for (int i = 0; i < 2000; ++i)
  {
    const double z = 1 - 2 * (i + 0.5) / 2000;
    const double r = std::sqrt(1 - z * z);
    points->InsertNextPoint(30 * r * std::cos(golden * i), 30 * r * std::sin(golden * i), 30 * z);
  }
  atoms->SetPoints(points);
  vtkNew<vtkMesoStructuredCutaway> cutaway;
  cutaway->SetInputData(atoms);
  cutaway->SetStructureVertices(200);
  vtkNew<vtkSphere> everything;
  everything->SetRadius(100);
  cutaway->SetCutFunction(everything);
  cutaway->SetFractionHidden(0.25);
  cutaway->Update();
  vtkPolyData* structure = cutaway->GetOutput(1);
  const vtkIdType made_vertices = structure->GetNumberOfPoints();
  EXPECT_GT(structure->GetNumberOfPoints(), 120);
  EXPECT_LT(structure->GetNumberOfPoints(), 320);
  EXPECT_GE(structure->GetFieldData()->GetArray(vtkMesoArrayNames::MinAngle)->GetTuple1(0), 30.0);
  EXPECT_LE(structure->GetFieldData()->GetArray(vtkMesoArrayNames::MaxAngle)->GetTuple1(0), 120.0);
  EXPECT_EQ(structure->GetFieldData()->GetArray(vtkMesoArrayNames::Components)->GetTuple1(0), 1.0);
  EXPECT_EQ(cutaway->GetOutput()
              ->GetFieldData()
              ->GetArray(vtkMesoArrayNames::MoleculesHidden)
              ->GetTuple1(0),
            500);
  // The hidden molecules are those nearest their triangles' centres.
  vtkDataArray* priority =
    cutaway->GetOutput()->GetPointData()->GetArray(vtkMesoArrayNames::RemovalPriority);
  vtkDataArray* visible =
    cutaway->GetOutput()->GetPointData()->GetArray(vtkMesoArrayNames::Visible);
  double lowest_hidden = 1;
  double highest_visible = 0;
  for (vtkIdType a = 0; a < 2000; ++a)
  {
    if (visible->GetTuple1(a) == 0)
      lowest_hidden = std::min(lowest_hidden, priority->GetTuple1(a));
    else
      highest_visible = std::max(highest_visible, priority->GetTuple1(a));
  }
  EXPECT_GE(lowest_hidden, highest_visible);
  // A new vertex count makes a new structure and a new assignment; the fraction does not.
  cutaway->SetFractionHidden(0.5);
  cutaway->Update();
  EXPECT_EQ(cutaway->GetNumberOfAssignments(), 1);
  cutaway->SetStructureVertices(100);
  cutaway->Update();
  EXPECT_EQ(cutaway->GetNumberOfAssignments(), 2);
  EXPECT_LT(cutaway->GetOutput(1)->GetNumberOfPoints(), made_vertices);
}

TEST(vtkMesoStructuredCutaway, MartiniVesicleCutOpenAndStableOverFrames)
{
  // 3072 DPPC lipids of a Martini vesicle split by its periodic box: gathered whole, the
  // structure made from the lipids' centres, cut by the plane x <= centre.
  vtkNew<vtkMesoTrajectoryReader> vesicle;
  vesicle->SetTopologyFileName(
    mesolens_test::data_file("membranes/martini_dppc_vesicle.gro").c_str());
  vesicle->SetTrajectoryFileName(
    mesolens_test::data_file("membranes/martini_dppc_vesicle.xtc").c_str());
  vtkNew<vtkMesoStructuredCutaway> cutaway;
  cutaway->SetInputConnection(vesicle->GetOutputPort());
  cutaway->SetStructureVertices(300);
  cutaway->SetFractionHidden(0.5);
  mesolens_test::EventRecorder events(cutaway);
  cutaway->Update();
  ASSERT_TRUE(events.Errors.empty()) << events.AllErrors();
  // Gathered: the beads lie in a shell around their mean, not across the box.
  vtkPolyData* atoms = cutaway->GetOutput();
  double centre[3] = { 0, 0, 0 };
  const vtkIdType n = atoms->GetNumberOfPoints();
  for (vtkIdType a = 0; a < n; ++a)
  {
    double p[3];
    atoms->GetPoint(a, p);
    for (int d = 0; d < 3; ++d)
      centre[d] += p[d] / double(n);
  }
  std::vector<double> radii;
  for (vtkIdType a = 0; a < n; ++a)
  {
    double p[3];
    atoms->GetPoint(a, p);
    radii.push_back(std::hypot(p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]));
  }
  std::sort(radii.begin(), radii.end());
  EXPECT_LT(radii[radii.size() * 95 / 100], 130.0); // Å; split across the box it was ~300
  EXPECT_GT(radii[radii.size() * 5 / 100], 50.0);

  vtkNew<vtkPlane> plane;
  plane->SetOrigin(centre);
  plane->SetNormal(1, 0, 0);
  cutaway->SetCutFunction(plane);
  cutaway->Update();
  auto field = [&](const char* name) {
    return vtkIdType(cutaway->GetOutput()->GetFieldData()->GetArray(name)->GetTuple1(0));
  };
  const vtkIdType in_cut = field(vtkMesoArrayNames::MoleculesInCut);
  EXPECT_GT(in_cut, 1300); // about half of 3072
  EXPECT_LT(in_cut, 1800);
  EXPECT_EQ(field(vtkMesoArrayNames::MoleculesHidden), std::llround(0.5 * double(in_cut)));
  // The structure through the bilayer's middle: one closed sheet of even triangles.
  vtkPolyData* structure = cutaway->GetOutput(1);
  auto quality = [&](const char* name) {
    return structure->GetFieldData()->GetArray(name)->GetTuple1(0);
  };
  EXPECT_GT(structure->GetNumberOfPoints(), 255);
  EXPECT_LT(structure->GetNumberOfPoints(), 345);
  EXPECT_GE(quality(vtkMesoArrayNames::MinAngle), 30.0);
  EXPECT_LE(quality(vtkMesoArrayNames::MaxAngle), 120.0);
  EXPECT_LT(quality(vtkMesoArrayNames::EdgeSpread), 0.25);
  EXPECT_EQ(quality(vtkMesoArrayNames::BoundaryEdges), 0.0);
  EXPECT_EQ(quality(vtkMesoArrayNames::Components), 1.0);
  const vtkIdType faces = structure->GetNumberOfCells();
  EXPECT_EQ(structure->GetNumberOfPoints() - 3 * faces / 2 + faces, 2); // a sphere
  // Its vertices between the leaflets: closer to the centre than most outer lipids.
  for (vtkIdType v = 0; v < structure->GetNumberOfPoints(); ++v)
  {
    double p[3];
    structure->GetPoint(v, p);
    const double r = std::hypot(p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]);
    EXPECT_GT(r, 55.0);
    EXPECT_LT(r, 110.0);
  }

  // A slider: new fractions reuse the order and hand on the same points (no new upload).
  vtkPoints* positions = cutaway->GetOutput()->GetPoints();
  const int orderings = cutaway->GetNumberOfOrderings();
  for (double fraction : { 0.2, 0.8, 0.5 })
  {
    cutaway->SetFractionHidden(fraction);
    cutaway->Update();
    EXPECT_EQ(field(vtkMesoArrayNames::MoleculesHidden), std::llround(fraction * double(in_cut)));
    EXPECT_EQ(cutaway->GetOutput()->GetPoints(), positions);
  }
  EXPECT_EQ(cutaway->GetNumberOfOrderings(), orderings);
  cutaway->SetInverted(true);
  cutaway->Update();
  EXPECT_EQ(cutaway->GetNumberOfOrderings(), orderings + 1);
  cutaway->SetInverted(false);
  cutaway->Update();

  // K: no change to the strict order's mask; in the probabilistic order a new mask of the
  // same size.
  auto mask = [&]() {
    vtkDataArray* visible =
      cutaway->GetOutput()->GetPointData()->GetArray(vtkMesoArrayNames::Visible);
    std::vector<int> values(std::size_t(visible->GetNumberOfTuples()));
    for (vtkIdType a = 0; a < visible->GetNumberOfTuples(); ++a)
      values[std::size_t(a)] = int(visible->GetTuple1(a));
    return values;
  };
  const auto strict = mask();
  cutaway->SetK(-0.8);
  cutaway->Update();
  EXPECT_EQ(mask(), strict);
  cutaway->ProbabilisticOrderOn();
  cutaway->Update();
  const auto sharp = mask();
  EXPECT_NE(sharp, strict);
  EXPECT_EQ(field(vtkMesoArrayNames::MoleculesHidden), std::llround(0.5 * double(in_cut)));
  cutaway->SetK(0.8);
  cutaway->Update();
  EXPECT_NE(mask(), sharp);
  cutaway->ProbabilisticOrderOff();
  cutaway->SetK(0);
  cutaway->Update();
  EXPECT_EQ(mask(), strict);

  // Over the next frames the order holds: of the molecules hidden in frame 0, nearly all stay
  // hidden, and the molecules are not assigned again.
  auto hidden_molecules = [&]() {
    std::set<long long> hidden;
    vtkPolyData* output = cutaway->GetOutput();
    vtkDataArray* visible = output->GetPointData()->GetArray(vtkMesoArrayNames::Visible);
    vtkDataArray* ids = output->GetPointData()->GetArray(vtkMesoArrayNames::MoleculeId);
    for (vtkIdType a = 0; a < output->GetNumberOfPoints(); ++a)
      if (visible->GetTuple1(a) == 0)
        hidden.insert((long long)ids->GetTuple1(a));
    return hidden;
  };
  // In every mode, over all 11 frames (0 to 1000 ps).
  const int frames =
    vesicle->GetOutputInformation(0)->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  // A copy: the pipeline replaces the information's vector when it updates.
  const double* steps_in_information =
    vesicle->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  const std::vector<double> times(steps_in_information, steps_in_information + frames);
  ASSERT_EQ(frames, 11);
  for (int mode = 0; mode < 4; ++mode)
  {
    cutaway->SetInverted(mode == 1);
    cutaway->SetRandomOrder(mode == 2);
    cutaway->SetProbabilisticOrder(mode == 3);
    cutaway->UpdateTimeStep(times[0]);
    const std::set<long long> first = hidden_molecules();
    for (int frame = 1; frame < frames; ++frame)
    {
      cutaway->UpdateTimeStep(times[frame]);
      const std::set<long long> later = hidden_molecules();
      std::size_t kept = 0;
      for (long long m : first)
        kept += later.count(m);
      EXPECT_GT(double(kept) / double(first.size()), 0.9) << "mode " << mode << " frame " << frame;
    }
  }
  EXPECT_EQ(cutaway->GetNumberOfAssignments(), 1);
}

namespace {
/// The Martini DPPC bilayer with 20 % cholesterol read by `bilayer`, and `cutaway` of it (a
/// structure of 100 vertices) cut by `ball`, 40 Å around its middle.
void CutTheCholesterolBilayerByABall(vtkMesoTrajectoryReader* bilayer, vtkSphere* ball,
                                     vtkMesoStructuredCutaway* cutaway)
{
  bilayer->SetTopologyFileName(
    mesolens_test::data_file("membranes/martini_dppc_chol_bilayer.gro").c_str());
  bilayer->Update();
  double bounds[6];
  bilayer->GetOutput()->GetBounds(bounds);
  ball->SetCenter(0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]),
                  0.5 * (bounds[4] + bounds[5]));
  ball->SetRadius(40);
  cutaway->SetInputConnection(bilayer->GetOutputPort());
  cutaway->SetStructureVertices(100);
  cutaway->SetCutFunction(ball);
}

/// The atoms `output` hides, each expected to be of residue `only`.
vtkIdType HiddenAtomsAllOf(vtkPolyData* output, const std::string& only)
{
  auto* names = vtkStringArray::SafeDownCast(
    output->GetPointData()->GetAbstractArray(vtkMesoArrayNames::ResidueName));
  vtkDataArray* visible = output->GetPointData()->GetArray(vtkMesoArrayNames::Visible);
  EXPECT_NE(names, nullptr);
  EXPECT_NE(visible, nullptr);
  vtkIdType hidden = 0;
  for (vtkIdType a = 0; names && visible && a < output->GetNumberOfPoints(); ++a)
  {
    if (visible->GetTuple1(a) == 0)
    {
      EXPECT_EQ(names->GetValue(a), only);
      ++hidden;
    }
  }
  return hidden;
}
}

TEST(vtkMesoStructuredCutaway, PerResidueFractionsAndVisibleAtomsOnly)
{
  // A Martini DPPC bilayer with 20 % cholesterol, cut by a ball around its middle.
  vtkNew<vtkMesoTrajectoryReader> bilayer;
  vtkNew<vtkSphere> ball;
  vtkNew<vtkMesoStructuredCutaway> cutaway;
  CutTheCholesterolBilayerByABall(bilayer, ball, cutaway);
  const vtkIdType atom_count = bilayer->GetOutput()->GetNumberOfPoints();
  cutaway->SetFractionHidden(0.0);
  cutaway->SetFractionHiddenOfResidue("CHOL", 1.0);
  mesolens_test::EventRecorder events(cutaway);
  cutaway->Update();
  ASSERT_TRUE(events.Errors.empty()) << events.AllErrors();
  vtkPolyData* output = cutaway->GetOutput();
  ASSERT_EQ(output->GetNumberOfPoints(), atom_count);
  const vtkIdType hidden_chol = HiddenAtomsAllOf(output, "CHOL"); // only cholesterol is hidden
  const vtkIdType visible_count = atom_count - hidden_chol;
  EXPECT_GT(hidden_chol, 8 * 5); // beads of at least 5 cholesterols
  const vtkIdType hidden =
    vtkIdType(output->GetFieldData()->GetArray(vtkMesoArrayNames::MoleculesHidden)->GetTuple1(0));
  EXPECT_EQ(hidden * 8, hidden_chol); // 8 beads per Martini cholesterol
  EXPECT_EQ(
    output->GetFieldData()->GetArray(vtkMesoArrayNames::MoleculeVisible)->GetNumberOfTuples(), 450);

  // The visible atoms alone, with the bonds among them.
  const vtkIdType all_bonds = output->GetNumberOfLines();
  cutaway->ExtractVisibleAtomsOn();
  cutaway->Update();
  ASSERT_TRUE(events.Errors.empty()) << events.AllErrors();
  EXPECT_EQ(cutaway->GetOutput()->GetNumberOfPoints(), visible_count);
  EXPECT_LT(cutaway->GetOutput()->GetNumberOfLines(), all_bonds);
  EXPECT_GT(cutaway->GetOutput()->GetNumberOfLines(), all_bonds / 2);
  vtkDataArray* kept = cutaway->GetOutput()->GetPointData()->GetArray(vtkMesoArrayNames::Visible);
  EXPECT_EQ(kept->GetRange()[0], 1.0);
  // Clearing the per-residue fraction with nothing else hidden: every atom comes back.
  cutaway->RemoveAllResidueFractions();
  cutaway->Update();
  EXPECT_EQ(cutaway->GetOutput()->GetNumberOfPoints(), atom_count);
}

TEST(vtkMesoStructuredCutaway, OnlyTheMoleculesAHideableSelectionMatchesAreHidden)
{
  // The Martini DPPC/cholesterol bilayer, all of a ball's molecules to be hidden, but only
  // DPPC may be: every hidden atom is DPPC, every DPPC in the ball is hidden, CHOL stays.
  vtkNew<vtkMesoTrajectoryReader> bilayer;
  vtkNew<vtkSphere> ball;
  vtkNew<vtkMesoStructuredCutaway> cutaway;
  CutTheCholesterolBilayerByABall(bilayer, ball, cutaway);
  cutaway->SetFractionHidden(1.0);
  mesolens_test::EventRecorder events(cutaway);
  cutaway->Update();
  const double everything = cutaway->GetOutput()
                              ->GetFieldData()
                              ->GetArray(vtkMesoArrayNames::MoleculesHidden)
                              ->GetTuple1(0);
  cutaway->SetHideableSelection("lipid and not resname CHOL");
  cutaway->Update();
  ASSERT_TRUE(events.Errors.empty()) << events.AllErrors();
  vtkPolyData* output = cutaway->GetOutput();
  const vtkIdType hidden_dppc = HiddenAtomsAllOf(output, "DPPC");
  const double hidden =
    output->GetFieldData()->GetArray(vtkMesoArrayNames::MoleculesHidden)->GetTuple1(0);
  EXPECT_EQ(vtkIdType(hidden) * 12, hidden_dppc); // 12 beads per Martini DPPC
  EXPECT_GT(hidden, 10.0);
  EXPECT_LT(hidden, everything); // the ball's cholesterols stay
  // A bad selection is an error with empty outputs; "" hides every molecule again.
  cutaway->SetHideableSelection("lipid and");
  events.Clear();
  EXPECT_EQ(cutaway->GetExecutive()->Update(), 0);
  EXPECT_EQ(cutaway->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_FALSE(events.Errors.empty());
  cutaway->SetHideableSelection("");
  cutaway->Update();
  EXPECT_EQ(cutaway->GetOutput()
              ->GetFieldData()
              ->GetArray(vtkMesoArrayNames::MoleculesHidden)
              ->GetTuple1(0),
            everything);
}

namespace {
/// The made structure of `atoms` with 300 vertices, checked to be one sheet of even triangles
/// with `loops` boundary loops; empty when the filter failed.
vtkSmartPointer<vtkPolyData> made_structure(vtkPolyData* atoms, int loops, const char* name)
{
  vtkNew<vtkMesoStructuredCutaway> cutaway;
  cutaway->SetInputData(atoms);
  cutaway->SetStructureVertices(300);
  mesolens_test::EventRecorder events(cutaway);
  cutaway->Update();
  EXPECT_TRUE(events.Errors.empty()) << name << ": " << events.AllErrors();
  auto structure = vtkSmartPointer<vtkPolyData>::New();
  structure->ShallowCopy(cutaway->GetOutput(1));
  if (structure->GetNumberOfCells() == 0)
  {
    return structure;
  }
  auto quality = [&](const char* field) {
    return structure->GetFieldData()->GetArray(field)->GetTuple1(0);
  };
  EXPECT_GE(quality(vtkMesoArrayNames::MinAngle), 30.0) << name;
  EXPECT_LE(quality(vtkMesoArrayNames::MaxAngle), 120.0) << name;
  EXPECT_EQ(quality(vtkMesoArrayNames::Components), 1.0) << name;
  EXPECT_EQ(quality(vtkMesoArrayNames::BoundaryLoops), double(loops)) << name;
  EXPECT_NEAR(double(structure->GetNumberOfPoints()), 300.0, 45.0) << name;
  return structure;
}

/// The atoms of `atoms` named `name` (AtomName), with their point and field data.
vtkSmartPointer<vtkPolyData> atoms_named(vtkPolyData* atoms, const std::string& name)
{
  auto* names = vtkStringArray::SafeDownCast(
    atoms->GetPointData()->GetAbstractArray(vtkMesoArrayNames::AtomName));
  vtkNew<vtkIdList> kept;
  for (vtkIdType a = 0; a < atoms->GetNumberOfPoints(); ++a)
  {
    if (names->GetValue(a) == name)
    {
      kept->InsertNextId(a);
    }
  }
  auto selected = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  atoms->GetPoints()->GetPoints(kept, points);
  selected->SetPoints(points);
  selected->GetPointData()->CopyAllocate(atoms->GetPointData(), kept->GetNumberOfIds());
  for (vtkIdType k = 0; k < kept->GetNumberOfIds(); ++k)
  {
    selected->GetPointData()->CopyData(atoms->GetPointData(), kept->GetId(k), k);
  }
  selected->GetFieldData()->ShallowCopy(atoms->GetFieldData());
  return selected;
}

/// The mean of the values below and of those above their median.
std::pair<double, double> two_layers(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  const std::size_t half = values.size() / 2;
  double low = 0, high = 0;
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    (i < half ? low : high) += values[i];
  }
  return { low / double(half), high / double(values.size() - half) };
}
} // namespace

TEST(vtkMesoStructuredCutaway, FlatMembranesGiveOneOpenSheetThroughTheirMiddleAcrossTheBox)
{
  // All-atom DPPC with 3840 waters, Martini DPPC/CHOL, CHARMM POPE/POPG around the YiiP
  // protein in a hexagonal box: each an open sheet spanning its periodic box, between the
  // leaflets' phosphate layers (P or PO4 along z), not a closed blob in the bilayer.
  for (const auto& [file, head] :
       { std::pair<const char*, const char*>{ "membranes/dppc128_slipids_323K.gro", "P" },
         { "membranes/martini_dppc_chol_bilayer.gro", "PO4" },
         { "membranes/yiip_popepopg.gro", "P" } })
  {
    vtkNew<vtkMesoTrajectoryReader> reader;
    reader->SetTopologyFileName(mesolens_test::data_file(file).c_str());
    reader->Update();
    const vtkSmartPointer<vtkPolyData> structure = made_structure(reader->GetOutput(), 1, file);
    ASSERT_GT(structure->GetNumberOfCells(), 0) << file;
    const vtkSmartPointer<vtkPolyData> heads = atoms_named(reader->GetOutput(), head);
    std::vector<double> heights;
    for (vtkIdType a = 0; a < heads->GetNumberOfPoints(); ++a)
    {
      heights.push_back(heads->GetPoint(a)[2]);
    }
    const auto [lower, upper] = two_layers(heights);
    const double middle = 0.5 * (lower + upper);
    double off = 0;
    for (vtkIdType v = 0; v < structure->GetNumberOfPoints(); ++v)
    {
      const double z = structure->GetPoint(v)[2];
      EXPECT_LT(std::abs(z - middle), 0.25 * (upper - lower)) << file;
      off += std::abs(z - middle) / double(structure->GetNumberOfPoints());
    }
    EXPECT_LT(off, 3.0) << file;
    // Across the box: its extent along b's y is the box's.
    double bounds[6];
    structure->GetBounds(bounds);
    vtkDataArray* box =
      reader->GetOutput()->GetFieldData()->GetArray(vtkMesoArrayNames::PeriodicBoxVectors);
    EXPECT_NEAR(bounds[3] - bounds[2], box->GetComponent(0, 4), 1e-3) << file;
    EXPECT_GT(bounds[1] - bounds[0], 0.95 * box->GetComponent(0, 0)) << file;
  }
}

TEST(vtkMesoStructuredCutaway, AVesicleGivesOneClosedSheetBetweenItsLeafletsFromLipidsOrHeadGroups)
{
  vtkNew<vtkMesoTrajectoryReader> reader;
  reader->SetTopologyFileName(
    mesolens_test::data_file("membranes/martini_dppc_vesicle.gro").c_str());
  reader->Update();
  // The PO4 beads gathered whole (by the filter), to measure against: the vesicle is not quite
  // round (its PO4 beads lie 49 to 163 Å from their mean), so the sheet is checked to keep
  // about half the leaflets' PO4-PO4 distance (about 40 Å) from the nearest bead everywhere.
  vtkNew<vtkMesoStructuredCutaway> gather;
  gather->SetInputConnection(reader->GetOutputPort());
  gather->SetStructureVertices(300);
  gather->Update();
  const vtkSmartPointer<vtkPolyData> heads = atoms_named(gather->GetOutput(), "PO4");
  // From every lipid's centre, and from the PO4 beads alone (one per lipid, as read: the
  // filter gathers them).
  const vtkSmartPointer<vtkPolyData> read_heads = atoms_named(reader->GetOutput(), "PO4");
  for (const auto& [input, name] :
       { std::pair<vtkPolyData*, const char*>{ reader->GetOutput(), "lipids" },
         { read_heads.Get(), "PO4 only" } })
  {
    const vtkSmartPointer<vtkPolyData> structure = made_structure(input, 0, name);
    ASSERT_GT(structure->GetNumberOfCells(), 0) << name;
    const vtkIdType faces = structure->GetNumberOfCells();
    EXPECT_EQ(structure->GetNumberOfPoints() - 3 * faces / 2 + faces, 2) << name; // a sphere
    double sum = 0;
    for (vtkIdType v = 0; v < structure->GetNumberOfPoints(); ++v)
    {
      const double* p = structure->GetPoint(v);
      double nearest = 1e9;
      for (vtkIdType a = 0; a < heads->GetNumberOfPoints(); ++a)
      {
        const double* q = heads->GetPoint(a);
        nearest = std::min(nearest, std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]));
      }
      EXPECT_GT(nearest, 12.0) << name; // not on a leaflet
      EXPECT_LT(nearest, 30.0) << name; // not off the bilayer
      sum += nearest;
    }
    EXPECT_NEAR(sum / double(structure->GetNumberOfPoints()), 19.0, 3.0) << name;
  }
}
