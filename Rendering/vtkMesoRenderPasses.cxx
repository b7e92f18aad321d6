// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoRenderPasses.h"

#include <vtkCameraPass.h>
#include <vtkLight.h>
#include <vtkObjectFactory.h>
#include <vtkRenderPass.h>
#include <vtkRenderPassCollection.h>
#include <vtkRenderStepsPass.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSSAOPass.h>
#include <vtkSequencePass.h>
#include <vtkShadowMapBakerPass.h>
#include <vtkShadowMapPass.h>

vtkStandardNewMacro(vtkMesoRenderPasses);

namespace {
// The sun's set-up: bright enough to cast visible shadows, with the headlight dimmed so that
// the sum stays near one light's brightness; a narrow cone keeps its shadow map's texels small.
constexpr double HeadlightIntensity = 0.5;
constexpr double SunIntensity = 0.7;
constexpr double SunConeAngle = 45.0;
} // namespace

vtkMesoRenderPasses::vtkMesoRenderPasses()
{
  this->Headlight->SetLightTypeToHeadlight();
  this->Headlight->SetIntensity(HeadlightIntensity);
  this->Sun->SetLightTypeToSceneLight();
  this->Sun->PositionalOn();
  this->Sun->SetConeAngle(SunConeAngle);
  this->Sun->SetIntensity(SunIntensity);
}

vtkMesoRenderPasses::~vtkMesoRenderPasses() = default;

vtkRenderPass* vtkMesoRenderPasses::GetPass()
{
  return this->Chain;
}

vtkSmartPointer<vtkRenderPass> vtkMesoRenderPasses::BuildChain()
{
  // Each link holds the next, so the outermost pass keeps the whole chain alive.
  vtkSmartPointer<vtkRenderPass> scene;
  if (this->Shadows)
  {
    // Bake the shadow maps first, then draw the geometry that reads them; the camera pass sets
    // the view up for both.
    vtkNew<vtkShadowMapPass> shadows;
    shadows->GetShadowMapBakerPass()->SetResolution(
      static_cast<unsigned int>(this->ShadowMapResolution));
    vtkNew<vtkRenderPassCollection> stages;
    stages->AddItem(shadows->GetShadowMapBakerPass());
    stages->AddItem(shadows);
    vtkNew<vtkSequencePass> sequence;
    sequence->SetPasses(stages);
    auto camera = vtkSmartPointer<vtkCameraPass>::New();
    camera->SetDelegatePass(sequence);
    scene = camera;
  }
  else
  {
    scene = vtkSmartPointer<vtkRenderStepsPass>::New();
  }
  if (!this->SSAO)
  {
    return this->Shadows ? scene : nullptr;
  }
  auto occlusion = vtkSmartPointer<vtkSSAOPass>::New();
  occlusion->SetDelegatePass(scene);
  occlusion->SetRadius(this->SSAORadius);
  occlusion->SetBias(this->SSAOBias);
  occlusion->SetKernelSize(static_cast<unsigned int>(this->SSAOKernelSize));
  occlusion->SetBlur(this->SSAOBlur);
  return occlusion;
}

void vtkMesoRenderPasses::Apply(vtkRenderer* renderer)
{
  if (!renderer)
  {
    return;
  }
  vtkWindow* window = renderer->GetRenderWindow();
  const bool current = this->ChainTime > this->GetMTime() && renderer == this->ChainRenderer &&
    window == this->ChainWindow && renderer->GetPass() == this->Chain;
  if (!current)
  {
    // New passes rather than old ones rewired: VTK 9.1's shadow map pass crashes when drawn
    // again after releasing its resources. The replaced chain frees its resources now, in the
    // window they were made in, as VTK would only do for the pass installed at that time.
    if (this->Chain && renderer->GetPass() == this->Chain && window)
    {
      this->Chain->ReleaseGraphicsResources(window);
    }
    this->Chain = this->BuildChain();
    this->ChainTime.Modified();
    this->ChainRenderer = renderer;
    this->ChainWindow = window;
  }
  if (this->SunLight)
  {
    this->SetLights(renderer);
  }
  renderer->SetPass(this->Chain);
  renderer->SetUseDepthPeeling(this->DepthPeeling);
  if (this->DepthPeeling)
  {
    renderer->SetMaximumNumberOfPeels(this->MaximumNumberOfPeels);
    renderer->SetOcclusionRatio(0.0);
  }
}

void vtkMesoRenderPasses::SetLights(vtkRenderer* renderer)
{
  // Removing every light, the automatic headlight VTK added at the first render included,
  // leaves VTK to add it again when nothing else lights the scene.
  renderer->RemoveAllLights();
  if (!this->Shadows)
  {
    return;
  }
  this->Sun->SetPosition(this->SunPosition);
  this->Sun->SetFocalPoint(this->SunFocalPoint);
  renderer->AddLight(this->Headlight);
  renderer->AddLight(this->Sun);
}

void vtkMesoRenderPasses::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SSAO: " << (this->SSAO ? "On" : "Off") << "\n";
  os << indent << "SSAORadius: " << this->SSAORadius << "\n";
  os << indent << "SSAOBias: " << this->SSAOBias << "\n";
  os << indent << "SSAOKernelSize: " << this->SSAOKernelSize << "\n";
  os << indent << "SSAOBlur: " << (this->SSAOBlur ? "On" : "Off") << "\n";
  os << indent << "Shadows: " << (this->Shadows ? "On" : "Off") << "\n";
  os << indent << "ShadowMapResolution: " << this->ShadowMapResolution << "\n";
  os << indent << "SunLight: " << (this->SunLight ? "On" : "Off") << "\n";
  os << indent << "SunPosition: (" << this->SunPosition[0] << ", " << this->SunPosition[1] << ", "
     << this->SunPosition[2] << ")\n";
  os << indent << "SunFocalPoint: (" << this->SunFocalPoint[0] << ", " << this->SunFocalPoint[1]
     << ", " << this->SunFocalPoint[2] << ")\n";
  os << indent << "DepthPeeling: " << (this->DepthPeeling ? "On" : "Off") << "\n";
  os << indent << "MaximumNumberOfPeels: " << this->MaximumNumberOfPeels << "\n";
  os << indent << "Pass: " << (this->Chain ? this->Chain->GetClassName() : "(none)") << "\n";
}
