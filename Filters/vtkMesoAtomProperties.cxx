// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoAtomProperties.h"

#include "vtkMesoArrayNames.h"

#include "mesolens/molecules/elements.h"

#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

vtkStandardNewMacro(vtkMesoAtomProperties);

vtkMesoAtomProperties::vtkMesoAtomProperties()
  : BeadRadius(mesolens::bead_radius)
{
}

int vtkMesoAtomProperties::RequestData(vtkInformation*, vtkInformationVector** inputVector,
                                       vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  output->Initialize();
  vtkDataArray* atomic_numbers = input->GetPointData()->GetArray(vtkMesoArrayNames::AtomicNumber);
  if (!atomic_numbers || atomic_numbers->GetNumberOfComponents() != 1)
  {
    vtkErrorMacro("The input has no one-component point array 'AtomicNumber'; "
                  "connect a MesoLens atom reader.");
    return 0;
  }
  output->ShallowCopy(input);
  const vtkIdType n = atomic_numbers->GetNumberOfTuples();
  vtkNew<vtkFloatArray> van_der_waals;
  van_der_waals->SetName(vtkMesoArrayNames::VanDerWaalsRadius);
  van_der_waals->SetNumberOfValues(n);
  vtkNew<vtkFloatArray> covalent;
  covalent->SetName(vtkMesoArrayNames::CovalentRadius);
  covalent->SetNumberOfValues(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    const int z = static_cast<int>(atomic_numbers->GetComponent(i, 0));
    const bool known = z > 0 && z <= mesolens::max_atomic_number;
    van_der_waals->SetValue(
      i,
      static_cast<float>((known ? mesolens::van_der_waals_radius(z) : this->BeadRadius) *
                         this->LengthScale));
    covalent->SetValue(
      i,
      static_cast<float>((known ? mesolens::covalent_radius(z) : this->BeadRadius) *
                         this->LengthScale));
  }
  output->GetPointData()->AddArray(van_der_waals);
  output->GetPointData()->AddArray(covalent);
  return 1;
}

void vtkMesoAtomProperties::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "LengthScale: " << this->LengthScale << "\n";
  os << indent << "BeadRadius: " << this->BeadRadius << "\n";
}
