// SPDX-License-Identifier: GPL-3.0-or-later
// Reads a structure with an installed MesoLens and prints its atom and bond counts.
#include <vtkMesoStructureReader.h>

#include <vtkExecutive.h>
#include <vtkNew.h>
#include <vtkPolyData.h>

#include <iostream>

int main(int argc, char* argv[])
{
  if (argc != 2)
  {
    std::cerr << "usage: count_atoms FILE.pdb\n";
    return 2;
  }
  vtkNew<vtkMesoStructureReader> reader;
  reader->SetFileName(argv[1]);
  if (!reader->GetExecutive()->Update())
  {
    return 1;
  }
  std::cout << reader->GetOutput()->GetNumberOfPoints() << " atoms, "
            << reader->GetOutput()->GetNumberOfLines() << " bonds\n";
  return 0;
}
