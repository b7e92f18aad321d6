// SPDX-License-Identifier: GPL-3.0-or-later
// vtkMesoRenderPasses: defaults, ranges, the chain Apply() installs for each combination, the
// renderer's depth peeling and lights, and pictures that change with each effect and return
// exactly when the effects are off again.
#include "vtkMesoRenderPasses.h"

#include "MesoAtomScenes.h"

#include <vtkCameraPass.h>
#include <vtkLight.h>
#include <vtkLightCollection.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkPointData.h>
#include <vtkRenderPassCollection.h>
#include <vtkRenderStepsPass.h>
#include <vtkSSAOPass.h>
#include <vtkSequencePass.h>
#include <vtkShadowMapBakerPass.h>
#include <vtkShadowMapPass.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowToImageFilter.h>

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace {
/// The class names of a chain from the renderer's pass inwards, through delegates and the
/// passes of sequences ("vtkSequencePass[vtkShadowMapBakerPass vtkShadowMapPass]").
std::string chain_of(vtkRenderPass* pass)
{
  if (!pass)
  {
    return "none";
  }
  std::string chain = pass->GetClassName();
  if (auto* occlusion = vtkSSAOPass::SafeDownCast(pass))
  {
    return chain + " > " + chain_of(occlusion->GetDelegatePass());
  }
  if (auto* camera = vtkCameraPass::SafeDownCast(pass))
  {
    return chain + " > " + chain_of(camera->GetDelegatePass());
  }
  if (auto* sequence = vtkSequencePass::SafeDownCast(pass))
  {
    chain += "[";
    vtkRenderPassCollection* passes = sequence->GetPasses();
    for (int i = 0; i < passes->GetNumberOfItems(); ++i)
    {
      chain += (i ? " " : "") + chain_of(vtkRenderPass::SafeDownCast(passes->GetItemAsObject(i)));
    }
    return chain + "]";
  }
  return chain;
}

std::vector<vtkLight*> lights_of(vtkRenderer* renderer)
{
  std::vector<vtkLight*> lights;
  vtkLightCollection* collection = renderer->GetLights();
  vtkCollectionSimpleIterator it;
  collection->InitTraversal(it);
  while (vtkLight* light = collection->GetNextLight(it))
  {
    lights.push_back(light);
  }
  return lights;
}

const std::string shadow_chain =
  "vtkCameraPass > vtkSequencePass[vtkShadowMapBakerPass vtkShadowMapPass]";

/// Crambin in balls and sticks in a small window, lit by a scene light from above-right that
/// casts shadows (positional, cone under 90 degrees).
struct Scene
{
  vtkSmartPointer<vtkMesoStructureReader> Reader = mesolens_test::crambin();
  vtkSmartPointer<vtkRenderWindow> Window = mesolens_test::test_window(120, 120);
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkMesoAtomMapper> Mapper;
  vtkNew<vtkActor> Actor;

  Scene()
  {
    this->Mapper->SetInputConnection(this->Reader->GetOutputPort());
    this->Mapper->SetStyleToBallAndStick();
    this->Actor->SetMapper(this->Mapper);
    this->Renderer->AddActor(this->Actor);
    this->Window->AddRenderer(this->Renderer);
    mesolens_test::look_at(this->Renderer, this->Reader->GetOutput(), 55.0);
  }

  std::vector<unsigned char> Picture()
  {
    this->Window->Render();
    vtkNew<vtkWindowToImageFilter> capture;
    capture->SetInput(this->Window);
    capture->Update();
    auto* pixels =
      vtkUnsignedCharArray::SafeDownCast(capture->GetOutput()->GetPointData()->GetScalars());
    return { pixels->GetPointer(0), pixels->GetPointer(0) + pixels->GetNumberOfValues() };
  }
};

/// Collects what VTK would print (errors and warnings of objects nobody observes).
class OutputCollector : public vtkOutputWindow
{
public:
  static OutputCollector* New();
  vtkTypeMacro(OutputCollector, vtkOutputWindow);
  void DisplayText(const char* text) override
  {
    this->Text += text;
  }
  std::string Text;
};
vtkStandardNewMacro(OutputCollector);

long long brightness(const std::vector<unsigned char>& picture)
{
  long long sum = 0;
  for (unsigned char value : picture)
  {
    sum += value;
  }
  return sum;
}
} // namespace

TEST(MesoRenderPasses, DefaultsAreVTKsAndNothingIsOn)
{
  vtkNew<vtkMesoRenderPasses> passes;
  EXPECT_FALSE(passes->GetSSAO());
  EXPECT_EQ(passes->GetSSAORadius(), 0.5);
  EXPECT_EQ(passes->GetSSAOBias(), 0.01);
  EXPECT_EQ(passes->GetSSAOKernelSize(), 32);
  EXPECT_FALSE(passes->GetSSAOBlur());
  EXPECT_FALSE(passes->GetShadows());
  EXPECT_FALSE(passes->GetSunLight());
  EXPECT_FALSE(passes->GetDepthPeeling());
  EXPECT_EQ(passes->GetMaximumNumberOfPeels(), 4);
  EXPECT_EQ(passes->GetPass(), nullptr);
  // The defaults of the passes and renderer this class sets.
  vtkNew<vtkSSAOPass> occlusion;
  EXPECT_EQ(passes->GetSSAORadius(), occlusion->GetRadius());
  EXPECT_EQ(passes->GetSSAOBias(), occlusion->GetBias());
  EXPECT_EQ(passes->GetSSAOKernelSize(), static_cast<int>(occlusion->GetKernelSize()));
  EXPECT_EQ(passes->GetSSAOBlur(), occlusion->GetBlur());
  vtkNew<vtkShadowMapBakerPass> baker;
  EXPECT_EQ(passes->GetShadowMapResolution(), static_cast<int>(baker->GetResolution()));
  vtkNew<vtkRenderer> renderer;
  EXPECT_EQ(passes->GetMaximumNumberOfPeels(), renderer->GetMaximumNumberOfPeels());
}

TEST(MesoRenderPasses, ParametersStayInRange)
{
  vtkNew<vtkMesoRenderPasses> passes;
  passes->SetSSAORadius(-1.0);
  EXPECT_EQ(passes->GetSSAORadius(), 0.0);
  passes->SetSSAOBias(-1.0);
  EXPECT_EQ(passes->GetSSAOBias(), 0.0);
  passes->SetSSAOKernelSize(0);
  EXPECT_EQ(passes->GetSSAOKernelSize(), 1);
  passes->SetSSAOKernelSize(5000);
  EXPECT_EQ(passes->GetSSAOKernelSize(), 1000);
  passes->SetShadowMapResolution(1);
  EXPECT_EQ(passes->GetShadowMapResolution(), 16);
  passes->SetShadowMapResolution(1 << 20);
  EXPECT_EQ(passes->GetShadowMapResolution(), 16384);
  passes->SetMaximumNumberOfPeels(0);
  EXPECT_EQ(passes->GetMaximumNumberOfPeels(), 1);
  passes->SetMaximumNumberOfPeels(1000);
  EXPECT_EQ(passes->GetMaximumNumberOfPeels(), 100);
}

TEST(MesoRenderPasses, ApplyInstallsTheChainOfEachCombination)
{
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkMesoRenderPasses> passes;
  passes->SSAOOn();
  passes->Apply(renderer);
  EXPECT_EQ(chain_of(renderer->GetPass()), "vtkSSAOPass > vtkRenderStepsPass");

  passes->ShadowsOn();
  passes->Apply(renderer);
  EXPECT_EQ(chain_of(renderer->GetPass()), "vtkSSAOPass > " + shadow_chain);

  passes->SSAOOff();
  passes->Apply(renderer);
  EXPECT_EQ(chain_of(renderer->GetPass()), shadow_chain);
  // The baker in the sequence is the one whose maps the shadow pass reads.
  auto* sequence = vtkSequencePass::SafeDownCast(
    vtkCameraPass::SafeDownCast(renderer->GetPass())->GetDelegatePass());
  auto* baker = sequence->GetPasses()->GetItemAsObject(0);
  auto* shadow = vtkShadowMapPass::SafeDownCast(sequence->GetPasses()->GetItemAsObject(1));
  EXPECT_EQ(baker, shadow->GetShadowMapBakerPass());

  passes->ShadowsOff();
  passes->Apply(renderer);
  EXPECT_EQ(renderer->GetPass(), nullptr);
}

TEST(MesoRenderPasses, ApplyKeepsTheChainUntilSomethingChanges)
{
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkMesoRenderPasses> passes;
  passes->SSAOOn();
  passes->Apply(renderer);
  vtkRenderPass* first = renderer->GetPass();
  EXPECT_EQ(passes->GetPass(), first);
  passes->SetSSAO(true); // unchanged
  passes->Apply(renderer);
  EXPECT_EQ(renderer->GetPass(), first);
  passes->SetSSAORadius(2.0);
  passes->Apply(renderer);
  EXPECT_NE(renderer->GetPass(), first);
  EXPECT_EQ(vtkSSAOPass::SafeDownCast(renderer->GetPass())->GetRadius(), 2.0);
  // Another renderer gets its own chain.
  vtkNew<vtkRenderer> other;
  passes->Apply(other);
  EXPECT_NE(other->GetPass(), renderer->GetPass());
}

TEST(MesoRenderPasses, ApplyPassesTheParametersOn)
{
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkMesoRenderPasses> passes;
  passes->SSAOOn();
  passes->ShadowsOn();
  passes->SetSSAORadius(3.0);
  passes->SetSSAOBias(0.05);
  passes->SetSSAOKernelSize(64);
  passes->SSAOBlurOn();
  passes->SetShadowMapResolution(2048);
  passes->Apply(renderer);
  auto* occlusion = vtkSSAOPass::SafeDownCast(renderer->GetPass());
  ASSERT_NE(occlusion, nullptr);
  EXPECT_EQ(occlusion->GetRadius(), 3.0);
  EXPECT_EQ(occlusion->GetBias(), 0.05);
  EXPECT_EQ(occlusion->GetKernelSize(), 64u);
  EXPECT_TRUE(occlusion->GetBlur());
  auto* sequence = vtkSequencePass::SafeDownCast(
    vtkCameraPass::SafeDownCast(occlusion->GetDelegatePass())->GetDelegatePass());
  auto* shadow = vtkShadowMapPass::SafeDownCast(sequence->GetPasses()->GetItemAsObject(1));
  EXPECT_EQ(shadow->GetShadowMapBakerPass()->GetResolution(), 2048u);
}

TEST(MesoRenderPasses, TheRendererKeepsTheChainAfterThePassesObjectIsGone)
{
  vtkNew<vtkRenderer> renderer;
  vtkRenderPass* top = nullptr;
  {
    vtkNew<vtkMesoRenderPasses> passes;
    passes->SSAOOn();
    passes->ShadowsOn();
    passes->Apply(renderer);
    top = renderer->GetPass();
  }
  // The renderer holds the chain; every link is still there.
  EXPECT_EQ(renderer->GetPass(), top);
  EXPECT_EQ(chain_of(renderer->GetPass()), "vtkSSAOPass > " + shadow_chain);
}

TEST(MesoRenderPasses, DepthPeelingIsTheRenderersAndExact)
{
  vtkNew<vtkRenderer> renderer;
  renderer->SetOcclusionRatio(0.1);
  vtkNew<vtkMesoRenderPasses> passes;
  passes->DepthPeelingOn();
  passes->SetMaximumNumberOfPeels(16);
  passes->Apply(renderer);
  EXPECT_TRUE(renderer->GetUseDepthPeeling());
  EXPECT_EQ(renderer->GetMaximumNumberOfPeels(), 16);
  EXPECT_EQ(renderer->GetOcclusionRatio(), 0.0);
  EXPECT_EQ(renderer->GetPass(), nullptr);
  passes->DepthPeelingOff();
  passes->Apply(renderer);
  EXPECT_FALSE(renderer->GetUseDepthPeeling());
}

TEST(MesoRenderPasses, SunLightReplacesTheLightsOnlyWhenAsked)
{
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkLight> own;
  renderer->AddLight(own);
  vtkNew<vtkMesoRenderPasses> passes;
  passes->ShadowsOn();
  passes->Apply(renderer);
  ASSERT_EQ(lights_of(renderer).size(), 1u);
  EXPECT_EQ(lights_of(renderer)[0], own.GetPointer());

  passes->SunLightOn();
  passes->SetSunPosition(1, 2, 3);
  passes->SetSunFocalPoint(4, 5, 6);
  passes->Apply(renderer);
  std::vector<vtkLight*> lights = lights_of(renderer);
  ASSERT_EQ(lights.size(), 2u);
  EXPECT_TRUE(lights[0]->LightTypeIsHeadlight());
  EXPECT_EQ(lights[0]->GetIntensity(), 0.5);
  EXPECT_TRUE(lights[1]->LightTypeIsSceneLight());
  EXPECT_TRUE(lights[1]->GetPositional());
  EXPECT_EQ(lights[1]->GetConeAngle(), 45.0);
  EXPECT_EQ(lights[1]->GetIntensity(), 0.7);
  EXPECT_EQ(lights[1]->GetPosition()[0], 1.0);
  EXPECT_EQ(lights[1]->GetPosition()[2], 3.0);
  EXPECT_EQ(lights[1]->GetFocalPoint()[1], 5.0);
  // Applied twice: still the same two lights.
  passes->Apply(renderer);
  EXPECT_EQ(lights_of(renderer).size(), 2u);

  // Without shadows VTK's automatic headlight comes back.
  passes->ShadowsOff();
  passes->Apply(renderer);
  EXPECT_TRUE(lights_of(renderer).empty());
}

TEST(MesoRenderPasses, EachEffectChangesThePictureAndOffRestoresItExactly)
{
  Scene scene;
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPosition(30, 40, 80);
  light->SetFocalPoint(10, 12, 8);
  light->PositionalOn();
  light->SetConeAngle(60);
  scene.Renderer->AddLight(light);
  const std::vector<unsigned char> plain = scene.Picture();

  vtkNew<vtkMesoRenderPasses> passes;
  passes->SSAOOn();
  passes->SetSSAORadius(3.0);
  passes->SetSSAOBias(0.05);
  passes->Apply(scene.Renderer);
  const std::vector<unsigned char> occluded = scene.Picture();
  EXPECT_LT(brightness(occluded), brightness(plain)); // the crevices darken

  passes->SSAOOff();
  passes->ShadowsOn();
  passes->Apply(scene.Renderer);
  const std::vector<unsigned char> shadowed = scene.Picture();
  EXPECT_LT(brightness(shadowed), brightness(plain)); // atoms shade the atoms behind them

  passes->SSAOOn();
  passes->Apply(scene.Renderer);
  EXPECT_LT(brightness(scene.Picture()), brightness(shadowed));

  passes->SSAOOff();
  passes->ShadowsOff();
  passes->Apply(scene.Renderer);
  EXPECT_EQ(scene.Picture(), plain);
}

TEST(MesoRenderPasses, ReplacedPassesFreeTheirBuffersInTheirWindow)
{
  vtkNew<OutputCollector> output;
  vtkOutputWindow* previous = vtkOutputWindow::GetInstance();
  previous->Register(nullptr);
  vtkOutputWindow::SetInstance(output);
  {
    Scene scene;
    vtkNew<vtkMesoRenderPasses> passes;
    passes->SunLightOn();
    passes->SetSunPosition(30, 40, 80);
    passes->SetSunFocalPoint(10, 12, 8);
    for (int effects : { 3, 2, 1, 3, 0 }) // SSAO and shadows, shadows, SSAO, both, none
    {
      passes->SetSSAO(effects & 1);
      passes->SetShadows(effects & 2);
      passes->Apply(scene.Renderer);
      scene.Picture();
    }
  }
  vtkOutputWindow::SetInstance(previous);
  previous->UnRegister(nullptr);
  // VTK's passes complain when they are deleted holding buffers.
  EXPECT_EQ(output->Text.find("should have been deleted"), std::string::npos) << output->Text;
}
