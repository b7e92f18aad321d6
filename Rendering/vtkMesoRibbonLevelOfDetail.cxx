// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoRibbonLevelOfDetail.h"

#include "vtkMesoArrayNames.h"

#include "vtkMesoRibbons.h"

#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkRenderer.h>

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkMesoRibbonLevelOfDetail);

vtkMesoRibbonLevelOfDetail::vtkMesoRibbonLevelOfDetail() = default;

vtkMesoRibbonLevelOfDetail::~vtkMesoRibbonLevelOfDetail()
{
  this->Unwatch();
}

void vtkMesoRibbonLevelOfDetail::SetRibbons(vtkMesoRibbons* ribbons)
{
  this->Ribbons = ribbons;
  this->Modified();
}

vtkMesoRibbons* vtkMesoRibbonLevelOfDetail::GetRibbons()
{
  return this->Ribbons;
}

void vtkMesoRibbonLevelOfDetail::SetRenderer(vtkRenderer* renderer)
{
  const bool watching = this->StartObserver != 0;
  this->Unwatch();
  this->Renderer = renderer;
  if (watching)
  {
    this->Watch();
  }
  this->Modified();
}

vtkRenderer* vtkMesoRibbonLevelOfDetail::GetRenderer()
{
  return this->Renderer;
}

void vtkMesoRibbonLevelOfDetail::SetPixelsPerSample(double pixels)
{
  pixels = std::clamp(pixels, 0.5, 100.0);
  if (pixels != this->PixelsPerSample || pixels != this->AdaptedPixelsPerSample)
  {
    this->PixelsPerSample = pixels;
    this->AdaptedPixelsPerSample = pixels;
    this->Modified();
  }
}

void vtkMesoRibbonLevelOfDetail::ReportFrameTime(double seconds)
{
  if (this->FrameTimeBudget <= 0)
  {
    this->AdaptedPixelsPerSample = this->PixelsPerSample;
    return;
  }
  if (seconds > this->FrameTimeBudget)
  {
    this->AdaptedPixelsPerSample = std::min(100.0, this->AdaptedPixelsPerSample * 1.5);
  }
  else if (seconds < 0.5 * this->FrameTimeBudget)
  {
    this->AdaptedPixelsPerSample =
      std::max(this->PixelsPerSample, this->AdaptedPixelsPerSample / 1.5);
  }
}

long long vtkMesoRibbonLevelOfDetail::Update()
{
  vtkMesoRibbons* ribbons = this->Ribbons;
  vtkRenderer* renderer = this->Renderer;
  if (!ribbons || !renderer)
  {
    return 0;
  }
  if (this->FrameTimeBudget <= 0)
  {
    this->AdaptedPixelsPerSample = this->PixelsPerSample;
  }
  this->AdaptedPixelsPerSample = std::max(this->AdaptedPixelsPerSample, this->PixelsPerSample);
  vtkPolyData* output = ribbons->GetOutput();
  if (!output->GetFieldData()->GetArray(vtkMesoArrayNames::SegmentBounds))
  {
    ribbons->Update();
  }
  vtkDataArray* bounds = output->GetFieldData()->GetArray(vtkMesoArrayNames::SegmentBounds);
  vtkDataArray* lengths = output->GetFieldData()->GetArray(vtkMesoArrayNames::SegmentResidueCounts);
  if (!bounds || !lengths)
  {
    return 0;
  }
  const int most = ribbons->GetSubdivisions();
  const vtkIdType pieces = bounds->GetNumberOfTuples();
  vtkNew<vtkIntArray> counts;
  counts->SetNumberOfValues(pieces);
  // World to normalized device coordinates, then pixels.
  const int* size = renderer->GetSize();
  const double aspect = size[1] > 0 ? double(size[0]) / double(size[1]) : 1.0;
  vtkMatrix4x4* to_device =
    renderer->GetActiveCamera()->GetCompositeProjectionTransformMatrix(aspect, -1, 1);
  long long total = 0;
  for (vtkIdType s = 0; s < pieces; ++s)
  {
    int count = most;
    if (!this->FullQuality)
    {
      double box[6];
      bounds->GetTuple(s, box);
      // The box's extent on screen, from its corners in front of the eye.
      double low[2] = { 1e30, 1e30 };
      double high[2] = { -1e30, -1e30 };
      bool in_front = false;
      for (int corner = 0; corner < 8; ++corner)
      {
        const double world[4] = { box[corner & 1 ? 1 : 0], box[corner & 2 ? 3 : 2],
                                  box[corner & 4 ? 5 : 4], 1.0 };
        double device[4];
        to_device->MultiplyPoint(world, device);
        if (device[3] <= 1e-9)
        {
          continue;
        }
        in_front = true;
        for (int d = 0; d < 2; ++d)
        {
          const double pixel = (device[d] / device[3] + 1.0) * 0.5 * size[d];
          low[d] = std::min(low[d], pixel);
          high[d] = std::max(high[d], pixel);
        }
      }
      const bool visible =
        in_front && high[0] >= 0 && low[0] <= size[0] && high[1] >= 0 && low[1] <= size[1];
      if (!visible)
      {
        count = 1;
      }
      else
      {
        const double diagonal_world =
          std::sqrt((box[1] - box[0]) * (box[1] - box[0]) + (box[3] - box[2]) * (box[3] - box[2]) +
                    (box[5] - box[4]) * (box[5] - box[4]));
        const double diagonal_pixels = std::hypot(high[0] - low[0], high[1] - low[1]);
        // A residue spans about 3.8 Å of chain; samples every AdaptedPixelsPerSample pixels.
        const double pixels_per_residue =
          diagonal_world > 1e-6 ? 3.8 * diagonal_pixels / diagonal_world : 0.0;
        count =
          std::clamp(int(std::ceil(pixels_per_residue / this->AdaptedPixelsPerSample)), 1, most);
      }
    }
    counts->SetValue(s, count);
    total += static_cast<long long>(count) * static_cast<long long>(lengths->GetTuple1(s));
  }
  vtkIntArray* current = ribbons->GetSegmentSubdivisions();
  bool same = current && current->GetNumberOfValues() == pieces;
  for (vtkIdType s = 0; same && s < pieces; ++s)
  {
    same = current->GetValue(s) == counts->GetValue(s);
  }
  if (!same)
  {
    ribbons->SetSegmentSubdivisions(counts);
  }
  return total;
}

void vtkMesoRibbonLevelOfDetail::Watch()
{
  vtkRenderer* renderer = this->Renderer;
  if (!renderer || this->StartObserver != 0)
  {
    return;
  }
  vtkNew<vtkCallbackCommand> before;
  before->SetClientData(this);
  before->SetCallback([](vtkObject*, unsigned long, void* self, void*) {
    static_cast<vtkMesoRibbonLevelOfDetail*>(self)->Update();
  });
  this->StartObserver = renderer->AddObserver(vtkCommand::StartEvent, before);
  vtkNew<vtkCallbackCommand> after;
  after->SetClientData(this);
  after->SetCallback([](vtkObject* caller, unsigned long, void* self, void*) {
    static_cast<vtkMesoRibbonLevelOfDetail*>(self)->ReportFrameTime(
      static_cast<vtkRenderer*>(caller)->GetLastRenderTimeInSeconds());
  });
  this->EndObserver = renderer->AddObserver(vtkCommand::EndEvent, after);
}

void vtkMesoRibbonLevelOfDetail::Unwatch()
{
  vtkRenderer* renderer = this->Renderer;
  if (renderer)
  {
    renderer->RemoveObserver(this->StartObserver);
    renderer->RemoveObserver(this->EndObserver);
  }
  this->StartObserver = 0;
  this->EndObserver = 0;
}

void vtkMesoRibbonLevelOfDetail::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PixelsPerSample: " << this->PixelsPerSample << "\n";
  os << indent << "FrameTimeBudget: " << this->FrameTimeBudget << "\n";
  os << indent << "FullQuality: " << this->FullQuality << "\n";
  os << indent << "AdaptedPixelsPerSample: " << this->AdaptedPixelsPerSample << "\n";
}
