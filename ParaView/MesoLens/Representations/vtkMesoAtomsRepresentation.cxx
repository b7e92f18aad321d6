// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoAtomsRepresentation.h"

#include "vtkActor.h"
#include "vtkAppendPolyData.h"
#include "vtkCellArray.h"
#include "vtkCellType.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkInformation.h"
#include "vtkIdList.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkMesoAtomMapper.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPVRenderView.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"

vtkStandardNewMacro(vtkMesoAtomsRepresentation);

namespace {
/// A dataset as atoms: polydata as it is; any other dataset (ParaView's Threshold or Extract
/// Selection of atoms give unstructured grids) as its points, point arrays and 2-point lines
/// (the bonds).
vtkSmartPointer<vtkPolyData> AtomsOfDataSet(vtkDataSet* data)
{
  auto atoms = vtkSmartPointer<vtkPolyData>::New();
  if (auto polydata = vtkPolyData::SafeDownCast(data))
  {
    atoms->ShallowCopy(polydata);
    return atoms;
  }
  if (auto point_set = vtkPointSet::SafeDownCast(data))
  {
    atoms->SetPoints(point_set->GetPoints()); // shared, not copied
  }
  else
  {
    vtkNew<vtkPoints> points;
    points->SetNumberOfPoints(data->GetNumberOfPoints());
    for (vtkIdType i = 0; i < data->GetNumberOfPoints(); ++i)
    {
      points->SetPoint(i, data->GetPoint(i));
    }
    atoms->SetPoints(points);
  }
  atoms->GetPointData()->ShallowCopy(data->GetPointData());
  vtkNew<vtkCellArray> bonds;
  vtkNew<vtkIdList> ends;
  for (vtkIdType c = 0; c < data->GetNumberOfCells(); ++c)
  {
    if (data->GetCellType(c) == VTK_LINE)
    {
      data->GetCellPoints(c, ends);
      bonds->InsertNextCell(ends);
    }
  }
  atoms->SetLines(bonds);
  return atoms;
}

/// Any input as one polydata of atoms: the blocks of a composite dataset appended in order.
vtkSmartPointer<vtkPolyData> AtomsOf(vtkDataObject* input)
{
  if (auto data = vtkDataSet::SafeDownCast(input))
  {
    return AtomsOfDataSet(data);
  }
  auto composite = vtkCompositeDataSet::SafeDownCast(input);
  if (!composite)
  {
    return vtkSmartPointer<vtkPolyData>::New();
  }
  vtkNew<vtkAppendPolyData> append;
  vtkSmartPointer<vtkCompositeDataIterator> block;
  block.TakeReference(composite->NewIterator());
  for (block->InitTraversal(); !block->IsDoneWithTraversal(); block->GoToNextItem())
  {
    if (auto data = vtkDataSet::SafeDownCast(block->GetCurrentDataObject()))
    {
      append->AddInputData(AtomsOfDataSet(data));
    }
  }
  if (append->GetNumberOfInputConnections(0) == 0)
  {
    return vtkSmartPointer<vtkPolyData>::New();
  }
  append->Update();
  return append->GetOutput();
}
}

vtkMesoAtomsRepresentation::vtkMesoAtomsRepresentation()
  : Atoms(vtkSmartPointer<vtkPolyData>::New())
  , Mapper(vtkMesoAtomMapper::New())
  , BoundsMapper(vtkMesoAtomMapper::New())
  , Actor(vtkActor::New())
{
  this->Actor->SetMapper(this->Mapper);
  this->Mapper->SetUseLookupTableScalarRange(true);
  this->Mapper->SetScalarModeToUsePointFieldData();
  this->Mapper->ScalarVisibilityOff();
  this->Mapper->SetInputData(this->Atoms);
}

vtkMesoAtomsRepresentation::~vtkMesoAtomsRepresentation()
{
  this->Actor->Delete();
  this->BoundsMapper->Delete();
  this->Mapper->Delete();
}

int vtkMesoAtomsRepresentation::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkCompositeDataSet");
  // Representations have no input on the client and on render-only servers.
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

int vtkMesoAtomsRepresentation::RequestData(vtkInformation* request, vtkInformationVector** inputs,
                                            vtkInformationVector* outputs)
{
  vtkDataObject* input = vtkDataObject::GetData(inputs[0], 0);
  this->Atoms = input ? AtomsOf(input) : vtkSmartPointer<vtkPolyData>::New();
  return this->Superclass::RequestData(request, inputs, outputs);
}

void vtkMesoAtomsRepresentation::ComputeBounds(double bounds[6])
{
  vtkMath::UninitializeBounds(bounds);
  if (this->Atoms->GetNumberOfPoints() == 0)
  {
    return;
  }
  this->BoundsMapper->SetInputData(this->Atoms);
  this->BoundsMapper->SetStyle(this->Mapper->GetStyle());
  this->BoundsMapper->SetRadiusScale(this->Mapper->GetRadiusScale());
  this->BoundsMapper->SetBallScale(this->Mapper->GetBallScale());
  this->BoundsMapper->SetBondRadius(this->Mapper->GetBondRadius());
  this->BoundsMapper->GetBounds(bounds);
}

int vtkMesoAtomsRepresentation::ProcessViewRequest(vtkInformationRequestKey* request,
                                                   vtkInformation* inInfo, vtkInformation* outInfo)
{
  if (!this->Superclass::ProcessViewRequest(request, inInfo, outInfo))
  {
    return 0; // not visible
  }
  if (request == vtkPVView::REQUEST_UPDATE())
  {
    vtkPVRenderView::SetPiece(inInfo, this, this->Atoms);
    double bounds[6];
    this->ComputeBounds(bounds);
    vtkNew<vtkMatrix4x4> matrix;
    this->Actor->GetMatrix(matrix);
    vtkPVRenderView::SetGeometryBounds(inInfo, this, bounds, matrix);
    // Translucent geometry on several ranks (these atoms or anything else in the view) is
    // composited in depth order: the view may then move atoms between ranks, each vertex and
    // bond to one rank (an atom at the end of a bond that went elsewhere is drawn on both).
    vtkPVRenderView::SetOrderedCompositingConfiguration(
      inInfo, this,
      vtkPVRenderView::DATA_IS_REDISTRIBUTABLE | vtkPVRenderView::USE_DATA_FOR_LOAD_BALANCING);
    vtkPVRenderView::SetRedistributionModeToUniquelyAssignBoundaryCells(inInfo, this);
    if (this->Actor->GetProperty()->GetOpacity() < 1.0)
    {
      outInfo->Set(vtkPVRenderView::NEED_ORDERED_COMPOSITING(), 1);
    }
  }
  else if (request == vtkPVView::REQUEST_RENDER())
  {
    vtkDataObject* delivered = vtkPVView::GetDeliveredPiece(inInfo, this);
    auto atoms = vtkPolyData::SafeDownCast(delivered);
    this->Mapper->SetInputData(atoms ? atoms : this->Atoms.GetPointer());
    this->UpdateColoring();
  }
  return 1;
}

void vtkMesoAtomsRepresentation::UpdateColoring()
{
  vtkInformation* info = this->GetInputArrayInformation(0);
  const char* name = info && info->Has(vtkDataObject::FIELD_NAME())
    ? info->Get(vtkDataObject::FIELD_NAME())
    : nullptr;
  const bool points = info && info->Has(vtkDataObject::FIELD_ASSOCIATION()) &&
    info->Get(vtkDataObject::FIELD_ASSOCIATION()) == vtkDataObject::FIELD_ASSOCIATION_POINTS;
  if (name && name[0] && points)
  {
    this->Mapper->ScalarVisibilityOn();
    this->Mapper->SelectColorArray(name);
  }
  else
  {
    // Element colours (an atom is a point: cell arrays have nothing to colour).
    this->Mapper->ScalarVisibilityOff();
    this->Mapper->SelectColorArray(static_cast<const char*>(nullptr));
  }
}

bool vtkMesoAtomsRepresentation::AddToView(vtkView* view)
{
  auto renderView = vtkPVRenderView::SafeDownCast(view);
  if (!renderView)
  {
    return false;
  }
  renderView->GetRenderer()->AddActor(this->Actor);
  renderView->RegisterPropForHardwareSelection(this, this->Actor);
  return this->Superclass::AddToView(view);
}

bool vtkMesoAtomsRepresentation::RemoveFromView(vtkView* view)
{
  auto renderView = vtkPVRenderView::SafeDownCast(view);
  if (!renderView)
  {
    return false;
  }
  renderView->GetRenderer()->RemoveActor(this->Actor);
  renderView->UnRegisterPropForHardwareSelection(this, this->Actor);
  return this->Superclass::RemoveFromView(view);
}

void vtkMesoAtomsRepresentation::SetVisibility(bool visible)
{
  this->Actor->SetVisibility(visible);
  this->Superclass::SetVisibility(visible);
}

// Properties that change the atoms' extent re-run the view's update, for new bounds.
void vtkMesoAtomsRepresentation::SetStyle(int style)
{
  this->Mapper->SetStyle(style);
  this->MarkModified();
}

void vtkMesoAtomsRepresentation::SetRadiusScale(double scale)
{
  this->Mapper->SetRadiusScale(scale);
  this->MarkModified();
}

void vtkMesoAtomsRepresentation::SetBallScale(double scale)
{
  this->Mapper->SetBallScale(scale);
  this->MarkModified();
}

void vtkMesoAtomsRepresentation::SetBondRadius(double radius)
{
  this->Mapper->SetBondRadius(radius);
  this->MarkModified();
}

void vtkMesoAtomsRepresentation::SetOcclusionCulling(bool cull)
{
  this->Mapper->SetOcclusionCulling(cull);
}

void vtkMesoAtomsRepresentation::SetVisibilityArrayName(const char* name)
{
  this->Mapper->SetVisibilityArrayName(name);
}

void vtkMesoAtomsRepresentation::SetLookupTable(vtkScalarsToColors* table)
{
  this->Mapper->SetLookupTable(table);
}

void vtkMesoAtomsRepresentation::SetOpacity(double opacity)
{
  this->Actor->GetProperty()->SetOpacity(opacity);
  this->MarkModified(); // the view's compositing depends on it
}

void vtkMesoAtomsRepresentation::SetAmbient(double ambient)
{
  this->Actor->GetProperty()->SetAmbient(ambient);
}

void vtkMesoAtomsRepresentation::SetDiffuse(double diffuse)
{
  this->Actor->GetProperty()->SetDiffuse(diffuse);
}

void vtkMesoAtomsRepresentation::SetSpecular(double specular)
{
  this->Actor->GetProperty()->SetSpecular(specular);
}

void vtkMesoAtomsRepresentation::SetSpecularPower(double power)
{
  this->Actor->GetProperty()->SetSpecularPower(power);
}

void vtkMesoAtomsRepresentation::SetAmbientColor(double r, double g, double b)
{
  this->Actor->GetProperty()->SetAmbientColor(r, g, b);
}

void vtkMesoAtomsRepresentation::SetDiffuseColor(double r, double g, double b)
{
  this->Actor->GetProperty()->SetDiffuseColor(r, g, b);
}

void vtkMesoAtomsRepresentation::SetSpecularColor(double r, double g, double b)
{
  this->Actor->GetProperty()->SetSpecularColor(r, g, b);
}

void vtkMesoAtomsRepresentation::SetPickable(int pickable)
{
  this->Actor->SetPickable(pickable);
}

void vtkMesoAtomsRepresentation::SetPosition(double x, double y, double z)
{
  this->Actor->SetPosition(x, y, z);
  this->MarkModified();
}

void vtkMesoAtomsRepresentation::SetOrientation(double x, double y, double z)
{
  this->Actor->SetOrientation(x, y, z);
  this->MarkModified();
}

void vtkMesoAtomsRepresentation::SetScale(double x, double y, double z)
{
  this->Actor->SetScale(x, y, z);
  this->MarkModified();
}

void vtkMesoAtomsRepresentation::SetOrigin(double x, double y, double z)
{
  this->Actor->SetOrigin(x, y, z);
  this->MarkModified();
}

void vtkMesoAtomsRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Atoms: " << this->Atoms->GetNumberOfPoints() << "\n";
  os << indent << "Mapper: " << this->Mapper << "\n";
}
