// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoAssemblyInstances.h"

#include "vtkMesoArrayNames.h"
#include "vtkMesoAtomTableConversion.h"

#include "mesolens/common/errors.h"

#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkTypeUInt32Array.h>
#include <vtkUnsignedCharArray.h>

namespace {

vtkNew<vtkDoubleArray> Doubles(const char* name, int components, vtkIdType tuples)
{
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(tuples);
  return array;
}

template<typename ArrayT>
ArrayT* Get(vtkFieldData* data, const char* name, int components, vtkIdType tuples)
{
  auto* array = ArrayT::SafeDownCast(data->GetAbstractArray(name));
  return array && array->GetNumberOfComponents() == components &&
      (tuples < 0 || array->GetNumberOfTuples() == tuples)
    ? array
    : nullptr;
}

void WriteAtomSets(const std::vector<mesolens::AssemblyAtomSet>& sets, vtkFieldData* fields)
{
  vtkNew<vtkIdTypeArray> offsets;
  offsets->SetName(vtkMesoArrayNames::AssemblyAtomSetOffsets);
  vtkNew<vtkTypeUInt32Array> atoms;
  atoms->SetName(vtkMesoArrayNames::AssemblyAtomSetAtoms);
  vtkNew<vtkUnsignedCharArray> whole;
  whole->SetName(vtkMesoArrayNames::AssemblyAtomSetWhole);
  offsets->InsertNextValue(0);
  for (const mesolens::AssemblyAtomSet& set : sets)
  {
    for (std::uint32_t row : set.atoms)
    {
      atoms->InsertNextValue(row);
    }
    offsets->InsertNextValue(atoms->GetNumberOfValues());
    whole->InsertNextValue(set.whole_table ? 1 : 0);
  }
  fields->AddArray(offsets);
  fields->AddArray(atoms);
  fields->AddArray(whole);
}

} // namespace

namespace vtkMesoAssemblyInstances {

bool Write(const mesolens::AssemblyInstances& instances, vtkPolyData* output)
{
  output->Initialize();
  const auto copies = static_cast<vtkIdType>(instances.instances.size());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(copies);
  vtkNew<vtkIntArray> copy_ids;
  copy_ids->SetName(vtkMesoArrayNames::AssemblyCopy);
  copy_ids->SetNumberOfValues(copies);
  vtkNew<vtkIntArray> sets;
  sets->SetName(vtkMesoArrayNames::AssemblyAtomSet);
  sets->SetNumberOfValues(copies);
  auto matrices = Doubles(vtkMesoArrayNames::AssemblyMatrix, 12, copies);
  auto orientations = Doubles(vtkMesoArrayNames::AssemblyOrientation, 4, copies);
  auto spheres = Doubles(vtkMesoArrayNames::AssemblyBoundingSphere, 4, copies);
  bool rotations = true;
  for (vtkIdType c = 0; c < copies; ++c)
  {
    const mesolens::AssemblyInstance& instance = instances.instances[std::size_t(c)];
    const mesolens::AssemblyMatrix& m = instance.matrix;
    points->SetPoint(c, m[3], m[7], m[11]);
    copy_ids->SetValue(c, int(c));
    sets->SetValue(c, int(instance.atom_set));
    matrices->SetTypedTuple(c, m.data());
    const double sphere[4] = { instance.center[0], instance.center[1], instance.center[2],
                               instance.radius };
    spheres->SetTypedTuple(c, sphere);
    try
    {
      orientations->SetTypedTuple(c, mesolens::rotation_quaternion(m).data());
    }
    catch (const mesolens::InvalidInput&)
    {
      rotations = false;
    }
  }
  output->SetPoints(points);
  vtkMesoAtomTableConversion::SetAtomVertices(output);
  vtkPointData* data = output->GetPointData();
  data->AddArray(copy_ids);
  data->AddArray(sets);
  data->AddArray(matrices);
  data->AddArray(spheres);
  if (rotations)
  {
    data->AddArray(orientations);
  }
  WriteAtomSets(instances.atom_sets, output->GetFieldData());
  return rotations;
}

bool Read(vtkPolyData* input, mesolens::AssemblyInstances& instances)
{
  instances = mesolens::AssemblyInstances{};
  if (!input)
  {
    return false;
  }
  const vtkIdType copies = input->GetNumberOfPoints();
  vtkPointData* data = input->GetPointData();
  vtkFieldData* fields = input->GetFieldData();
  auto* sets = Get<vtkIntArray>(data, vtkMesoArrayNames::AssemblyAtomSet, 1, copies);
  auto* matrices = Get<vtkDoubleArray>(data, vtkMesoArrayNames::AssemblyMatrix, 12, copies);
  auto* spheres = Get<vtkDoubleArray>(data, vtkMesoArrayNames::AssemblyBoundingSphere, 4, copies);
  auto* offsets = Get<vtkIdTypeArray>(fields, vtkMesoArrayNames::AssemblyAtomSetOffsets, 1, -1);
  auto* atoms = Get<vtkTypeUInt32Array>(fields, vtkMesoArrayNames::AssemblyAtomSetAtoms, 1, -1);
  auto* whole = Get<vtkUnsignedCharArray>(fields, vtkMesoArrayNames::AssemblyAtomSetWhole, 1, -1);
  if (!sets || !matrices || !spheres || !offsets || !atoms || !whole ||
      offsets->GetNumberOfTuples() != whole->GetNumberOfTuples() + 1 ||
      offsets->GetValue(offsets->GetNumberOfTuples() - 1) != atoms->GetNumberOfTuples())
  {
    return false;
  }
  for (vtkIdType s = 0; s < whole->GetNumberOfTuples(); ++s)
  {
    mesolens::AssemblyAtomSet set;
    const vtkIdType begin = offsets->GetValue(s);
    const vtkIdType end = offsets->GetValue(s + 1);
    if (begin < 0 || begin > end || end > atoms->GetNumberOfTuples())
    {
      return false;
    }
    set.atoms.assign(atoms->GetPointer(begin), atoms->GetPointer(0) + end);
    set.whole_table = whole->GetValue(s) != 0;
    instances.atom_sets.push_back(std::move(set));
  }
  for (vtkIdType c = 0; c < copies; ++c)
  {
    mesolens::AssemblyInstance instance;
    matrices->GetTypedTuple(c, instance.matrix.data());
    const int set = sets->GetValue(c);
    if (set < 0 || std::size_t(set) >= instances.atom_sets.size())
    {
      return false;
    }
    instance.atom_set = std::size_t(set);
    double sphere[4];
    spheres->GetTypedTuple(c, sphere);
    instance.center = { sphere[0], sphere[1], sphere[2] };
    instance.radius = sphere[3];
    instances.instances.push_back(instance);
  }
  return true;
}

} // namespace vtkMesoAssemblyInstances
