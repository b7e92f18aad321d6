// SPDX-License-Identifier: GPL-3.0-or-later
// vtkMesoAtomMapper: picking against a CPU ray cast, GPU data size, animation uploads, bounds
// and bad input.
#include "vtkMesoArrayNames.h"
#include "MesoAtomScenes.h"
#include "mesolens_vtk_test_utilities.h"

#include "mesolens/molecules/elements.h"
#include "mesolens/protein/assembly.h"
#include "mesolens/render/impostor_geometry.h"

#include "vtkMesoAssemblyInstances.h"
#include "vtkMesoAtomTableConversion.h"

#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkHardwareSelector.h>
#include <vtkIdList.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkProperty.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowToImageFilter.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <random>
#include <vector>
#include <optional>

namespace {
using mesolens::Vector3;

struct Scene
{
  vtkSmartPointer<vtkRenderWindow> Window;
  vtkSmartPointer<vtkRenderer> Renderer;
  vtkSmartPointer<vtkMesoAtomMapper> Mapper;
  vtkSmartPointer<vtkActor> Actor;
};

/// A window, renderer, actor and mapper in a style, without input.
Scene empty_scene(int style, int size)
{
  Scene scene;
  scene.Window = mesolens_test::test_window(size, size);
  scene.Renderer = vtkSmartPointer<vtkRenderer>::New();
  scene.Mapper = vtkSmartPointer<vtkMesoAtomMapper>::New();
  scene.Mapper->SetStyle(style);
  scene.Actor = vtkSmartPointer<vtkActor>::New();
  scene.Actor->SetMapper(scene.Mapper);
  scene.Renderer->AddActor(scene.Actor);
  scene.Window->AddRenderer(scene.Renderer);
  return scene;
}

Scene make_scene(vtkAlgorithm* source, int style, int size = 160)
{
  Scene scene = empty_scene(style, size);
  scene.Mapper->SetInputConnection(source->GetOutputPort());
  return scene;
}

Scene make_scene(vtkPolyData* atoms, int style)
{
  Scene scene = empty_scene(style, 64);
  scene.Mapper->SetInputData(atoms);
  return scene;
}

/// The world-space ray through the centre of pixel (x, y).
void pixel_ray(vtkRenderer* renderer, int x, int y, Vector3& origin, Vector3& direction)
{
  double world[2][4];
  for (int end = 0; end < 2; ++end)
  {
    renderer->SetDisplayPoint(x + 0.5, y + 0.5, end);
    renderer->DisplayToWorld();
    renderer->GetWorldPoint(world[end]);
    for (int d = 0; d < 3; ++d)
    {
      world[end][d] /= world[end][3];
    }
  }
  double length = 0;
  for (int d = 0; d < 3; ++d)
  {
    origin[d] = world[0][d];
    direction[d] = world[1][d] - world[0][d];
    length += direction[d] * direction[d];
  }
  for (double& c : direction)
  {
    c /= std::sqrt(length);
  }
}

/// The cell (atom i: i; bond j: atoms + j) that the CPU ray cast finds first, or -1.
vtkIdType cpu_pick(vtkPolyData* atoms, int style, const Vector3& origin, const Vector3& direction)
{
  const double ball = style == vtkMesoAtomMapper::BALL_AND_STICK ? 0.25 : 1.0;
  vtkDataArray* numbers = atoms->GetPointData()->GetArray(vtkMesoArrayNames::AtomicNumber);
  double nearest = std::numeric_limits<double>::infinity();
  vtkIdType picked = -1;
  for (vtkIdType i = 0; i < atoms->GetNumberOfPoints(); ++i)
  {
    double p[3];
    atoms->GetPoint(i, p);
    const double radius =
      ball * mesolens::van_der_waals_radius(static_cast<int>(numbers->GetComponent(i, 0)));
    const auto hit = mesolens::ray_sphere(origin, direction, { p[0], p[1], p[2] }, radius);
    if (hit && hit->t < nearest)
    {
      nearest = hit->t;
      picked = i;
    }
  }
  if (style == vtkMesoAtomMapper::BALL_AND_STICK)
  {
    vtkIdType bond = 0;
    vtkIdType size = 0;
    const vtkIdType* ids = nullptr;
    vtkCellArray* lines = atoms->GetLines();
    for (lines->InitTraversal(); lines->GetNextCell(size, ids); ++bond)
    {
      double a[3];
      double b[3];
      atoms->GetPoint(ids[0], a);
      atoms->GetPoint(ids[1], b);
      const auto hit =
        mesolens::ray_cylinder(origin, direction, { a[0], a[1], a[2] }, { b[0], b[1], b[2] }, 0.2);
      if (hit && hit->t < nearest)
      {
        nearest = hit->t;
        picked = atoms->GetNumberOfPoints() + bond;
      }
    }
  }
  return picked;
}

/// Hardware picks on a grid of pixels against the CPU ray cast: the fraction that agree among
/// the pixels where either finds something. `atoms_per_cell` > 0: the atoms are drawn in cells.
double picking_agreement(int style, int atoms_per_cell = 0)
{
  auto reader = mesolens_test::crambin();
  Scene scene = make_scene(reader, style);
  scene.Mapper->SetAtomsPerCell(atoms_per_cell);
  mesolens_test::look_at(scene.Renderer, reader->GetOutput(), 55.0);
  scene.Window->Render();
  vtkNew<vtkHardwareSelector> selector;
  selector->SetRenderer(scene.Renderer);
  selector->SetFieldAssociation(vtkDataObject::FIELD_ASSOCIATION_CELLS);
  selector->SetArea(0, 0, 159, 159);
  EXPECT_TRUE(selector->CaptureBuffers());
  int compared = 0;
  int agreed = 0;
  for (unsigned int y = 0; y < 160; y += 3)
  {
    for (unsigned int x = 0; x < 160; x += 3)
    {
      const unsigned int position[2] = { x, y };
      unsigned int found[2];
      const auto info = selector->GetPixelInformation(position, 0, found);
      const vtkIdType gpu = info.Valid ? info.AttributeID : -1;
      Vector3 origin;
      Vector3 direction;
      pixel_ray(scene.Renderer, int(x), int(y), origin, direction);
      const vtkIdType cpu = cpu_pick(reader->GetOutput(), style, origin, direction);
      if (gpu >= 0 || cpu >= 0)
      {
        ++compared;
        agreed += gpu == cpu;
      }
    }
  }
  selector->ClearBuffers();
  EXPECT_GT(compared, 400);
  return compared ? double(agreed) / compared : 0.0;
}

vtkSmartPointer<vtkPolyData> two_atoms()
{
  auto atoms = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  points->InsertNextPoint(1.5, 0, 0);
  atoms->SetPoints(points);
  vtkNew<vtkCellArray> vertices;
  vertices->InsertNextCell({ 0 });
  vertices->InsertNextCell({ 1 });
  atoms->SetVerts(vertices);
  vtkNew<vtkCellArray> lines;
  lines->InsertNextCell({ 0, 1 });
  atoms->SetLines(lines);
  return atoms;
}

/// Whether anything but the black background was drawn.
bool drew_something(vtkRenderWindow* window)
{
  vtkNew<vtkWindowToImageFilter> capture;
  capture->SetInput(window);
  capture->Update();
  vtkDataArray* pixels = capture->GetOutput()->GetPointData()->GetScalars();
  for (vtkIdType i = 0; i < pixels->GetNumberOfValues(); ++i)
  {
    if (pixels->GetVariantValue(i).ToInt() != 0)
    {
      return true;
    }
  }
  return false;
}

/// A simple cubic block of side^3 carbon atoms 1.5 Å apart, as vertices.
vtkSmartPointer<vtkPolyData> carbon_block(int side)
{
  auto atoms = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  vtkNew<vtkUnsignedCharArray> numbers;
  numbers->SetName(vtkMesoArrayNames::AtomicNumber);
  for (int i = 0; i < side * side * side; ++i)
  {
    points->InsertNextPoint(1.5 * (i % side), 1.5 * (i / side % side), 1.5 * (i / (side * side)));
    numbers->InsertNextValue(i % 7 == 0 ? 8 : 6); // some oxygens, for colour
  }
  atoms->SetPoints(points);
  atoms->GetPointData()->AddArray(numbers);
  vtkMesoAtomTableConversion::SetAtomVertices(atoms);
  return atoms;
}

std::vector<unsigned char> capture(vtkRenderWindow* window)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->Update();
  vtkDataArray* pixels = grab->GetOutput()->GetPointData()->GetScalars();
  std::vector<unsigned char> values(static_cast<std::size_t>(pixels->GetNumberOfValues()));
  for (vtkIdType i = 0; i < pixels->GetNumberOfValues(); ++i)
  {
    values[std::size_t(i)] = static_cast<unsigned char>(pixels->GetVariantValue(i).ToInt());
  }
  return values;
}

/// Pixels (RGB) of which a channel differs by more than 2.
int differing_pixels(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b)
{
  int count = 0;
  for (std::size_t i = 0; i + 2 < a.size() && i + 2 < b.size(); i += 3)
  {
    bool differs = false;
    for (std::size_t c = 0; c < 3; ++c)
    {
      differs = differs || std::abs(int(a[i + c]) - int(b[i + c])) > 2;
    }
    count += differs ? 1 : 0;
  }
  return count;
}

/// The same atoms drawn with culling and without, by the same camera.
struct CullingPair
{
  Scene Culled = empty_scene(vtkMesoAtomMapper::SPACE_FILLING, 200);
  Scene Whole = empty_scene(vtkMesoAtomMapper::SPACE_FILLING, 200);

  explicit CullingPair(vtkPolyData* atoms)
  {
    this->Culled.Mapper->SetInputData(atoms);
    this->Whole.Mapper->SetInputData(atoms);
    this->Whole.Mapper->OcclusionCullingOff();
    this->Culled.Renderer->ResetCamera();
    this->Whole.Renderer->SetActiveCamera(this->Culled.Renderer->GetActiveCamera());
  }

  /// Renders both; the number of pixels that differ.
  int Render()
  {
    this->Culled.Renderer->ResetCameraClippingRange();
    this->Culled.Window->Render();
    this->Whole.Window->Render();
    return differing_pixels(capture(this->Culled.Window), capture(this->Whole.Window));
  }
};
} // namespace

TEST(MesoAtomMapper, PicksTheAtomTheRayMeetsFirst)
{
  EXPECT_GT(picking_agreement(vtkMesoAtomMapper::SPACE_FILLING), 0.97);
}

TEST(MesoAtomMapper, PointPickingReportsTheAtom)
{
  auto reader = mesolens_test::crambin();
  Scene scene = make_scene(reader, vtkMesoAtomMapper::SPACE_FILLING);
  mesolens_test::look_at(scene.Renderer, reader->GetOutput(), 55.0);
  int compared = 0;
  int pass = 0;
  // Atoms in input order, then in cells of 16 (buffers in cell order).
  for (int association :
       { vtkDataObject::FIELD_ASSOCIATION_CELLS, vtkDataObject::FIELD_ASSOCIATION_POINTS,
         vtkDataObject::FIELD_ASSOCIATION_CELLS, vtkDataObject::FIELD_ASSOCIATION_POINTS })
  {
    scene.Mapper->SetAtomsPerCell(pass++ < 2 ? 0 : 16);
    scene.Window->Render();
    vtkNew<vtkHardwareSelector> selector;
    selector->SetRenderer(scene.Renderer);
    selector->SetFieldAssociation(association);
    selector->SetArea(0, 0, 159, 159);
    ASSERT_TRUE(selector->CaptureBuffers());
    for (unsigned int y = 20; y < 140; y += 10)
    {
      for (unsigned int x = 20; x < 140; x += 10)
      {
        const unsigned int position[2] = { x, y };
        unsigned int found[2];
        const auto info = selector->GetPixelInformation(position, 0, found);
        if (!info.Valid)
        {
          continue;
        }
        Vector3 origin;
        Vector3 direction;
        pixel_ray(scene.Renderer, int(x), int(y), origin, direction);
        const vtkIdType cpu =
          cpu_pick(reader->GetOutput(), vtkMesoAtomMapper::SPACE_FILLING, origin, direction);
        EXPECT_EQ(info.AttributeID, cpu) << "pixel " << x << ", " << y;
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 200);
}

TEST(MesoAtomMapper, PicksAtomsAndBondsInBallAndStick)
{
  EXPECT_GT(picking_agreement(vtkMesoAtomMapper::BALL_AND_STICK), 0.95);
}

TEST(MesoAtomMapper, PicksInputIdsWhenAtomsAreDrawnInCells)
{
  // Crambin in cells of 16 atoms: the buffers are in cell order, picking reports input ids.
  EXPECT_GT(picking_agreement(vtkMesoAtomMapper::SPACE_FILLING, 16), 0.97);
  EXPECT_GT(picking_agreement(vtkMesoAtomMapper::BALL_AND_STICK, 16), 0.95);
}

TEST(MesoAtomMapper, CullingSkipsHiddenCellsAndKeepsThePicture)
{
  auto block = carbon_block(30); // 27000 atoms: cells of 256
  CullingPair pair(block);
  vtkCamera* camera = pair.Culled.Renderer->GetActiveCamera();
  camera->Azimuth(30);
  camera->Elevation(20);
  for (int frame = 0; frame < 4; ++frame)
  {
    EXPECT_LT(pair.Render(), 5) << "frame " << frame; // of 40000 pixels: the same picture
    EXPECT_EQ(pair.Whole.Mapper->GetLastDrawnAtomCount(), 27000);
    // The first frames draw the nearest cells whole, then learn what shows: 3 faces of the
    // block, about 900 atoms each, and some of the layer below.
    EXPECT_LT(pair.Culled.Mapper->GetLastDrawnAtomCount(), frame < 2 ? 27000 / 2 : 27000 / 5)
      << "frame " << frame;
    EXPECT_GT(pair.Culled.Mapper->GetLastDrawnAtomCount(), 27000 / 20) << "frame " << frame;
    camera->Azimuth(10);
  }
  // Close up on a corner: the cells out of view are skipped too.
  const vtkIdType far = pair.Culled.Mapper->GetLastDrawnAtomCount();
  camera->Zoom(4);
  EXPECT_LT(pair.Render(), 5);
  EXPECT_LT(pair.Render(), 5); // the first frame still draws what the last one saw
  EXPECT_LT(pair.Culled.Mapper->GetLastDrawnAtomCount(), far / 2);
  // From inside the block, cells reach the eye and the near plane: drawn without a test.
  camera->SetPosition(20, 20, 20);
  camera->SetFocalPoint(40, 30, 35);
  EXPECT_LT(pair.Render(), 5);
  // Translucent atoms are all drawn.
  pair.Culled.Actor->GetProperty()->SetOpacity(0.5);
  pair.Whole.Actor->GetProperty()->SetOpacity(0.5);
  camera->SetPosition(-40, -30, -50);
  pair.Render();
  EXPECT_EQ(pair.Culled.Mapper->GetLastDrawnAtomCount(), 27000);
}

TEST(MesoAtomMapper, MultisampledWindowsDrawEveryAtomInView)
{
  // A multisampled depth buffer cannot be read back as it is: no atom is left out.
  auto block = carbon_block(21); // 9261 atoms: cells
  CullingPair pair(block);
  pair.Culled.Window->SetMultiSamples(4);
  pair.Whole.Window->SetMultiSamples(4);
  pair.Culled.Renderer->GetActiveCamera()->Azimuth(30);
  for (int frame = 0; frame < 2; ++frame)
  {
    EXPECT_LT(pair.Render(), 5);
    EXPECT_EQ(pair.Culled.Mapper->GetLastDrawnAtomCount(), 9261);
  }
}

TEST(MesoAtomMapper, CulledPictureIsExactForScatteredAtoms)
{
  // 12000 atoms at random in a slab, in cells of 8: many cells half hidden behind others, whose
  // atoms reach past their boxes of centres by their radius.
  auto atoms = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  vtkNew<vtkUnsignedCharArray> numbers;
  numbers->SetName(vtkMesoArrayNames::AtomicNumber);
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < 12000; ++i)
  {
    points->InsertNextPoint(80 * unit(random), 80 * unit(random), 12 * unit(random));
    numbers->InsertNextValue(i % 3 == 0 ? 16 : 6);
  }
  atoms->SetPoints(points);
  atoms->GetPointData()->AddArray(numbers);
  vtkMesoAtomTableConversion::SetAtomVertices(atoms);
  CullingPair pair(atoms);
  pair.Culled.Mapper->SetAtomsPerCell(8);
  vtkCamera* camera = pair.Culled.Renderer->GetActiveCamera();
  camera->Elevation(-50);
  for (int frame = 0; frame < 3; ++frame)
  {
    EXPECT_LT(pair.Render(), 5) << "frame " << frame;
    camera->Azimuth(25);
  }
  EXPECT_LT(pair.Culled.Mapper->GetLastDrawnAtomCount(), 12000);
  // A parallel projection, then a moved, turned and scaled actor.
  camera->ParallelProjectionOn();
  for (int frame = 0; frame < 2; ++frame)
  {
    EXPECT_LT(pair.Render(), 5) << "parallel frame " << frame;
  }
  camera->ParallelProjectionOff();
  for (vtkActor* actor : { pair.Culled.Actor.Get(), pair.Whole.Actor.Get() })
  {
    actor->SetScale(1.5);
    actor->RotateZ(30);
    actor->SetPosition(10, -5, 3);
  }
  pair.Culled.Renderer->ResetCamera();
  for (int frame = 0; frame < 2; ++frame)
  {
    EXPECT_LT(pair.Render(), 5) << "actor frame " << frame;
  }
}

TEST(MesoAtomMapper, CellsStayForANewFrameUntilTheAtomsSpread)
{
  auto block = carbon_block(24); // 13824 atoms
  const vtkIdType n = block->GetNumberOfPoints();
  CullingPair pair(block);
  pair.Culled.Renderer->GetActiveCamera()->Elevation(30);
  EXPECT_LT(pair.Render(), 5);
  // A small step: positions only (in the cells' order), the cells stay.
  vtkNew<vtkPoints> step;
  step->DeepCopy(block->GetPoints());
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    step->GetPoint(i, p);
    step->SetPoint(i, p[0] + 0.3, p[1], p[2] - 0.2);
  }
  block->SetPoints(step);
  EXPECT_LT(pair.Render(), 5);
  EXPECT_EQ(pair.Culled.Mapper->GetLastUploadBytes(), 12 * n);
  // Every other atom jumps 40 Å away: the cells are remade and the types follow the new order.
  vtkNew<vtkPoints> spread;
  spread->DeepCopy(block->GetPoints());
  for (vtkIdType i = 0; i < n; i += 2)
  {
    double p[3];
    spread->GetPoint(i, p);
    spread->SetPoint(i, p[0] + 40.0, p[1], p[2]);
  }
  block->SetPoints(spread);
  pair.Culled.Renderer->ResetCamera();
  EXPECT_LT(pair.Render(), 5);
  EXPECT_EQ(pair.Culled.Mapper->GetLastUploadBytes(), 14 * n);
  EXPECT_LT(pair.Culled.Mapper->GetLastDrawnAtomCount(), n);
}

TEST(MesoAtomMapper, FourteenBytesPerAtomAndOnlyPositionsForANewFrame)
{
  auto reader = mesolens_test::crambin();
  vtkNew<vtkPolyData> atoms;
  atoms->DeepCopy(reader->GetOutput());
  Scene scene = make_scene(atoms, vtkMesoAtomMapper::SPACE_FILLING);
  EXPECT_EQ(scene.Mapper->GetBufferBytesPerAtom(), 0.0);
  scene.Renderer->ResetCamera();
  scene.Window->Render();
  const vtkIdType n = atoms->GetNumberOfPoints();
  EXPECT_EQ(scene.Mapper->GetBufferBytesPerAtom(), 14.0);
  EXPECT_EQ(scene.Mapper->GetLastUploadBytes(), 14 * n + 8 * 337); // + the bonds' indices

  // A new time step: the same atoms elsewhere.
  vtkNew<vtkPoints> moved;
  moved->DeepCopy(atoms->GetPoints());
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    moved->GetPoint(i, p);
    moved->SetPoint(i, p[0] + 0.5, p[1], p[2]);
  }
  atoms->SetPoints(moved);
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetLastUploadBytes(), 12 * n);

  // Other elements: the types go up again, not the positions.
  vtkDataArray* numbers = atoms->GetPointData()->GetArray(vtkMesoArrayNames::AtomicNumber);
  numbers->SetComponent(0, 0, 26);
  numbers->Modified();
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetLastUploadBytes(), 2 * n);
}

namespace {
/// The atoms whose mask is non-zero, and the bonds between them.
vtkSmartPointer<vtkPolyData> visible_subset(vtkPolyData* atoms, const std::vector<bool>& visible)
{
  auto subset = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  vtkNew<vtkUnsignedCharArray> numbers;
  numbers->SetName(vtkMesoArrayNames::AtomicNumber);
  vtkDataArray* source = atoms->GetPointData()->GetArray(vtkMesoArrayNames::AtomicNumber);
  std::vector<vtkIdType> renumber(visible.size(), -1);
  for (vtkIdType a = 0; a < atoms->GetNumberOfPoints(); ++a)
  {
    if (visible[std::size_t(a)])
    {
      renumber[std::size_t(a)] = points->InsertNextPoint(atoms->GetPoint(a));
      numbers->InsertNextValue(static_cast<unsigned char>(source->GetTuple1(a)));
    }
  }
  subset->SetPoints(points);
  subset->GetPointData()->AddArray(numbers);
  vtkMesoAtomTableConversion::SetAtomVertices(subset);
  vtkNew<vtkCellArray> bonds;
  vtkNew<vtkIdList> ends;
  for (vtkIdType c = 0; atoms->GetLines() && c < atoms->GetLines()->GetNumberOfCells(); ++c)
  {
    atoms->GetLines()->GetCellAtId(c, ends);
    const vtkIdType a = renumber[std::size_t(ends->GetId(0))];
    const vtkIdType b = renumber[std::size_t(ends->GetId(1))];
    if (a >= 0 && b >= 0)
      bonds->InsertNextCell({ a, b });
  }
  subset->SetLines(bonds);
  return subset;
}

/// A `Visible` array on `atoms` from a mask; returns it.
vtkUnsignedCharArray* set_mask(vtkPolyData* atoms, const std::vector<bool>& visible)
{
  vtkNew<vtkUnsignedCharArray> mask;
  mask->SetName(vtkMesoArrayNames::Visible);
  for (bool v : visible)
    mask->InsertNextValue(v ? 1 : 0);
  atoms->GetPointData()->AddArray(mask);
  return mask;
}
} // namespace

TEST(MesoAtomMapper, VisibilityMaskHidesAtomsAndBondsWithoutNewPositions)
{
  auto reader = mesolens_test::crambin();
  vtkNew<vtkPolyData> atoms;
  atoms->DeepCopy(reader->GetOutput());
  const vtkIdType n = atoms->GetNumberOfPoints();
  std::vector<bool> visible(static_cast<std::size_t>(n));
  vtkIdType hidden = 0;
  for (vtkIdType a = 0; a < n; ++a)
  {
    visible[std::size_t(a)] = a % 3 != 0;
    hidden += a % 3 == 0;
  }
  vtkUnsignedCharArray* mask = set_mask(atoms, visible);
  // The masked atoms against the visible ones alone, in ball-and-stick (bonds to hidden atoms
  // must go too).
  Scene masked = make_scene(atoms, vtkMesoAtomMapper::BALL_AND_STICK);
  auto subset = visible_subset(atoms, visible);
  Scene alone = make_scene(subset, vtkMesoAtomMapper::BALL_AND_STICK);
  for (Scene* scene : { &masked, &alone })
    scene->Window->SetSize(160, 160);
  mesolens_test::look_at(masked.Renderer, atoms, 45.0);
  alone.Renderer->SetActiveCamera(masked.Renderer->GetActiveCamera());
  masked.Window->Render();
  alone.Window->Render();
  EXPECT_EQ(masked.Mapper->GetHiddenAtomCount(), hidden);
  EXPECT_LT(differing_pixels(capture(masked.Window), capture(alone.Window)), 5);
  // Unmasked, the picture differs: the test can tell.
  masked.Mapper->SetVisibilityArrayName(nullptr);
  masked.Window->Render();
  EXPECT_EQ(masked.Mapper->GetHiddenAtomCount(), 0);
  EXPECT_GT(differing_pixels(capture(masked.Window), capture(alone.Window)), 500);
  masked.Mapper->SetVisibilityArrayName(vtkMesoArrayNames::Visible);
  masked.Window->Render();

  // A new mask (a cutaway slider): the type bytes go up again, the positions do not.
  for (vtkIdType a = 0; a < n; ++a)
    mask->SetValue(a, a % 2);
  mask->Modified();
  masked.Window->Render();
  EXPECT_EQ(masked.Mapper->GetLastUploadBytes(), 2 * n);
  EXPECT_EQ(masked.Mapper->GetHiddenAtomCount(), n - n / 2);

  // Hidden atoms cannot be picked.
  vtkNew<vtkHardwareSelector> selector;
  selector->SetRenderer(masked.Renderer);
  selector->SetFieldAssociation(vtkDataObject::FIELD_ASSOCIATION_CELLS);
  selector->SetArea(0, 0, 159, 159);
  ASSERT_TRUE(selector->CaptureBuffers());
  int picked_atoms = 0;
  for (unsigned int y = 0; y < 160; y += 2)
    for (unsigned int x = 0; x < 160; x += 2)
    {
      const unsigned int position[2] = { x, y };
      unsigned int found[2];
      const auto info = selector->GetPixelInformation(position, 0, found);
      if (info.Valid && info.AttributeID < n)
      {
        ++picked_atoms;
        EXPECT_EQ(info.AttributeID % 2, 1) << "a hidden atom was picked";
      }
    }
  selector->ClearBuffers();
  EXPECT_GT(picked_atoms, 100);
}

TEST(MesoAtomMapper, SelectionDrawsOnlyTheAtomsItMatches)
{
  auto reader = mesolens_test::crambin();
  vtkNew<vtkPolyData> atoms;
  atoms->DeepCopy(reader->GetOutput());
  const vtkIdType n = atoms->GetNumberOfPoints();
  auto* residues = atoms->GetPointData()->GetArray(vtkMesoArrayNames::ResidueNumber);
  std::vector<bool> in_selection(static_cast<std::size_t>(n));
  for (vtkIdType a = 0; a < n; ++a)
    in_selection[std::size_t(a)] = residues->GetTuple1(a) <= 10.0;
  Scene selected = make_scene(atoms, vtkMesoAtomMapper::BALL_AND_STICK);
  Scene alone = make_scene(visible_subset(atoms, in_selection), vtkMesoAtomMapper::BALL_AND_STICK);
  for (Scene* scene : { &selected, &alone })
    scene->Window->SetSize(160, 160);
  mesolens_test::look_at(selected.Renderer, atoms, 45.0);
  alone.Renderer->SetActiveCamera(selected.Renderer->GetActiveCamera());
  selected.Mapper->SetAtomSelection("resid 1-10");
  selected.Window->Render();
  alone.Window->Render();
  EXPECT_EQ(selected.Mapper->GetHiddenAtomCount(), n - 70);
  EXPECT_LT(differing_pixels(capture(selected.Window), capture(alone.Window)), 5);
  // With a visibility mask as well, an atom shows when both keep it.
  std::vector<bool> visible(static_cast<std::size_t>(n));
  vtkIdType shown = 0;
  for (vtkIdType a = 0; a < n; ++a)
  {
    visible[std::size_t(a)] = a % 2 == 0;
    shown += visible[std::size_t(a)] && in_selection[std::size_t(a)];
  }
  set_mask(atoms, visible);
  selected.Window->Render();
  EXPECT_EQ(selected.Mapper->GetHiddenAtomCount(), n - shown);
  // A bad selection is an error and draws nothing; none draws every atom the mask keeps.
  mesolens_test::EventRecorder events(selected.Mapper);
  selected.Mapper->SetAtomSelection("resid 1-10 and (name CA");
  selected.Window->Render();
  EXPECT_EQ(selected.Mapper->GetHiddenAtomCount(), n);
  EXPECT_NE(events.AllErrors().find("no atom is drawn"), std::string::npos) << events.AllErrors();
  selected.Mapper->SetAtomSelection("");
  selected.Window->Render();
  EXPECT_EQ(selected.Mapper->GetHiddenAtomCount(), n - (n + 1) / 2);
}

TEST(MesoAtomMapper, VisibilityMaskWithCulling)
{
  // Half a 27 000-atom block hidden (x below the middle), drawn in culling cells: the same
  // picture as the visible half alone, from several sides.
  auto block = carbon_block(30);
  std::vector<bool> visible(27000);
  for (vtkIdType a = 0; a < 27000; ++a)
    visible[std::size_t(a)] = block->GetPoint(a)[0] > 21.0;
  set_mask(block, visible);
  CullingPair pair(block);
  pair.Whole.Mapper->SetInputData(visible_subset(block, visible));
  vtkCamera* camera = pair.Culled.Renderer->GetActiveCamera();
  camera->Azimuth(-60);
  for (int frame = 0; frame < 4; ++frame)
  {
    EXPECT_LT(pair.Render(), 5) << "frame " << frame;
    EXPECT_EQ(pair.Culled.Mapper->GetHiddenAtomCount(),
              27000 - pair.Whole.Mapper->GetInput()->GetNumberOfPoints());
    camera->Azimuth(50);
  }
}

TEST(MesoAtomMapper, BoundsIncludeTheRadii)
{
  auto reader = mesolens_test::crambin();
  vtkNew<vtkMesoAtomMapper> mapper;
  mapper->SetInputConnection(reader->GetOutputPort());
  double atoms[6];
  reader->GetOutput()->GetBounds(atoms);
  double drawn[6];
  mapper->GetBounds(drawn);
  // Crambin's largest atom is sulfur, 1.8 Å.
  for (int d = 0; d < 3; ++d)
  {
    EXPECT_NEAR(drawn[2 * d], atoms[2 * d] - 1.8, 1e-5);
    EXPECT_NEAR(drawn[2 * d + 1], atoms[2 * d + 1] + 1.8, 1e-5);
  }
  mapper->SetStyleToSticks();
  mapper->GetBounds(drawn);
  EXPECT_NEAR(drawn[0], atoms[0] - 0.2, 1e-5);
}

TEST(MesoAtomMapper, ParametersStayInRange)
{
  vtkNew<vtkMesoAtomMapper> mapper;
  mapper->SetBallScale(5);
  EXPECT_EQ(mapper->GetBallScale(), 1.0);
  mapper->SetBondRadius(-1);
  EXPECT_EQ(mapper->GetBondRadius(), 1e-3);
  mapper->SetStyle(7);
  EXPECT_EQ(mapper->GetStyle(), vtkMesoAtomMapper::STICKS);
  mapper->SetRadiusScale(0);
  EXPECT_GT(mapper->GetRadiusScale(), 0.0);
}

TEST(MesoAtomMapper, EmptyInputDrawsNothing)
{
  vtkNew<vtkPolyData> empty;
  Scene scene = make_scene(empty, vtkMesoAtomMapper::BALL_AND_STICK);
  scene.Window->Render();
  EXPECT_FALSE(drew_something(scene.Window));
  EXPECT_EQ(scene.Mapper->GetBufferBytesPerAtom(), 0.0);
}

TEST(MesoAtomMapper, AtomsWithoutElementsAreGreyBeads)
{
  auto atoms = two_atoms();
  Scene scene = make_scene(atoms, vtkMesoAtomMapper::SPACE_FILLING);
  mesolens_test::EventRecorder events(scene.Mapper);
  scene.Renderer->ResetCamera();
  scene.Window->Render();
  EXPECT_TRUE(events.Errors.empty());
  EXPECT_TRUE(drew_something(scene.Window));
  double bounds[6];
  scene.Mapper->GetBounds(bounds);
  EXPECT_NEAR(bounds[0], -1.0, 1e-6); // radius 1 for beads
}

TEST(MesoAtomMapper, NonFinitePositionIsAnErrorAndDrawsNothing)
{
  auto atoms = two_atoms();
  atoms->GetPoints()->SetPoint(1, std::nan(""), 0, 0);
  Scene scene = make_scene(atoms, vtkMesoAtomMapper::SPACE_FILLING);
  mesolens_test::EventRecorder events(scene.Mapper);
  scene.Renderer->GetActiveCamera()->SetPosition(0, 0, 10);
  scene.Renderer->GetActiveCamera()->SetFocalPoint(0, 0, 0);
  scene.Window->Render();
  EXPECT_NE(events.AllErrors().find("non-finite"), std::string::npos) << events.AllErrors();
  EXPECT_FALSE(drew_something(scene.Window));
}

TEST(MesoAtomMapper, BondToAMissingAtomIsAnError)
{
  auto atoms = two_atoms();
  atoms->GetLines()->InsertNextCell({ 1, 5 });
  Scene scene = make_scene(atoms, vtkMesoAtomMapper::BALL_AND_STICK);
  mesolens_test::EventRecorder events(scene.Mapper);
  scene.Renderer->GetActiveCamera()->SetPosition(0, 0, 10);
  scene.Renderer->GetActiveCamera()->SetFocalPoint(0, 0, 0);
  scene.Window->Render();
  EXPECT_NE(events.AllErrors().find("refers to atom 5 of 2"), std::string::npos)
    << events.AllErrors();
  EXPECT_FALSE(drew_something(scene.Window));
}

TEST(MesoAtomMapper, WarpInputMustComeFromTheMembraneMapping)
{
  auto atoms = two_atoms();
  vtkNew<vtkPolyData> not_a_warp;
  Scene scene = make_scene(atoms, vtkMesoAtomMapper::SPACE_FILLING);
  scene.Mapper->SetInputDataObject(1, not_a_warp);
  mesolens_test::EventRecorder events(scene.Mapper);
  scene.Renderer->GetActiveCamera()->SetPosition(0, 0, 10);
  scene.Renderer->GetActiveCamera()->SetFocalPoint(0, 0, 0);
  scene.Window->Render();
  EXPECT_NE(events.AllErrors().find("not the output of a vtkMesoMembraneMapping"),
            std::string::npos)
    << events.AllErrors();
  EXPECT_FALSE(drew_something(scene.Window));
}

TEST(MesoAtomMapper, WarpNeedsThePatchNotTheMappedAtoms)
{
  auto mapped = mesolens_test::mapped_membrane(vtkMesoMembraneMapping::POLYNOMIAL, true);
  Scene scene = make_scene(mapped, vtkMesoAtomMapper::SPACE_FILLING);
  scene.Mapper->SetWarpConnection(mapped->GetOutputPort());
  mesolens_test::EventRecorder events(scene.Mapper);
  scene.Renderer->ResetCamera();
  scene.Window->Render();
  EXPECT_NE(events.AllErrors().find("must be the membrane patch"), std::string::npos)
    << events.AllErrors();
}

namespace {
/// Copies of an asymmetric unit: one per translation (Å, along x), all of the set `rows`.
vtkSmartPointer<vtkPolyData> assembly_copies(const std::vector<double>& shifts,
                                             const std::vector<std::uint32_t>& rows)
{
  mesolens::AssemblyInstances instances;
  instances.atom_sets.resize(1);
  instances.atom_sets[0].atoms = rows;
  for (const double shift : shifts)
  {
    mesolens::AssemblyInstance copy;
    copy.matrix[3] = shift;
    copy.center = { shift, 0, 0 };
    copy.radius = 2;
    instances.instances.push_back(copy);
  }
  auto copies = vtkSmartPointer<vtkPolyData>::New();
  vtkMesoAssemblyInstances::Write(instances, copies);
  return copies;
}
} // namespace

TEST(MesoAtomMapper, AssemblyCopiesAreDrawnWhereTheirMatricesPutThem)
{
  Scene scene = make_scene(two_atoms(), vtkMesoAtomMapper::SPACE_FILLING);
  scene.Mapper->SetInputDataObject(1, assembly_copies({ 0.0, 10.0, -20.0 }, { 0, 1 }));
  mesolens_test::EventRecorder events(scene.Mapper);
  double bounds[6];
  scene.Mapper->GetBounds(bounds);
  const double r = 1.0; // beads without elements
  EXPECT_NEAR(bounds[0], -20.0 - r, 1e-6);
  EXPECT_NEAR(bounds[1], 11.5 + r, 1e-6);
  scene.Renderer->ResetCamera();
  scene.Window->Render();
  EXPECT_TRUE(events.AllErrors().empty()) << events.AllErrors();
  EXPECT_TRUE(drew_something(scene.Window));
  EXPECT_EQ(scene.Mapper->GetLastDrawnAtomCount(), 6);
  EXPECT_EQ(scene.Mapper->GetHiddenAtomCount(), 0);
  EXPECT_DOUBLE_EQ(scene.Mapper->GetBufferBytesPerAtom(), 16.0);
  // A set of atom 1 alone: atom 0 is hidden in every copy.
  scene.Mapper->SetInputDataObject(1, assembly_copies({ 0.0, 10.0, -20.0 }, { 1 }));
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetHiddenAtomCount(), 3);
}

TEST(MesoAtomMapper, AssemblyCopiesOfAnotherUnitAreAnError)
{
  // Copies made for a unit of three atoms, drawn over two; then a copy with a matrix that is no
  // number; then copies that lost their arrays.
  Scene scene = make_scene(two_atoms(), vtkMesoAtomMapper::SPACE_FILLING);
  scene.Renderer->GetActiveCamera()->SetPosition(0, 0, 10);
  scene.Renderer->GetActiveCamera()->SetFocalPoint(0, 0, 0);
  mesolens_test::EventRecorder events(scene.Mapper);
  scene.Mapper->SetInputDataObject(1, assembly_copies({ 0.0, 10.0 }, { 0, 1, 2 }));
  scene.Window->Render();
  EXPECT_NE(events.AllErrors().find("another asymmetric unit"), std::string::npos)
    << events.AllErrors();
  EXPECT_FALSE(drew_something(scene.Window));

  auto not_a_number = assembly_copies({ 0.0, 10.0 }, { 0, 1 });
  not_a_number->GetPointData()
    ->GetArray(vtkMesoArrayNames::AssemblyMatrix)
    ->SetComponent(1, 5, std::nan(""));
  scene.Mapper->SetInputDataObject(1, not_a_number);
  scene.Window->Render();
  EXPECT_NE(events.AllErrors().find("copy 1's matrix is not finite"), std::string::npos)
    << events.AllErrors();
  EXPECT_FALSE(drew_something(scene.Window));

  auto damaged = assembly_copies({ 0.0 }, { 0, 1 });
  damaged->GetFieldData()->RemoveArray(vtkMesoArrayNames::AssemblyAtomSetAtoms);
  scene.Mapper->SetInputDataObject(1, damaged);
  scene.Window->Render();
  EXPECT_NE(events.AllErrors().find("not a vtkMesoStructureReader's output 1"), std::string::npos)
    << events.AllErrors();
  EXPECT_FALSE(drew_something(scene.Window));
}

namespace {
/// The GPU-warped bounds hold the atoms mapped on the CPU, and not much more.
void expect_bounds_cover(vtkMesoAtomMapper* mapper, vtkPolyData* mapped_atoms)
{
  double mapped[6];
  mapped_atoms->GetBounds(mapped);
  double drawn[6];
  mapper->GetBounds(drawn);
  for (int d = 0; d < 3; ++d)
  {
    EXPECT_LE(drawn[2 * d], mapped[2 * d]);
    EXPECT_GE(drawn[2 * d + 1], mapped[2 * d + 1]);
    EXPECT_LT(drawn[2 * d + 1] - drawn[2 * d], 1.5 * (mapped[2 * d + 1] - mapped[2 * d]));
  }
}
} // namespace

TEST(MesoAtomMapper, InstancingWarpTakesSixteenBytesPerAtom)
{
  auto mapping = mesolens_test::mapped_membrane(vtkMesoMembraneMapping::MOLECULE_INSTANCING, false);
  EXPECT_EQ(mapping->GetOutput()->GetNumberOfPoints(), 4 * 128); // the molecules' centres
  Scene scene = make_scene(mapping, vtkMesoAtomMapper::SPACE_FILLING, 64);
  scene.Mapper->SetInputConnection(mapping->GetInputConnection(1, 0));
  scene.Mapper->SetWarpConnection(mapping->GetOutputPort());
  scene.Mapper->SetRadiusScale(1e-4);
  mesolens_test::EventRecorder events(scene.Mapper);
  scene.Renderer->ResetCamera();
  scene.Window->Render();
  EXPECT_TRUE(events.Errors.empty()) << events.AllErrors();
  EXPECT_EQ(scene.Mapper->GetBufferBytesPerAtom(), 16.0);
  EXPECT_TRUE(drew_something(scene.Window));
  // The warped bounds cover the 2 x 2 tiles mapped on the CPU.
  auto cpu = mesolens_test::mapped_membrane(vtkMesoMembraneMapping::MOLECULE_INSTANCING, true);
  expect_bounds_cover(scene.Mapper, cpu->GetOutput());
}

TEST(MesoAtomMapper, SplitPolynomialWarpBoundsCoverTheMappedAtoms)
{
  // A bound of 0.2 Å splits every tile into pieces; the GPU's bounds follow the pieces.
  auto mapping = mesolens_test::mapped_membrane(vtkMesoMembraneMapping::POLYNOMIAL, false, 0.2);
  vtkDataArray* splits =
    mapping->GetOutput()->GetFieldData()->GetArray(vtkMesoArrayNames::PolynomialSplits);
  ASSERT_NE(splits, nullptr);
  ASSERT_EQ(splits->GetNumberOfTuples(), 4);
  EXPECT_GE(splits->GetRange()[1], 2.0);
  Scene scene = make_scene(mapping, vtkMesoAtomMapper::SPACE_FILLING, 64);
  scene.Mapper->SetInputConnection(mapping->GetInputConnection(1, 0));
  scene.Mapper->SetWarpConnection(mapping->GetOutputPort());
  scene.Mapper->SetRadiusScale(1e-4);
  mesolens_test::EventRecorder events(scene.Mapper);
  scene.Renderer->ResetCamera();
  scene.Window->Render();
  EXPECT_TRUE(events.Errors.empty()) << events.AllErrors();
  auto cpu = mesolens_test::mapped_membrane(vtkMesoMembraneMapping::POLYNOMIAL, true, 0.2);
  expect_bounds_cover(scene.Mapper, cpu->GetOutput());
}

TEST(MesoAtomMapper, CullingAWarpedPatchKeepsThePicture)
{
  // 2 x 2 tiles of the DPPC patch warped on the GPU, culled by the patch's cells carried into
  // every tile, against every atom drawn.
  for (const int method :
       { vtkMesoMembraneMapping::POLYNOMIAL, vtkMesoMembraneMapping::MOLECULE_INSTANCING })
  {
    auto mapping = mesolens_test::mapped_membrane(method, false);
    vtkDataObject* patch = mapping->GetInputDataObject(1, 0);
    const vtkIdType all = 4 * vtkPolyData::SafeDownCast(patch)->GetNumberOfPoints();
    CullingPair pair(vtkPolyData::SafeDownCast(patch));
    for (Scene* scene : { &pair.Culled, &pair.Whole })
    {
      scene->Mapper->SetWarpConnection(mapping->GetOutputPort());
      scene->Mapper->SetRadiusScale(1e-4);
    }
    mesolens_test::EventRecorder events(pair.Culled.Mapper);
    pair.Culled.Renderer->ResetCamera();
    vtkCamera* camera = pair.Culled.Renderer->GetActiveCamera();
    camera->Elevation(-35);
    for (int frame = 0; frame < 4; ++frame)
    {
      EXPECT_LT(pair.Render(), 5) << "method " << method << " frame " << frame;
      EXPECT_EQ(pair.Whole.Mapper->GetLastDrawnAtomCount(), all);
      // The first frame draws the nearest cells whole, then learns what shows.
      EXPECT_LT(pair.Culled.Mapper->GetLastDrawnAtomCount(), frame == 0 ? all * 3 / 4 : all / 2)
        << "method " << method << " frame " << frame;
      EXPECT_GT(pair.Culled.Mapper->GetLastDrawnAtomCount(), all / 50);
      camera->Azimuth(25);
    }
    // Close up: tiles out of view are skipped as well.
    camera->Zoom(5);
    EXPECT_LT(pair.Render(), 5);
    EXPECT_LT(pair.Render(), 5);
    EXPECT_TRUE(events.Errors.empty()) << events.AllErrors();
    // Translucent atoms are all drawn.
    pair.Culled.Actor->GetProperty()->SetOpacity(0.5);
    pair.Whole.Actor->GetProperty()->SetOpacity(0.5);
    pair.Render();
    EXPECT_EQ(pair.Culled.Mapper->GetLastDrawnAtomCount(), all);
  }
}

TEST(MesoAtomMapper, CutawayOnTheGPUPathHidesWhatItHidesOnTheCPU)
{
  for (const int method :
       { vtkMesoMembraneMapping::POLYNOMIAL, vtkMesoMembraneMapping::MOLECULE_INSTANCING })
  {
    mesolens_test::CutMembrane cpu(method, false);
    mesolens_test::CutMembrane gpu(method, true);
    cpu.Cutaway->Update();
    gpu.Cutaway->Update();
    // The same decisions: per molecule and tile on the GPU path, per atom on the CPU path.
    vtkPolyData* atoms = cpu.Cutaway->GetOutput();
    vtkPolyData* molecules = gpu.Cutaway->GetOutput();
    ASSERT_EQ(molecules->GetNumberOfPoints(), 4 * 128);
    vtkDataArray* atom_visible = atoms->GetPointData()->GetArray(vtkMesoArrayNames::Visible);
    vtkDataArray* molecule_visible =
      molecules->GetPointData()->GetArray(vtkMesoArrayNames::Visible);
    ASSERT_NE(atom_visible, nullptr);
    ASSERT_NE(molecule_visible, nullptr);
    const vtkIdType per_tile = atoms->GetNumberOfPoints() / 4;
    const vtkIdType atoms_per_molecule = per_tile / 128; // DPPC: 130 atoms each
    vtkIdType hidden = 0;
    for (vtkIdType a = 0; a < atoms->GetNumberOfPoints(); ++a)
    {
      const vtkIdType molecule = a / per_tile * 128 + (a % per_tile) / atoms_per_molecule;
      ASSERT_EQ(atom_visible->GetComponent(a, 0), molecule_visible->GetComponent(molecule, 0))
        << "atom " << a;
      hidden += atom_visible->GetComponent(a, 0) == 0 ? 1 : 0;
    }
    EXPECT_GT(hidden, atoms->GetNumberOfPoints() / 10);

    // Drawn: the GPU path hides as many atoms, and a slider step uploads the mask alone.
    Scene scene = empty_scene(vtkMesoAtomMapper::SPACE_FILLING, 120);
    scene.Actor->SetMapper(gpu.Mapper);
    mesolens_test::EventRecorder events(gpu.Mapper);
    scene.Renderer->ResetCamera();
    scene.Window->Render();
    EXPECT_TRUE(events.Errors.empty()) << events.AllErrors();
    EXPECT_TRUE(drew_something(scene.Window));
    EXPECT_EQ(gpu.Mapper->GetHiddenAtomCount(), hidden);
    gpu.Cutaway->SetFractionHidden(0.3);
    scene.Window->Render();
    EXPECT_EQ(gpu.Mapper->GetLastUploadBytes(), 4 * ((4 * 128 + 31) / 32));
    EXPECT_LT(gpu.Mapper->GetHiddenAtomCount(), hidden);
  }
}
