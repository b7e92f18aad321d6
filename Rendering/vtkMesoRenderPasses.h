// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * @class   vtkMesoRenderPasses
 * @brief   Builds and installs the render-pass chain of a renderer for ambient occlusion
 *          (SSAO), shadow maps and depth-peeled translucency, composed so that they work
 *          together with vtkMesoAtomMapper's impostors.
 *
 * Set what is wanted, then Apply() it to a renderer; Apply() again after a change. The object
 * makes and owns the passes and lights (callers keep none of their own), frees the graphics
 * resources of a chain it replaces, and serves one renderer at a time.
 *
 * The chain Apply() installs (outermost first):
 * - SSAO only: vtkSSAOPass over vtkRenderStepsPass (VTK's usual steps: lights, opaque,
 *   translucent, volumes, overlay).
 * - Shadows only: vtkCameraPass over a vtkSequencePass of the vtkShadowMapPass' baker
 *   (vtkShadowMapBakerPass: one depth map per shadow-casting light) and then the
 *   vtkShadowMapPass itself (lights and opaque geometry, shadowed by those maps). The maps must
 *   be baked before the geometry that reads them is drawn, hence this order, and both need the
 *   camera pass to set up the view first.
 * - SSAO and shadows: vtkSSAOPass over the shadow chain. SSAO is outermost because it darkens
 *   the finished, lit and shadowed picture with the depths and normals written while drawing
 *   it; the shadow map baker draws into its own maps, not into the depths and normals SSAO
 *   reads.
 * - Neither: no pass; the renderer draws as usual.
 *
 * vtkMesoAtomMapper writes exact per-pixel depths and view-space normals from its ray-cast
 * spheres and cylinders, so both passes see the impostors as true spheres and cylinders (see
 * vtkMesoAtomMapper.h).
 *
 * Limits of VTK 9.1's passes that this class keeps, rather than hides:
 * - VTK 9.1's vtkSSAOPass draws black in a renderer whose viewport does not start at the
 *   window's origin: use SSAO in a renderer at the lower left or one that fills the window.
 * - vtkShadowMapPass draws lights and opaque geometry only: with Shadows on, translucent props,
 *   volumes and 2D overlays of this renderer are not drawn (put overlays in another renderer).
 * - Depth peeling (DepthPeeling) is the renderer's own translucent step, so it applies when
 *   neither SSAO nor Shadows is on; with SSAO translucent geometry is blended in drawing order
 *   (VTK 9.1's vtkDualDepthPeelingPass inside vtkSSAOPass' framebuffer leaves noise where the
 *   translucent layers were).
 *
 * Lights: shadows are cast by the renderer's lights that are not headlights and are
 * directional, or positional with a cone angle under 90 degrees
 * (vtkShadowMapBakerPass::LightCreatesShadow). By default Apply() leaves the renderer's lights
 * alone and the caller adds such a light. With SunLight on, Apply() lights the scene itself:
 * with Shadows a headlight of intensity 0.5 and a sun (a positional scene light at SunPosition
 * aimed at SunFocalPoint, cone angle 45 degrees, intensity 0.7) replace the renderer's lights;
 * without Shadows the renderer's lights are removed, so that VTK's automatic headlight returns.
 */
#ifndef vtkMesoRenderPasses_h
#define vtkMesoRenderPasses_h

#include "MesoLensRenderingModule.h"
#include "vtkNew.h"
#include "vtkObject.h"
#include "vtkSmartPointer.h"
#include "vtkTimeStamp.h"
#include "vtkWeakPointer.h"

class vtkLight;
class vtkRenderPass;
class vtkRenderer;
class vtkWindow;

class MESOLENSRENDERING_EXPORT vtkMesoRenderPasses : public vtkObject
{
public:
  static vtkMesoRenderPasses* New();
  vtkTypeMacro(vtkMesoRenderPasses, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Screen-space ambient occlusion (vtkSSAOPass) over the rest of the chain. Default off.
  vtkSetMacro(SSAO, bool);
  vtkGetMacro(SSAO, bool);
  vtkBooleanMacro(SSAO, bool);
  ///@}

  ///@{
  /// Radius of the hemisphere around each pixel in which SSAO looks for occluders, in world
  /// units (the scene's length unit), >= 0. Default 0.5 (vtkSSAOPass' default); about 3 Å for
  /// atoms, or a twentieth of a mapped patch's extent.
  vtkSetClampMacro(SSAORadius, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(SSAORadius, double);
  ///@}

  ///@{
  /// Depth by which an occluder must lie in front of a sample to count, in world units, >= 0;
  /// keeps curved surfaces from shadowing themselves. Default 0.01 (vtkSSAOPass' default).
  vtkSetClampMacro(SSAOBias, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(SSAOBias, double);
  ///@}

  ///@{
  /// Samples per pixel in the SSAO hemisphere, [1, 1000]. Default 32 (vtkSSAOPass' default).
  vtkSetClampMacro(SSAOKernelSize, int, 1, 1000);
  vtkGetMacro(SSAOKernelSize, int);
  ///@}

  ///@{
  /// Smooth the occlusion over 3 x 3 pixels before darkening the picture (hides the pattern of
  /// the per-pixel sample rotations). Default off (vtkSSAOPass' default).
  vtkSetMacro(SSAOBlur, bool);
  vtkGetMacro(SSAOBlur, bool);
  vtkBooleanMacro(SSAOBlur, bool);
  ///@}

  ///@{
  /// Shadows cast by the renderer's shadow-casting lights (vtkShadowMapPass). Default off.
  vtkSetMacro(Shadows, bool);
  vtkGetMacro(Shadows, bool);
  vtkBooleanMacro(Shadows, bool);
  ///@}

  ///@{
  /// Width and height of each light's square shadow map, pixels, [16, 16384]. Default 1024
  /// (vtkShadowMapBakerPass' default in VTK 9.1); more gives sharper shadows of small atoms.
  vtkSetClampMacro(ShadowMapResolution, int, 16, 16384);
  vtkGetMacro(ShadowMapResolution, int);
  ///@}

  ///@{
  /// Apply() sets the renderer's lights: with Shadows a headlight (intensity 0.5) and a sun at
  /// SunPosition (intensity 0.7, cone angle 45 degrees), without Shadows none (VTK's automatic
  /// headlight). Default off: Apply() leaves the renderer's lights as they are.
  vtkSetMacro(SunLight, bool);
  vtkGetMacro(SunLight, bool);
  vtkBooleanMacro(SunLight, bool);
  ///@}

  ///@{
  /// Where the sun is and where it points, world coordinates (SunLight only). Defaults
  /// (0, 0, 1) and (0, 0, 0), vtkLight's.
  vtkSetVector3Macro(SunPosition, double);
  vtkGetVector3Macro(SunPosition, double);
  vtkSetVector3Macro(SunFocalPoint, double);
  vtkGetVector3Macro(SunFocalPoint, double);
  ///@}

  ///@{
  /// Translucent geometry composited exactly by the renderer's depth peeling (with no
  /// occlusion-ratio shortcut) when neither SSAO nor Shadows is on; off, Apply() turns the
  /// renderer's depth peeling off. Default off (alpha blending in drawing order).
  vtkSetMacro(DepthPeeling, bool);
  vtkGetMacro(DepthPeeling, bool);
  vtkBooleanMacro(DepthPeeling, bool);
  ///@}

  ///@{
  /// Most peels the depth peeling makes, [1, 100]; each sorts more of the translucent layers
  /// that overlap in a pixel. Default 4 (vtkRenderer's default).
  vtkSetClampMacro(MaximumNumberOfPeels, int, 1, 100);
  vtkGetMacro(MaximumNumberOfPeels, int);
  ///@}

  /// Installs the chain for the current settings in the renderer (vtkRenderer::SetPass; none
  /// when neither SSAO nor Shadows is on), sets its depth peeling, and with SunLight its
  /// lights. The chain is built anew when a setting, the renderer or its window has changed
  /// since the last Apply(); the chain it replaces frees its graphics resources then. Does
  /// nothing for a null renderer.
  void Apply(vtkRenderer* renderer);

  /// The outermost pass of the chain the last Apply() installed (it belongs to this object),
  /// or nullptr when none.
  vtkRenderPass* GetPass();

protected:
  vtkMesoRenderPasses();
  ~vtkMesoRenderPasses() override;

  bool SSAO = false;
  double SSAORadius = 0.5;
  double SSAOBias = 0.01;
  int SSAOKernelSize = 32;
  bool SSAOBlur = false;
  bool Shadows = false;
  int ShadowMapResolution = 1024;
  bool SunLight = false;
  double SunPosition[3] = { 0.0, 0.0, 1.0 };
  double SunFocalPoint[3] = { 0.0, 0.0, 0.0 };
  bool DepthPeeling = false;
  int MaximumNumberOfPeels = 4;

private:
  vtkMesoRenderPasses(const vtkMesoRenderPasses&) = delete;
  void operator=(const vtkMesoRenderPasses&) = delete;

  vtkSmartPointer<vtkRenderPass> BuildChain();
  void SetLights(vtkRenderer* renderer);

  vtkSmartPointer<vtkRenderPass> Chain;
  vtkTimeStamp ChainTime;
  vtkWeakPointer<vtkRenderer> ChainRenderer;
  vtkWeakPointer<vtkWindow> ChainWindow;
  vtkNew<vtkLight> Headlight;
  vtkNew<vtkLight> Sun;
};

#endif
