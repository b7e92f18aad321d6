// SPDX-License-Identifier: GPL-3.0-or-later
// Render tests of protein cartoons (vtkMesoSecondaryStructure + vtkMesoRibbons): draws one
// scene to a PNG that the test compares with its baseline.
//
//   TestMesoRibbonsImage SCENE OUTPUT.png [--strand-width W]
//
// Scenes: ribbons_1tii (helix ribbons, coloured by secondary structure), cylinders_1tii (helix
// cylinders, coloured by chain), ribbons_1igy and cylinders_1igy (the antibody from
// ../shared/data, by chain; they print "needs ../shared/data" and draw nothing without it),
// styles_1hpv (ribbons, the inhibitor in ball-and-stick through vtkMesoAtomMapper and the
// translucent solvent-excluded surface of the protein, composited by depth peeling). --strand-width
// changes the strands' width (Å; a test breaks the picture on purpose with it).
#include "vtkMesoArrayNames.h"
#include "MesoAtomScenes.h"
#include "mesolens_test_data.h"
#include "mesolens_test_protein.h"
#include "vtkMesoAtomMapper.h"
#include "vtkMesoMolecularSurface.h"
#include "vtkMesoRenderPasses.h"
#include "vtkMesoRibbons.h"
#include "vtkMesoSecondaryStructure.h"
#include "vtkMesoStructureReader.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkIdList.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkStringArray.h>
#include <vtkWindowToImageFilter.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <string>

namespace {
double strand_width = 2.0;

/// Colours of the secondary-structure codes (mesolens::SecondaryStructure): coil, turn, bend,
/// polyproline grey; alpha helix red, 3-10 pink, pi purple; strand and bridge yellow.
vtkSmartPointer<vtkLookupTable> secondary_structure_colours()
{
  auto table = vtkSmartPointer<vtkLookupTable>::New();
  table->SetNumberOfTableValues(10);
  const double colours[10][3] = { { 0.75, 0.75, 0.75 }, { 0.90, 0.20, 0.25 }, { 0.95, 0.50, 0.65 },
                                  { 0.60, 0.30, 0.80 }, { 0.98, 0.80, 0.15 }, { 0.75, 0.75, 0.75 },
                                  { 0.75, 0.75, 0.75 }, { 0.98, 0.80, 0.15 }, { 0.90, 0.20, 0.25 },
                                  { 0.75, 0.75, 0.75 } };
  for (int i = 0; i < 10; ++i)
    table->SetTableValue(i, colours[i][0], colours[i][1], colours[i][2], 1.0);
  table->SetRange(0, 9);
  return table;
}

/// Eight well-separated chain colours, repeated.
vtkSmartPointer<vtkLookupTable> chain_colours(int chains)
{
  auto table = vtkSmartPointer<vtkLookupTable>::New();
  const double palette[8][3] = { { 0.30, 0.55, 0.85 }, { 0.90, 0.45, 0.20 }, { 0.35, 0.70, 0.35 },
                                 { 0.85, 0.30, 0.45 }, { 0.60, 0.45, 0.80 }, { 0.70, 0.55, 0.35 },
                                 { 0.90, 0.55, 0.75 }, { 0.55, 0.75, 0.80 } };
  table->SetNumberOfTableValues(std::max(chains, 1));
  for (int i = 0; i < std::max(chains, 1); ++i)
    table->SetTableValue(i, palette[i % 8][0], palette[i % 8][1], palette[i % 8][2], 1.0);
  table->SetRange(0, std::max(chains - 1, 1));
  return table;
}

struct Cartoon
{
  vtkNew<vtkMesoStructureReader> Reader;
  vtkNew<vtkMesoSecondaryStructure> Assignment;
  vtkNew<vtkMesoRibbons> Ribbons;
  vtkNew<vtkPolyDataMapper> Mapper;
  vtkNew<vtkActor> Actor;

  Cartoon(const std::string& path, bool cylinders, bool by_chain)
  {
    this->Reader->SetFileName(path.c_str());
    this->Assignment->SetInputConnection(this->Reader->GetOutputPort());
    this->Ribbons->SetInputConnection(this->Assignment->GetOutputPort());
    this->Ribbons->SetHelixAsCylinder(cylinders);
    this->Ribbons->SetStrandWidth(strand_width);
    this->Ribbons->Update();
    this->Mapper->SetInputConnection(this->Ribbons->GetOutputPort());
    this->Mapper->SetScalarModeToUsePointFieldData();
    this->Mapper->SetColorModeToMapScalars(); // unsigned char codes are no colours
    this->Mapper->ScalarVisibilityOn();
    this->Mapper->UseLookupTableScalarRangeOn();
    if (by_chain)
    {
      const int chains = int(this->Ribbons->GetOutput()
                               ->GetPointData()
                               ->GetArray(vtkMesoArrayNames::ChainIndex)
                               ->GetRange()[1]) +
        1;
      this->Mapper->SelectColorArray(vtkMesoArrayNames::ChainIndex);
      this->Mapper->SetLookupTable(chain_colours(chains));
    }
    else
    {
      this->Mapper->SelectColorArray(vtkMesoArrayNames::SecondaryStructure);
      this->Mapper->SetLookupTable(secondary_structure_colours());
    }
    this->Actor->SetMapper(this->Mapper);
    this->Actor->GetProperty()->SetSpecular(0.3);
    this->Actor->GetProperty()->SetSpecularPower(30);
  }
};

vtkSmartPointer<vtkRenderWindow> window_with(vtkRenderer* renderer, int width, int height)
{
  auto window = mesolens_test::test_window(width, height);
  renderer->SetBackground(1.0, 1.0, 1.0);
  window->AddRenderer(renderer);
  return window;
}

/// The cartoon of a file, seen along z, filling the window.
vtkSmartPointer<vtkRenderWindow> cartoon(const std::string& path, bool cylinders, bool by_chain)
{
  static std::unique_ptr<Cartoon> keep;
  keep = std::make_unique<Cartoon>(path, cylinders, by_chain);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(keep->Actor);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Zoom(1.3);
  return window_with(renderer, 400, 400);
}

/// HIV-1 protease: ribbons, the inhibitor (residue 478) as balls and sticks, and the translucent
/// solvent-excluded surface of the protein, composited by depth peeling.
vtkSmartPointer<vtkRenderWindow> styles()
{
  static std::unique_ptr<Cartoon> keep;
  keep = std::make_unique<Cartoon>(mesolens_test::data_file("proteins/1hpv.pdb"), false, false);
  vtkPolyData* atoms = keep->Reader->GetOutput();
  // The ligand: its atoms, as a polydata of vertices with the reader's arrays.
  static vtkNew<vtkPolyData> ligand;
  {
    auto* residues = vtkStringArray::SafeDownCast(
      atoms->GetPointData()->GetAbstractArray(vtkMesoArrayNames::ResidueName));
    vtkNew<vtkIdList> kept;
    for (vtkIdType a = 0; a < atoms->GetNumberOfPoints(); ++a)
      if (residues->GetValue(a) == "478")
        kept->InsertNextId(a);
    vtkNew<vtkPoints> points;
    atoms->GetPoints()->GetPoints(kept, points);
    ligand->SetPoints(points);
    ligand->GetPointData()->CopyAllocate(atoms->GetPointData(), kept->GetNumberOfIds());
    vtkNew<vtkIdList> order;
    for (vtkIdType i = 0; i < kept->GetNumberOfIds(); ++i)
      order->InsertNextId(i);
    ligand->GetPointData()->CopyData(atoms->GetPointData(), kept, order);
    // Bonds within the ligand, renumbered.
    vtkNew<vtkCellArray> bonds;
    vtkNew<vtkIdList> ends;
    std::map<vtkIdType, vtkIdType> renumber;
    for (vtkIdType i = 0; i < kept->GetNumberOfIds(); ++i)
      renumber[kept->GetId(i)] = i;
    for (vtkIdType c = 0; c < atoms->GetLines()->GetNumberOfCells(); ++c)
    {
      atoms->GetLines()->GetCellAtId(c, ends);
      const auto a = renumber.find(ends->GetId(0));
      const auto b = renumber.find(ends->GetId(1));
      if (a != renumber.end() && b != renumber.end())
        bonds->InsertNextCell({ a->second, b->second });
    }
    ligand->SetLines(bonds);
    vtkNew<vtkCellArray> vertices;
    for (vtkIdType i = 0; i < kept->GetNumberOfIds(); ++i)
      vertices->InsertNextCell(1, &i);
    ligand->SetVerts(vertices);
  }
  static vtkNew<vtkMesoAtomMapper> ligand_mapper;
  ligand_mapper->SetInputData(ligand);
  ligand_mapper->SetStyle(vtkMesoAtomMapper::BALL_AND_STICK);
  ligand_mapper->SetBallScale(0.45);
  ligand_mapper->SetBondRadius(0.3);
  static vtkNew<vtkActor> ligand_actor;
  ligand_actor->SetMapper(ligand_mapper);
  // The solvent-excluded surface of the protein's atoms (no waters, no ligand).
  static vtkNew<vtkPolyData> protein;
  protein->ShallowCopy(mesolens_test::protein_atoms(atoms));
  static vtkNew<vtkMesoMolecularSurface> surface;
  surface->SetInputData(protein);
  surface->SetTolerance(0.2);
  static vtkNew<vtkPolyDataMapper> surface_mapper;
  surface_mapper->SetInputConnection(surface->GetOutputPort());
  surface_mapper->ScalarVisibilityOff();
  static vtkNew<vtkActor> surface_actor;
  surface_actor->SetMapper(surface_mapper);
  surface_actor->GetProperty()->SetColor(0.55, 0.7, 0.95);
  surface_actor->GetProperty()->SetOpacity(0.25);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(keep->Actor);
  renderer->AddActor(ligand_actor);
  renderer->AddActor(surface_actor);
  vtkNew<vtkMesoRenderPasses> passes;
  passes->DepthPeelingOn();
  passes->SetMaximumNumberOfPeels(8);
  passes->Apply(renderer);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Elevation(-60);
  renderer->GetActiveCamera()->OrthogonalizeViewUp();
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Zoom(1.3);
  auto window = window_with(renderer, 400, 400);
  window->SetAlphaBitPlanes(1);
  return window;
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc < 3)
  {
    std::fprintf(stderr, "usage: TestMesoRibbonsImage SCENE OUTPUT.png\n");
    return 2;
  }
  const std::string scene = argv[1];
  if (argc >= 5 && !std::strcmp(argv[3], "--strand-width"))
    strand_width = std::atof(argv[4]);
  vtkSmartPointer<vtkRenderWindow> window;
  if (scene == "ribbons_1tii")
    window = cartoon(mesolens_test::data_file("proteins/1tii.pdb"), false, false);
  else if (scene == "cylinders_1tii")
    window = cartoon(mesolens_test::data_file("proteins/1tii.pdb"), true, true);
  else if (scene == "ribbons_1igy" || scene == "cylinders_1igy")
  {
    const std::string path = mesolens_test::shared_file("proteins/1igy.pdb");
    if (!mesolens_test::exists(path))
    {
      std::printf("needs ../shared/data\n");
      return 0;
    }
    window = cartoon(path, scene == "cylinders_1igy", true);
  }
  else if (scene == "styles_1hpv")
    window = styles();
  else
  {
    std::fprintf(stderr, "unknown scene %s\n", scene.c_str());
    return 2;
  }
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(argv[2]);
  writer->SetInputConnection(grab->GetOutputPort());
  writer->Write();
  return 0;
}
