// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoRibbonLevelOfDetail.h"

#include "MesoAtomScenes.h"
#include "vtkMesoRibbons.h"
#include "vtkMesoSecondaryStructure.h"

#include <vtkIntArray.h>
#include <vtkPolyDataMapper.h>

#include <gtest/gtest.h>

namespace {
struct Scene
{
  vtkNew<vtkMesoStructureReader> Reader;
  vtkNew<vtkMesoSecondaryStructure> Assignment;
  vtkNew<vtkMesoRibbons> Ribbons;
  vtkNew<vtkPolyDataMapper> Mapper;
  vtkNew<vtkActor> Actor;
  vtkNew<vtkRenderer> Renderer;
  vtkSmartPointer<vtkRenderWindow> Window = mesolens_test::test_window(300, 300);

  Scene()
  {
    this->Reader->SetFileName((std::string(MESOLENS_DATA_DIR) + "/proteins/1tii.pdb").c_str());
    this->Assignment->SetInputConnection(this->Reader->GetOutputPort());
    this->Ribbons->SetInputConnection(this->Assignment->GetOutputPort());
    this->Ribbons->SetSubdivisions(8);
    this->Mapper->SetInputConnection(this->Ribbons->GetOutputPort());
    this->Actor->SetMapper(this->Mapper);
    this->Renderer->AddActor(this->Actor);
    this->Window->AddRenderer(this->Renderer);
    this->Ribbons->Update();
    this->Renderer->ResetCamera();
  }
};
} // namespace

TEST(vtkMesoRibbonLevelOfDetail, SamplesFollowTheSizeOnScreen)
{
  Scene scene;
  vtkNew<vtkMesoRibbonLevelOfDetail> detail;
  detail->SetRibbons(scene.Ribbons);
  detail->SetRenderer(scene.Renderer);
  detail->SetPixelsPerSample(4);
  const long long near = detail->Update();
  ASSERT_NE(scene.Ribbons->GetSegmentSubdivisions(), nullptr);
  scene.Ribbons->Update();
  const vtkIdType near_triangles = scene.Ribbons->GetOutput()->GetNumberOfPolys();
  // Far away: fewer samples and triangles.
  scene.Renderer->GetActiveCamera()->Dolly(0.1);
  const long long far = detail->Update();
  scene.Ribbons->Update();
  EXPECT_LT(far, near / 2);
  EXPECT_LT(scene.Ribbons->GetOutput()->GetNumberOfPolys(), near_triangles);
  // Out of view: one sample per residue.
  scene.Renderer->GetActiveCamera()->Azimuth(180);
  scene.Renderer->GetActiveCamera()->SetFocalPoint(1000, 1000, 1000);
  detail->Update();
  vtkIntArray* counts = scene.Ribbons->GetSegmentSubdivisions();
  for (vtkIdType s = 0; s < counts->GetNumberOfValues(); ++s)
    EXPECT_EQ(counts->GetValue(s), 1);
  // Full quality for a still image: every piece at the ribbons' Subdivisions.
  detail->FullQualityOn();
  detail->Update();
  counts = scene.Ribbons->GetSegmentSubdivisions();
  for (vtkIdType s = 0; s < counts->GetNumberOfValues(); ++s)
    EXPECT_EQ(counts->GetValue(s), 8);
}

TEST(vtkMesoRibbonLevelOfDetail, FrameTimeBudgetCoarsensSlowFramesAndRecovers)
{
  vtkNew<vtkMesoRibbonLevelOfDetail> detail;
  detail->SetPixelsPerSample(2);
  detail->SetFrameTimeBudget(0.05);
  detail->ReportFrameTime(0.2);
  detail->ReportFrameTime(0.2);
  EXPECT_NEAR(detail->GetAdaptedPixelsPerSample(), 4.5, 1e-9);
  detail->ReportFrameTime(0.04); // within budget, not fast: unchanged
  EXPECT_NEAR(detail->GetAdaptedPixelsPerSample(), 4.5, 1e-9);
  for (int frame = 0; frame < 5; ++frame)
    detail->ReportFrameTime(0.001);
  EXPECT_NEAR(detail->GetAdaptedPixelsPerSample(), 2.0, 1e-9);
  // Watching a renderer: every render sets the counts first.
  Scene scene;
  detail->SetRibbons(scene.Ribbons);
  detail->SetRenderer(scene.Renderer);
  detail->Watch();
  scene.Ribbons->SetSegmentSubdivisions(nullptr);
  scene.Window->Render();
  EXPECT_NE(scene.Ribbons->GetSegmentSubdivisions(), nullptr);
  detail->Unwatch();
  // Without ribbons or a renderer nothing happens.
  vtkNew<vtkMesoRibbonLevelOfDetail> idle;
  EXPECT_EQ(idle->Update(), 0);
}
