// SPDX-License-Identifier: GPL-3.0-or-later
/**
 * @class   vtkMesoRibbonLevelOfDetail
 * @brief   Chooses a vtkMesoRibbons' samples per residue for each piece of chain from its size
 *          on screen, and keeps the frame time under a budget (BioBrowser's adaptive level of
 *          detail).
 *
 * Before each render of Renderer (Watch()), or when Update() is called, every piece of chain
 * (the ribbons' `SegmentBounds`) gets as many samples per residue as keep neighbouring samples
 * about PixelsPerSample pixels apart on screen, between 1 and the ribbons' Subdivisions; pieces
 * out of view get 1. With a FrameTimeBudget (seconds), the spacing used grows by half while
 * frames take longer than the budget and shrinks back (never below PixelsPerSample) while they
 * take less than half of it. FullQuality gives every piece the ribbons' Subdivisions (for still
 * images and screenshots). The ribbons re-execute only when a count changes.
 */
#ifndef vtkMesoRibbonLevelOfDetail_h
#define vtkMesoRibbonLevelOfDetail_h

#include "MesoLensRenderingModule.h"
#include "vtkObject.h"
#include "vtkWeakPointer.h"

class vtkMesoRibbons;
class vtkRenderer;

class MESOLENSRENDERING_EXPORT vtkMesoRibbonLevelOfDetail : public vtkObject
{
public:
  static vtkMesoRibbonLevelOfDetail* New();
  vtkTypeMacro(vtkMesoRibbonLevelOfDetail, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The ribbons to steer and the renderer that shows them (weak references).
  void SetRibbons(vtkMesoRibbons* ribbons);
  vtkMesoRibbons* GetRibbons();
  void SetRenderer(vtkRenderer* renderer);
  vtkRenderer* GetRenderer();
  ///@}

  ///@{
  /// Screen distance wanted between samples, pixels, [0.5, 100]; default 4. Setting it
  /// restarts the frame-time adaptation from it.
  void SetPixelsPerSample(double pixels);
  vtkGetMacro(PixelsPerSample, double);
  ///@}

  ///@{
  /// Frame time to stay under, seconds, [0, 10]; 0 (default): no adaptation.
  vtkSetClampMacro(FrameTimeBudget, double, 0.0, 10.0);
  vtkGetMacro(FrameTimeBudget, double);
  ///@}

  ///@{
  /// Every piece at the ribbons' Subdivisions. Default off.
  vtkSetMacro(FullQuality, bool);
  vtkGetMacro(FullQuality, bool);
  vtkBooleanMacro(FullQuality, bool);
  ///@}

  /// The spacing in use after the frame-time adaptation, pixels.
  vtkGetMacro(AdaptedPixelsPerSample, double);

  /// Sets the ribbons' per-piece samples from the renderer's current view (updating the
  /// ribbons first when they have no output yet). Returns the total samples per residue summed
  /// over the pieces (a measure of the work), 0 without ribbons or renderer.
  long long Update();

  /// Calls Update() before every render of the renderer and reads each frame's time after it
  /// (for FrameTimeBudget). Unwatch() stops.
  void Watch();
  void Unwatch();

  /// Feeds one frame time (seconds) to the budget adaptation; Watch() does it after each render.
  void ReportFrameTime(double seconds);

protected:
  vtkMesoRibbonLevelOfDetail();
  ~vtkMesoRibbonLevelOfDetail() override;

  double PixelsPerSample = 4.0;
  double FrameTimeBudget = 0.0;
  bool FullQuality = false;
  double AdaptedPixelsPerSample = 4.0;

private:
  vtkMesoRibbonLevelOfDetail(const vtkMesoRibbonLevelOfDetail&) = delete;
  void operator=(const vtkMesoRibbonLevelOfDetail&) = delete;

  vtkWeakPointer<vtkMesoRibbons> Ribbons;
  vtkWeakPointer<vtkRenderer> Renderer;
  unsigned long StartObserver = 0;
  unsigned long EndObserver = 0;
};

#endif
