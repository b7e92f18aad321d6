// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoAtomMapper.h"

#include "vtkMesoArrayNames.h"

#include "vtkMesoAtomGPUData.h"
#include "vtkMesoParallelFor.h"
#include "vtkMesoSelectAtoms.h"

#include "vtkMesoAtomColorFS.h"
#include "vtkMesoAtomSphereFSDec.h"
#include "vtkMesoAtomSphereFSImpl.h"
#include "vtkMesoAtomSphereVS.h"
#include "vtkMesoBondCylinderFSDec.h"
#include "vtkMesoBondCylinderFSImpl.h"
#include "vtkMesoBondCylinderGS.h"
#include "vtkMesoBondVS.h"
#include "vtkMesoMoleculeInstancingVS.h"
#include "vtkMesoPolynomialWarpVS.h"

#include "mesolens/common/errors.h"
#include "mesolens/mapping/mapping_method.h"
#include "mesolens/mapping/warped_cells.h"
#include "mesolens/render/atom_cells.h"
#include "mesolens/render/depth_pyramid.h"
#include "mesolens/render/first_occluders.h"

#include <vtkFloatArray.h>
#include <vtkOpenGLActor.h>
#include <vtkOpenGLState.h>
#include <vtkAlgorithmOutput.h>
#include <vtkExecutive.h>
#include <vtkInformation.h>
#include <vtkMatrix4x4.h>
#include <vtkObjectFactory.h>
#include <vtkOpenGLBufferObject.h>
#include <vtkOpenGLCamera.h>
#include <vtkOpenGLHelper.h>
#include <vtkOpenGLIndexBufferObject.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLVertexArrayObject.h>
#include <vtkPolyData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkPointData.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>

#include <vtk_glew.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <tuple>

vtkStandardNewMacro(vtkMesoAtomMapper);

namespace {
enum class Pass
{
  Atoms,
  Bonds
};

/// With automatic cells, inputs smaller than this are drawn whole: culling would not pay for its
/// queries.
constexpr vtkIdType minimum_culled_atoms = 8192;

void set_uniform_int(vtkShaderProgram* program, const char* name, int value)
{
  if (program->IsUniformUsed(name))
  {
    program->SetUniformi(name, value);
  }
}

void set_uniform_float(vtkShaderProgram* program, const char* name, float value)
{
  if (program->IsUniformUsed(name))
  {
    program->SetUniformf(name, value);
  }
}

/// The actor's model to clip coordinates through the renderer's camera, as the shaders see it
/// (VTK keeps its matrices transposed).
mesolens::ViewTransform model_view(vtkRenderer* ren, vtkActor* act)
{
  vtkMatrix4x4* wcvc = nullptr;
  vtkMatrix3x3* normals = nullptr;
  vtkMatrix4x4* vcdc = nullptr;
  vtkMatrix4x4* wcdc = nullptr;
  static_cast<vtkOpenGLCamera*>(ren->GetActiveCamera())
    ->GetKeyMatrices(ren, wcvc, normals, vcdc, wcdc);
  vtkNew<vtkMatrix4x4> mcvc;
  mcvc->DeepCopy(wcvc);
  if (!act->GetIsIdentity())
  {
    vtkMatrix4x4* mcwc = nullptr;
    vtkMatrix3x3* actor_normals = nullptr;
    static_cast<vtkOpenGLActor*>(act)->GetKeyMatrices(mcwc, actor_normals);
    vtkMatrix4x4::Multiply4x4(mcwc, wcvc, mcvc);
  }
  mesolens::ViewTransform view;
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      view.model_to_view[4 * r + c] = mcvc->GetElement(c, r);
      view.view_to_clip[4 * r + c] = vcdc->GetElement(c, r);
    }
  }
  view.Complete();
  return view;
}

/// A texture buffer of RGBA float texels and the buffer object behind it.
struct TexelBuffer
{
  vtkNew<vtkOpenGLBufferObject> Buffer;
  vtkNew<vtkTextureObject> Texture;
  unsigned long UploadedVersion = 0; // the texels' version on the GPU, 0: none

  void Upload(vtkOpenGLRenderWindow* window, const std::vector<float>& texels,
              unsigned long version)
  {
    if (version == this->UploadedVersion && this->Texture->GetHandle() != 0)
    {
      return;
    }
    this->Texture->SetContext(window);
    this->Buffer->SetType(vtkOpenGLBufferObject::TextureBuffer);
    this->Buffer->Upload(texels, vtkOpenGLBufferObject::TextureBuffer);
    this->Texture->CreateTextureBuffer(static_cast<unsigned int>(texels.size() / 4), 4, VTK_FLOAT,
                                       this->Buffer);
    this->UploadedVersion = version;
  }

  void Release(vtkWindow* window)
  {
    this->Texture->ReleaseGraphicsResources(window);
    this->Buffer->ReleaseGraphicsResources();
    this->UploadedVersion = 0;
  }
};
} // namespace

/// What a camera saw in its last frame: per atom (slot) the mesolens::AtomVisibility bits, per
/// cell whether any of its atoms was seen.
struct ViewHistory
{
  unsigned long CellsVersion = 0;
  std::vector<std::uint8_t> Flags;
  std::vector<std::uint8_t> Seen;
};

/// The mapper's AtomSelection as a mask: a vtkMesoSelectAtoms of the input, its mask combined with
/// the input's visibility mask; kept while the input, the text and the mask name stay.
class SelectionMask
{
public:
  static constexpr const char* MaskName = "MesoLensAtomMapperSelection";

  /// The input with the combined mask array MaskName (every atom hidden after an error, which
  /// `mapper` reports), or `input` itself when `selection` is empty.
  vtkPolyData* Apply(vtkPolyData* input, const std::string& selection, const char* visibility,
                     vtkMapper* mapper)
  {
    if (selection.empty() || !input)
    {
      return input;
    }
    const std::string mask_name = visibility ? visibility : "";
    if (input == this->Input && input->GetMTime() == this->InputTime && selection == this->Text &&
        mask_name == this->Visibility)
    {
      return this->Output;
    }
    this->Input = input;
    this->InputTime = input->GetMTime();
    this->Text = selection;
    this->Visibility = mask_name;
    this->Select->SetInputData(input);
    this->Select->SetSelection(selection.c_str());
    this->Select->SetMaskArrayName(MaskName);
    this->Output = vtkSmartPointer<vtkPolyData>::New();
    vtkNew<vtkUnsignedCharArray> mask;
    if (this->Select->GetExecutive()->Update())
    {
      this->Output->ShallowCopy(this->Select->GetOutput());
      mask->DeepCopy(this->Output->GetPointData()->GetArray(MaskName));
    }
    else
    {
      vtkErrorWithObjectMacro(mapper,
                              "Selection \"" << selection
                                             << "\" failed (see the error above): "
                                                "no atom is drawn");
      this->Output->ShallowCopy(input);
      mask->SetNumberOfValues(input->GetNumberOfPoints());
      mask->FillValue(0);
    }
    mask->SetName(MaskName);
    vtkDataArray* visible =
      mask_name.empty() ? nullptr : input->GetPointData()->GetArray(mask_name.c_str());
    for (vtkIdType i = 0; visible && i < mask->GetNumberOfValues(); ++i)
    {
      mask->SetValue(i, mask->GetValue(i) && visible->GetComponent(i, 0) != 0.0 ? 1 : 0);
    }
    this->Output->GetPointData()->AddArray(mask);
    return this->Output;
  }

private:
  vtkNew<vtkMesoSelectAtoms> Select;
  vtkPolyData* Input = nullptr;
  vtkMTimeType InputTime = 0;
  std::string Text;
  std::string Visibility;
  vtkSmartPointer<vtkPolyData> Output;
};

struct vtkMesoAtomMapper::Internals
{
  vtkMesoAtomGPUData Data;
  SelectionMask Selected;
  vtkNew<vtkOpenGLBufferObject> Positions;
  vtkNew<vtkOpenGLBufferObject> Types;
  vtkNew<vtkOpenGLBufferObject> Molecules;
  // The atom buffers seen as texture buffers by the sphere pass (vertex pulling).
  vtkNew<vtkTextureObject> PositionTexture;
  vtkNew<vtkTextureObject> TypeTexture;
  vtkNew<vtkTextureObject> MoleculeTexture;
  unsigned long UploadedTypes = 0;     // TypesVersion on the GPU, 0: none
  unsigned long UploadedPositions = 0; // PositionsVersion on the GPU, 0: none
  unsigned long UploadedMolecules = 0; // WarpVersion of the molecule slots on the GPU
  unsigned long UploadedBonds = 0;
  TexelBuffer Colors;
  TexelBuffer Warp;
  // Culling: the slots of the atoms drawn first, and of those drawn after the test (4 bytes
  // per drawn atom, as R32UI texture buffers).
  std::array<vtkNew<vtkOpenGLBufferObject>, 2> DrawLists;
  std::array<vtkNew<vtkTextureObject>, 2> DrawListTextures;
  std::vector<std::uint32_t> DrawList;
  std::size_t DrawListBytes = 0;
  std::vector<float> Depth; // culling: the depth image read back
  mesolens::DepthPyramid Pyramid;
  vtkNew<vtkOpenGLBufferObject> Slots;  // picking: the slot of each input atom
  vtkNew<vtkTextureObject> SlotTexture; // ... as an R32UI texture buffer
  unsigned long UploadedSlots = 0;      // CellsVersion of the slots on the GPU, 0: none
  vtkIdType LastDrawnAtoms = 0;
  vtkTimeStamp BufferTime;    // the buffers behind the vertex attributes changed
  vtkTimeStamp ShaderKeyTime; // the warp method or the grouping into cells changed
  int ShaderWarpMethod = -1;
  bool ShaderMask = false; // the shaders read a molecule mask
  // The molecule mask of a warped patch (vtkMesoAtomGPUData::MoleculeMask), R32UI texels.
  vtkNew<vtkOpenGLBufferObject> MaskBuffer;
  vtkNew<vtkTextureObject> MaskTexture;
  unsigned long UploadedMask = 0;
  vtkIdType LastUploadBytes = 0;
  double Bounds[6] = { 0, 0, 0, 0, 0, 0 }; // the last ComputeBounds
  vtkMTimeType BoundsTime = 0;             // of the inputs and settings at this time
  Pass Current = Pass::Atoms;
  bool Inverted = false;
  // Keyed by renderer and viewport size: a shadow map (another size) keeps its own; cameras
  // are no key, as VTK renders through temporary copies of them (image capture). The renderer
  // is only compared, never dereferenced: a stale entry costs time, not pixels.
  using ViewKey = std::tuple<const vtkRenderer*, int, int>;
  std::map<ViewKey, ViewHistory> Histories;

  ViewHistory& History(const ViewKey& key, unsigned long version, std::size_t atoms,
                       std::size_t cells)
  {
    if (this->Histories.size() > 16 && !this->Histories.count(key))
    {
      this->Histories.clear();
    }
    ViewHistory& history = this->Histories[key];
    if (history.CellsVersion != version || history.Flags.size() != atoms ||
        history.Seen.size() != cells)
    {
      history = ViewHistory{ version, std::vector<std::uint8_t>(atoms, 0),
                             std::vector<std::uint8_t>(cells, 0) };
    }
    return history;
  }

  /// Puts `slots` in draw list `which` and its texture.
  void UploadDrawList(vtkOpenGLRenderWindow* window, int which,
                      const std::vector<std::uint32_t>& slots)
  {
    this->DrawLists[which]->Upload(slots, vtkOpenGLBufferObject::TextureBuffer);
    vtkTextureObject* texture = this->DrawListTextures[which];
    texture->SetContext(window);
    texture->SetInternalFormat(GL_R32UI);
    texture->CreateTextureBuffer(static_cast<unsigned int>(slots.size()), 1, VTK_UNSIGNED_INT,
                                 this->DrawLists[which]);
  }

  /// Draws, through draw list `which`, the atoms of the listed cells whose visibility bits
  /// include `bit` (the sphere program `spheres` bound): slot s of `atoms` is drawn as list
  /// entry s, the atom in buffer slot s mod n of tile s / n (n atoms). Returns how many.
  std::size_t DrawAtoms(vtkOpenGLRenderWindow* window, vtkShaderProgram* spheres, int which,
                        const mesolens::CellAtoms& atoms, const std::vector<std::uint8_t>& flags,
                        std::uint8_t bit, const std::vector<mesolens::CellInView>& cells,
                        const std::vector<std::uint8_t>& cell_listed)
  {
    const auto n = static_cast<std::uint32_t>(this->Data.AtomCount);
    this->DrawList.clear();
    for (const mesolens::CellInView& viewed : cells)
    {
      if (!cell_listed[viewed.cell])
      {
        continue;
      }
      // A cell's slots lie in one tile: slot = tile n + buffer slot.
      const std::uint32_t first = atoms.first_slot(viewed.cell);
      const std::uint32_t end = atoms.first_slot(std::size_t(viewed.cell) + 1);
      const std::uint32_t tile = first / n;
      const std::uint32_t base = tile * n;
      for (std::uint32_t slot = first; slot < end; ++slot)
      {
        if ((flags[slot] & bit) &&
            this->Data.Types[2 * (slot - base)] != vtkMesoAtomGPUData::HiddenElement &&
            !this->MoleculeHidden(tile, slot - base))
        {
          this->DrawList.push_back(slot);
        }
      }
    }
    return this->DrawListed(window, spheres, which);
  }

  /// Whether the molecule mask hides the atom in buffer slot `atom` in `tile`.
  bool MoleculeHidden(std::uint32_t tile, std::uint32_t atom) const
  {
    const std::vector<std::uint32_t>& mask = this->Data.MoleculeMask;
    if (mask.empty())
    {
      return false;
    }
    const std::size_t molecule =
      std::size_t(tile) * std::size_t(this->Data.MoleculesPerTile) + this->Data.MoleculeSlots[atom];
    return ((mask[molecule / 32] >> (molecule % 32)) & 1u) != 0;
  }

  /// Draws the atoms of DrawList (entries t n + slot: the atom in that slot, in tile t of a
  /// warp) through draw list `which`. Returns how many.
  std::size_t DrawListed(vtkOpenGLRenderWindow* window, vtkShaderProgram* spheres, int which)
  {
    this->DrawListBytes += sizeof(std::uint32_t) * this->DrawList.size();
    if (this->DrawList.empty())
    {
      return 0;
    }
    this->UploadDrawList(window, which, this->DrawList);
    vtkTextureObject* texture = this->DrawListTextures[which];
    texture->Activate();
    spheres->SetUniformi("atomDrawList", texture->GetTextureUnit());
    spheres->SetUniformi("useDrawList", 1);
    spheres->SetUniformi("drawListAtoms", static_cast<int>(this->Data.AtomCount));
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(3 * this->DrawList.size()));
    spheres->SetUniformi("useDrawList", 0);
    texture->Deactivate();
    return this->DrawList.size();
  }

  /// Reads the depth of the current viewport of the framebuffer being drawn into Depth. False
  /// where it cannot be read as it is (multisampled, or a pixel buffer bound for reading).
  bool ReadDepth(vtkOpenGLRenderWindow* window, int& width, int& height)
  {
    GLint viewport[4] = { 0, 0, 0, 0 };
    glGetIntegerv(GL_VIEWPORT, viewport);
    GLint samples = 0;
    glGetIntegerv(GL_SAMPLE_BUFFERS, &samples);
    GLint pack_buffer = 0;
    glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &pack_buffer);
    if (samples != 0 || pack_buffer != 0 || viewport[2] <= 0 || viewport[3] <= 0)
    {
      return false;
    }
    width = viewport[2];
    height = viewport[3];
    this->Depth.resize(std::size_t(width) * std::size_t(height));
    GLint draw = 0;
    GLint read = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read);
    vtkOpenGLState* state = window->GetState();
    if (draw != read)
    {
      state->PushReadFramebufferBinding();
      state->vtkglBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<unsigned int>(draw));
    }
    glReadPixels(viewport[0], viewport[1], width, height, GL_DEPTH_COMPONENT, GL_FLOAT,
                 this->Depth.data());
    if (draw != read)
    {
      state->PopReadFramebufferBinding();
    }
    return true;
  }

  /// The pyramid of the depth drawn so far; where the depth cannot be read, one that hides
  /// nothing.
  void BuildPyramid(vtkOpenGLRenderWindow* window)
  {
    int width = 0;
    int height = 0;
    if (this->ReadDepth(window, width, height))
    {
      this->Pyramid.Build(this->Depth.data(), width, height);
    }
    else
    {
      this->Pyramid.Build(nullptr, 0, 0);
    }
  }
};

vtkMesoAtomMapper::vtkMesoAtomMapper()
  : Internal(std::make_unique<Internals>())
{
  this->SetNumberOfInputPorts(2);
  this->SetVisibilityArrayName(vtkMesoArrayNames::Visible);
}

vtkMesoAtomMapper::~vtkMesoAtomMapper()
{
  this->SetVisibilityArrayName(nullptr);
}

vtkIdType vtkMesoAtomMapper::GetHiddenAtomCount() const
{
  const vtkMesoAtomGPUData& data = this->Internal->Data;
  return data.HiddenAtoms * data.TileCount + data.HiddenInTiles;
}

int vtkMesoAtomMapper::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  }
  return 1;
}

void vtkMesoAtomMapper::SetWarpConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(1, output);
}

void vtkMesoAtomMapper::SetAssemblyConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(1, output);
}

vtkPolyData* vtkMesoAtomMapper::WarpInput()
{
  if (this->GetNumberOfInputConnections(1) == 0)
  {
    return nullptr;
  }
  return vtkPolyData::SafeDownCast(this->GetExecutive()->GetInputData(1, 0));
}

void vtkMesoAtomMapper::Render(vtkRenderer* ren, vtkActor* act)
{
  if (this->GetNumberOfInputConnections(1) > 0)
  {
    this->GetInputAlgorithm(1, 0)->Update(this->GetInputConnection(1, 0)->GetIndex());
  }
  // Translucent atoms: the back halves first, then the front ones.
  if (act->GetProperty()->GetOpacity() < 1.0 && !act->GetProperty()->GetBackfaceCulling())
  {
    this->Internal->Inverted = true;
    this->Superclass::Render(ren, act);
    this->Internal->Inverted = false;
  }
  this->Superclass::Render(ren, act);
}

bool vtkMesoAtomMapper::GetNeedToRebuildBufferObjects(vtkRenderer* ren, vtkActor* act)
{
  vtkPolyData* warp = this->WarpInput();
  return this->Superclass::GetNeedToRebuildBufferObjects(ren, act) ||
    (warp && warp->GetMTime() > this->VBOBuildTime);
}

void vtkMesoAtomMapper::BuildBufferObjects(vtkRenderer* ren, vtkActor*)
{
  Internals& in = *this->Internal;
  in.LastUploadBytes = 0;
  vtkMesoAtomGPUData::Style style{ this->Style, this->RadiusScale, this->BallScale,
                                   this->BondRadius };
  std::size_t atoms_per_cell = 0;
  vtkPolyData* drawn =
    in.Selected.Apply(this->CurrentInput, this->AtomSelection, this->VisibilityArrayName, this);
  const char* mask_name =
    this->AtomSelection.empty() ? this->VisibilityArrayName : SelectionMask::MaskName;
  const vtkIdType input_atoms = drawn ? drawn->GetNumberOfPoints() : 0;
  if (this->OcclusionCulling && this->AtomsPerCell > 0)
  {
    atoms_per_cell = static_cast<std::size_t>(this->AtomsPerCell);
  }
  else if (this->OcclusionCulling && this->GetNumberOfInputConnections(1) > 0)
  {
    // A warped patch's cells go into every tile: about 32 per patch (fewer cells cost less per
    // frame than tighter ones save; BenchmarkAtomMapper --atoms-per-cell), of patches big
    // enough to have 4.
    atoms_per_cell = input_atoms >= 256
      ? static_cast<std::size_t>(std::clamp<vtkIdType>(input_atoms / 32, 64, 2048))
      : 0;
  }
  else if (this->OcclusionCulling && input_atoms >= minimum_culled_atoms)
  {
    atoms_per_cell = static_cast<std::size_t>(std::clamp<vtkIdType>(input_atoms / 1024, 256, 2048));
  }
  if (!in.Data.Update(drawn, this->WarpInput(), style, this, atoms_per_cell, mask_name))
  {
    this->VBOBuildTime.Modified();
    return;
  }
  vtkOpenGLRenderWindow* window = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  const vtkMesoAtomGPUData& data = in.Data;

  const std::size_t position_values = 3 * static_cast<std::size_t>(data.AtomCount);
  if (data.PositionsVersion != in.UploadedPositions)
  {
    in.Positions->Upload(data.PositionData, position_values, vtkOpenGLBufferObject::ArrayBuffer);
    in.UploadedPositions = data.PositionsVersion;
    in.LastUploadBytes += static_cast<vtkIdType>(sizeof(float) * position_values);
  }
  if (data.TypesVersion != in.UploadedTypes)
  {
    in.Types->Upload(data.Types, vtkOpenGLBufferObject::ArrayBuffer);
    in.UploadedTypes = data.TypesVersion;
    in.LastUploadBytes += static_cast<vtkIdType>(data.Types.size());
  }
  if (data.UsesMoleculeSlots() && data.MoleculeSlotsVersion != in.UploadedMolecules)
  {
    in.Molecules->Upload(data.MoleculeSlots, vtkOpenGLBufferObject::ArrayBuffer);
    in.UploadedMolecules = data.MoleculeSlotsVersion;
    in.LastUploadBytes +=
      static_cast<vtkIdType>(sizeof(unsigned short) * data.MoleculeSlots.size());
  }
  const auto atoms = static_cast<unsigned int>(data.AtomCount);
  in.PositionTexture->SetContext(window);
  in.PositionTexture->CreateTextureBuffer(atoms, 3, VTK_FLOAT, in.Positions);
  in.TypeTexture->SetContext(window);
  in.TypeTexture->CreateTextureBuffer(atoms, 2, VTK_UNSIGNED_CHAR, in.Types);
  if (data.UsesMoleculeSlots())
  {
    in.MoleculeTexture->SetContext(window);
    in.MoleculeTexture->CreateTextureBuffer(atoms, 1, VTK_UNSIGNED_SHORT, in.Molecules);
  }
  vtkOpenGLIndexBufferObject* bonds = this->Primitives[PrimitiveLines].IBO;
  if (data.BondsVersion != in.UploadedBonds)
  {
    if (!data.Bonds.empty())
    {
      bonds->Upload(data.Bonds, vtkOpenGLBufferObject::ElementArrayBuffer);
      in.LastUploadBytes += static_cast<vtkIdType>(sizeof(unsigned int) * data.Bonds.size());
    }
    in.UploadedBonds = data.BondsVersion;
  }
  bonds->IndexCount = data.Bonds.size();
  this->Primitives[PrimitiveTris].IBO->IndexCount = static_cast<size_t>(data.AtomCount);
  this->Primitives[PrimitivePoints].IBO->IndexCount = 0;
  this->Primitives[PrimitiveTriStrips].IBO->IndexCount = 0;
  in.Colors.Upload(window, data.ColorTable, data.TypesVersion);
  if (!data.WarpTexels.empty())
  {
    in.Warp.Upload(window, data.WarpTexels, data.WarpVersion);
  }
  if (!data.MoleculeMask.empty() && data.MoleculeMaskVersion != in.UploadedMask)
  {
    // A cutaway step: a bit per molecule and tile goes up, nothing else.
    in.MaskBuffer->Upload(data.MoleculeMask, vtkOpenGLBufferObject::TextureBuffer);
    in.MaskTexture->SetContext(window);
    in.MaskTexture->SetInternalFormat(GL_R32UI);
    in.MaskTexture->CreateTextureBuffer(static_cast<unsigned int>(data.MoleculeMask.size()), 1,
                                        VTK_UNSIGNED_INT, in.MaskBuffer);
    in.UploadedMask = data.MoleculeMaskVersion;
    in.LastUploadBytes += static_cast<vtkIdType>(sizeof(std::uint32_t) * data.MoleculeMask.size());
  }
  if (data.WarpMethod != in.ShaderWarpMethod || data.MoleculeMask.empty() != !in.ShaderMask)
  {
    in.ShaderWarpMethod = data.WarpMethod;
    in.ShaderMask = !data.MoleculeMask.empty();
    in.ShaderKeyTime.Modified();
  }
  in.BufferTime.Modified();
  this->VBOBuildTime.Modified();
}

bool vtkMesoAtomMapper::GetNeedToRebuildShaders(vtkOpenGLHelper& cellBO, vtkRenderer* ren,
                                                vtkActor* act)
{
  return this->Superclass::GetNeedToRebuildShaders(cellBO, ren, act) ||
    this->Internal->ShaderKeyTime > cellBO.ShaderSourceTime;
}

void vtkMesoAtomMapper::GetShaderTemplate(std::map<vtkShader::Type, vtkShader*> shaders,
                                          vtkRenderer* ren, vtkActor* act)
{
  this->Superclass::GetShaderTemplate(shaders, ren, act);
  const bool atoms = this->Internal->Current == Pass::Atoms;
  shaders[vtkShader::Vertex]->SetSource(atoms ? vtkMesoAtomSphereVS : vtkMesoBondVS);
  shaders[vtkShader::Geometry]->SetSource(atoms ? "" : vtkMesoBondCylinderGS);
}

void vtkMesoAtomMapper::ReplaceShaderValues(std::map<vtkShader::Type, vtkShader*> shaders,
                                            vtkRenderer* ren, vtkActor* act)
{
  const bool atoms = this->Internal->Current == Pass::Atoms;
  const int warp = this->Internal->Data.WarpMethod;

  std::string vertex = shaders[vtkShader::Vertex]->GetSource();
  std::string position = "gl_Position = MCVCMatrix * vertexMC;\n";
  if (warp != vtkMesoAtomGPUData::NoWarp)
  {
    vtkShaderProgram::Substitute(vertex, "//MESO::Warp::Dec",
                                 warp == static_cast<int>(mesolens::MappingMethod::Polynomial)
                                   ? vtkMesoPolynomialWarpVS
                                   : vtkMesoMoleculeInstancingVS);
    // Bonds read the molecule slot as an attribute, atoms pull it like the rest of the atom.
    const std::string slot = warp != static_cast<int>(mesolens::MappingMethod::MoleculeInstancing)
      ? "0.0"
      : atoms ? "floor(texelFetch(atomMolecules, slot).x * 65535.0 + 0.5)"
              : "atomMolecule";
    // Atoms know their tile (the instance, or a culling draw list's entry), bonds the instance.
    position = "vertexMC = vec4(warpedPosition(atomPosition, " + slot + ", " +
      (atoms ? "tile" : "gl_InstanceID") + "), 1.0);\n  " + position;
  }
  vtkShaderProgram::Substitute(vertex, "//MESO::Warp::Impl", position);
  // A molecule mask: hidden molecules of a tile get radius 0 (atoms), or hide their bonds.
  if (warp != vtkMesoAtomGPUData::NoWarp && this->Internal->ShaderMask)
  {
    vtkShaderProgram::Substitute(
      vertex, "//MESO::MoleculeMask::Dec",
      "uniform usamplerBuffer moleculeMask;\nuniform int maskMoleculesPerTile;\n"
      "bool moleculeHidden(int tile, float moleculeSlot)\n{\n"
      "  int molecule = tile * maskMoleculesPerTile + int(moleculeSlot + 0.5);\n"
      "  return ((texelFetch(moleculeMask, molecule >> 5).r >> uint(molecule & 31)) & 1u) != 0u;\n"
      "}\n");
    vtkShaderProgram::Substitute(
      vertex, "//MESO::MoleculeMask::Impl",
      atoms
        ? "if (moleculeHidden(tile, floor(texelFetch(atomMolecules, slot).x * 65535.0 + 0.5)))\n"
          "  {\n    radius = 0.0;\n  }"
        : "if (moleculeHidden(gl_InstanceID, atomMolecule))\n  {\n"
          "    atomHiddenVSOutput = 1.0;\n  }");
  }
  // Culling draws lists of the atoms' slots.
  if (atoms && !ren->GetSelector() && !this->Internal->Data.Cells.cell_start.empty())
  {
    // An entry is t n + slot for the atom in that slot, in tile t of a warp (n atoms).
    vtkShaderProgram::Substitute(
      vertex, "//MESO::AtomSlot::Dec",
      "uniform usamplerBuffer atomDrawList;\nuniform int useDrawList;\nuniform int drawListAtoms;");
    vtkShaderProgram::Substitute(vertex, "//MESO::AtomSlot::Impl",
                                 "if (useDrawList != 0)\n  {\n"
                                 "    uint entry = texelFetch(atomDrawList, drawn).r;\n"
                                 "    slot = int(entry % uint(drawListAtoms));\n"
                                 "    tile = int(entry / uint(drawListAtoms));\n"
                                 "    atom = slot;\n  }");
  }
  // Picking draws the atoms in input order: each finds its slot in the cell order.
  if (atoms && ren->GetSelector() && !this->Internal->Data.Cells.cell_start.empty())
  {
    vtkShaderProgram::Substitute(vertex, "//MESO::AtomSlot::Dec",
                                 "uniform usamplerBuffer atomSlots;");
    vtkShaderProgram::Substitute(vertex, "//MESO::AtomSlot::Impl",
                                 "slot = int(texelFetch(atomSlots, atom).r);");
  }
  shaders[vtkShader::Vertex]->SetSource(vertex);

  std::string fragment = shaders[vtkShader::Fragment]->GetSource();
  vtkShaderProgram::Substitute(fragment, "//VTK::PositionVC::Dec", "in vec4 vertexVCGSOutput;");
  vtkShaderProgram::Substitute(fragment, "//VTK::PositionVC::Impl",
                               "vec4 vertexVC = vertexVCGSOutput;\n");
  vtkShaderProgram::Substitute(fragment, "//VTK::Normal::Dec",
                               atoms ? vtkMesoAtomSphereFSDec : vtkMesoBondCylinderFSDec);
  vtkShaderProgram::Substitute(fragment, "//VTK::Depth::Impl",
                               atoms ? vtkMesoAtomSphereFSImpl : vtkMesoBondCylinderFSImpl);
  // The normal comes from the intersection.
  vtkShaderProgram::Substitute(fragment, "//VTK::Normal::Impl", "");
  // VTK's colour code first, then the atom's colour on top.
  vtkShaderProgram::Substitute(fragment, "//VTK::Color::Impl",
                               "//VTK::Color::Impl\n//MESO::AtomColor::Impl\n");
  shaders[vtkShader::Fragment]->SetSource(fragment);

  this->Superclass::ReplaceShaderValues(shaders, ren, act);

  if (atoms)
  {
    // Point picking reports the vertex id: three vertices per atom here.
    vertex = shaders[vtkShader::Vertex]->GetSource();
    vtkShaderProgram::Substitute(vertex, "= gl_VertexID;", "= atom;");
    shaders[vtkShader::Vertex]->SetSource(vertex);
  }
  fragment = shaders[vtkShader::Fragment]->GetSource();
  vtkShaderProgram::Substitute(fragment, "//MESO::AtomColor::Impl", vtkMesoAtomColorFS);
  shaders[vtkShader::Fragment]->SetSource(fragment);
}

void vtkMesoAtomMapper::SetCameraShaderParameters(vtkOpenGLHelper& cellBO, vtkRenderer* ren,
                                                  vtkActor* act)
{
  this->Superclass::SetCameraShaderParameters(cellBO, ren, act);
  vtkShaderProgram* program = cellBO.Program;
  vtkOpenGLCamera* camera = static_cast<vtkOpenGLCamera*>(ren->GetActiveCamera());
  vtkMatrix4x4* wcvc = nullptr;
  vtkMatrix3x3* normals = nullptr;
  vtkMatrix4x4* vcdc = nullptr;
  vtkMatrix4x4* wcdc = nullptr;
  camera->GetKeyMatrices(ren, wcvc, normals, vcdc, wcdc);
  if (program->IsUniformUsed("VCDCMatrix"))
  {
    program->SetUniformMatrix("VCDCMatrix", vcdc);
  }
  set_uniform_int(program, "cameraParallel", camera->GetParallelProjection());
}

void vtkMesoAtomMapper::SetMapperShaderParameters(vtkOpenGLHelper& cellBO, vtkRenderer* ren,
                                                  vtkActor* act)
{
  Internals& in = *this->Internal;
  const vtkMesoAtomGPUData& data = in.Data;
  vtkShaderProgram* program = cellBO.Program;
  if (in.Current == Pass::Bonds &&
      (cellBO.ShaderSourceTime > cellBO.AttributeUpdateTime ||
       in.BufferTime > cellBO.AttributeUpdateTime))
  {
    cellBO.VAO->Bind();
    cellBO.VAO->AddAttributeArray(program, in.Positions, "atomPosition", 0, 3 * sizeof(float),
                                  VTK_FLOAT, 3, false);
    cellBO.VAO->AddAttributeArray(program, in.Types, "atomType", 0, 2, VTK_UNSIGNED_CHAR, 2, false);
    if (data.UsesMoleculeSlots())
    {
      cellBO.VAO->AddAttributeArray(program, in.Molecules, "atomMolecule", 0,
                                    sizeof(unsigned short), VTK_UNSIGNED_SHORT, 1, false);
    }
  }
  set_uniform_float(program, "invertedDepth", in.Inverted ? -1.0f : 1.0f);
  set_uniform_float(program, "bondRadius", data.BondRadius);
  if (program->IsUniformUsed("atomRadii"))
  {
    program->SetUniform1fv("atomRadii", static_cast<int>(data.Radii.size()), data.Radii.data());
  }
  set_uniform_int(program, "atomColorTable", in.Colors.Texture->GetTextureUnit());
  if (in.Current == Pass::Atoms)
  {
    set_uniform_int(program, "atomPositions", in.PositionTexture->GetTextureUnit());
    set_uniform_int(program, "atomTypes", in.TypeTexture->GetTextureUnit());
    if (program->IsUniformUsed("atomSlots"))
    {
      program->SetUniformi("atomSlots", in.SlotTexture->GetTextureUnit());
    }
    if (program->IsUniformUsed("atomDrawList"))
    {
      program->SetUniformi("atomDrawList", in.DrawListTextures[0]->GetTextureUnit());
      program->SetUniformi("useDrawList", 0);
    }

    if (data.UsesMoleculeSlots())
    {
      set_uniform_int(program, "atomMolecules", in.MoleculeTexture->GetTextureUnit());
    }
  }
  if (data.WarpMethod != vtkMesoAtomGPUData::NoWarp)
  {
    const char* buffer = data.WarpMethod == static_cast<int>(mesolens::MappingMethod::Polynomial)
      ? "warpCoefficients"
      : "moleculeMotions";
    set_uniform_int(program, buffer, in.Warp.Texture->GetTextureUnit());
    if (program->IsUniformUsed("patchOrigin"))
    {
      program->SetUniform2f("patchOrigin", data.PatchOrigin);
    }
    if (program->IsUniformUsed("patchToFractional"))
    {
      program->SetUniform4f("patchToFractional", data.PatchToFractional);
    }
    set_uniform_float(program, "patchCentreHeight", data.PatchCentreHeight);
    set_uniform_float(program, "inverseLayerHalfThickness", data.InverseLayerHalfThickness);
    set_uniform_int(program, "moleculesPerTile", data.MoleculesPerTile);
    set_uniform_int(program, "maskMoleculesPerTile", data.MoleculesPerTile);
    if (in.ShaderMask)
    {
      set_uniform_int(program, "moleculeMask", in.MaskTexture->GetTextureUnit());
    }
    set_uniform_int(program, "polynomialTiles", data.TileCountForHeader);
  }
  this->Superclass::SetMapperShaderParameters(cellBO, ren, act);
  cellBO.AttributeUpdateTime.Modified();
}

// Why atoms are drawn this way (measured with BenchmarkAtomMapper on Mesa llvmpipe, 1 M atoms):
// a geometry stage that expands points costs twice the vertex time of vertex pulling (0.28 s
// against 0.13 s); point sprites are slower still (llvmpipe expands them on the CPU); one
// triangle per atom beats a quad (the cost per primitive outweighs the pixels of small atoms);
// GL_ARB_conservative_depth (depth_greater) made llvmpipe slower, so depth stays plain
// gl_FragDepth. What remains is fragment work on hidden atoms (late depth, ~40x overdraw).
void vtkMesoAtomMapper::RenderPieceDraw(vtkRenderer* ren, vtkActor* act)
{
  Internals& in = *this->Internal;
  const vtkMesoAtomGPUData& data = in.Data;
  if (data.AtomCount == 0)
  {
    return;
  }
  const GLsizei instances = static_cast<GLsizei>(data.TileCount);
  in.Colors.Texture->Activate();
  in.PositionTexture->Activate();
  in.TypeTexture->Activate();
  if (data.WarpMethod != vtkMesoAtomGPUData::NoWarp)
  {
    in.Warp.Texture->Activate();
  }
  if (data.UsesMoleculeSlots())
  {
    in.MoleculeTexture->Activate();
  }
  if (!data.MoleculeMask.empty())
  {
    in.MaskTexture->Activate();
  }
  const bool grouped = !data.Cells.cell_start.empty();
  const bool picking = ren->GetSelector() != nullptr;
  if (grouped && picking)
  {
    if (in.UploadedSlots != data.CellsVersion || in.SlotTexture->GetHandle() == 0)
    {
      in.Slots->Upload(data.SlotOfAtom, vtkOpenGLBufferObject::TextureBuffer);
      in.SlotTexture->SetContext(static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow()));
      // Integer texels: VTK would pick a float format for VTK_UNSIGNED_INT.
      in.SlotTexture->SetInternalFormat(GL_R32UI);
      in.SlotTexture->CreateTextureBuffer(static_cast<unsigned int>(data.AtomCount), 1,
                                          VTK_UNSIGNED_INT, in.Slots);
      in.UploadedSlots = data.CellsVersion;
    }
    in.SlotTexture->Activate();
  }
  else if (in.UploadedSlots != 0)
  {
    // The slot table is for picking only.
    in.SlotTexture->ReleaseGraphicsResources(ren->GetRenderWindow());
    in.Slots->ReleaseGraphicsResources();
    in.UploadedSlots = 0;
  }

  if (grouped && !picking)
  {
    // The shader reads a draw list only when culling, but its sampler needs a texture.
    if (in.DrawListTextures[0]->GetHandle() == 0)
    {
      in.UploadDrawList(static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow()), 0,
                        std::vector<std::uint32_t>(1, 0));
    }
    in.DrawListTextures[0]->Activate();
  }

  in.Current = Pass::Atoms;
  this->PrimitiveIDOffset = 0;
  vtkOpenGLHelper& spheres = this->Primitives[PrimitiveTris];
  this->UpdateShaders(spheres, ren, act);
  const bool translucent = act->GetProperty()->GetOpacity() < 1.0;
  const bool warped = data.WarpMethod != vtkMesoAtomGPUData::NoWarp;
  if (grouped && this->OcclusionCulling && !picking && !translucent &&
      (!warped || data.WarpedAtoms))
  {
    in.DrawListTextures[0]->Deactivate();
    if (warped)
    {
      this->DrawVisibleWarpedCells(ren, act, spheres.Program);
    }
    else
    {
      this->DrawVisibleCells(ren, act, spheres.Program);
    }
  }
  else
  {
    glDrawArraysInstanced(GL_TRIANGLES, 0, static_cast<GLsizei>(3 * data.AtomCount), instances);
    in.LastDrawnAtoms = data.AtomCount * data.TileCount;
  }

  vtkOpenGLHelper& bonds = this->Primitives[PrimitiveLines];
  if (this->Style != SPACE_FILLING && bonds.IBO->IndexCount > 0)
  {
    in.Current = Pass::Bonds;
    // Bonds follow the atoms' vertex cells in VTK's cell numbering (of the patch in warp mode).
    this->PrimitiveIDOffset = static_cast<int>(data.AtomCount);
    this->UpdateShaders(bonds, ren, act);
    bonds.IBO->Bind();
    glDrawElementsInstanced(GL_LINES, static_cast<GLsizei>(bonds.IBO->IndexCount), GL_UNSIGNED_INT,
                            nullptr, instances);
    bonds.IBO->Release();
    in.Current = Pass::Atoms;
  }
}

void vtkMesoAtomMapper::DrawVisibleCells(vtkRenderer* ren, vtkActor* act, vtkShaderProgram* spheres)
{
  const vtkMesoAtomGPUData& data = this->Internal->Data;
  const mesolens::StoredCellAtoms atoms({ data.PositionData, std::size_t(data.AtomCount) },
                                        data.Types.data(), 2, data.Radii.data(), data.Cells);
  this->DrawVisibleAtoms(ren, act, spheres, atoms, data.CellBoxes,
                         this->CellPaddingFactor * 1.01 * data.LargestPresentRadius);
}

void vtkMesoAtomMapper::DrawVisibleWarpedCells(vtkRenderer* ren, vtkActor* act,
                                               vtkShaderProgram* spheres)
{
  const vtkMesoAtomGPUData& data = this->Internal->Data;
  // The boxes hold the warped centres up to the GPU's rounding.
  this->DrawVisibleAtoms(ren, act, spheres, *data.WarpedAtoms, data.WarpedAtoms->boxes(),
                         this->CellPaddingFactor *
                           (1.01 * data.LargestPresentRadius + data.WarpedAtoms->margin()));
}

void vtkMesoAtomMapper::DrawVisibleAtoms(vtkRenderer* ren, vtkActor* act, vtkShaderProgram* spheres,
                                         const mesolens::CellAtoms& atoms,
                                         const std::vector<float>& boxes, double padding)
{
  Internals& in = *this->Internal;
  auto* window = static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow());
  const mesolens::ViewTransform view = model_view(ren, act);
  const std::vector<mesolens::CellInView> cells =
    mesolens::cells_in_view(boxes, padding, view.model_to_clip);

  // What this renderer saw last time at this viewport size.
  GLint viewport[4] = { 0, 0, 0, 0 };
  glGetIntegerv(GL_VIEWPORT, viewport);
  const std::size_t cell_count = atoms.cell_count();
  ViewHistory& history = in.History({ ren, viewport[2], viewport[3] }, in.Data.CellsVersion,
                                    atoms.first_slot(cell_count), cell_count);

  // 1. The atoms seen last time; with none (a first frame, a jump), the cells that make the
  // nearest surface of what is in view, whole.
  if (std::find(history.Seen.begin(), history.Seen.end(), 1) == history.Seen.end())
  {
    history.Seen =
      mesolens::first_occluders(atoms, boxes, cells, padding, view, viewport[2], viewport[3]);
    for (std::size_t cell = 0; cell < cell_count; ++cell)
    {
      if (history.Seen[cell])
      {
        std::fill(history.Flags.begin() + atoms.first_slot(cell),
                  history.Flags.begin() + atoms.first_slot(cell + 1), std::uint8_t(mesolens::SEEN));
      }
    }
  }
  in.DrawListBytes = 0;
  in.DrawAtoms(window, spheres, 0, atoms, history.Flags, mesolens::SEEN, cells, history.Seen);

  // 2. Every atom in view tested against that depth; those that show and were not drawn yet
  // are drawn now. Where the depth cannot be read, everything in view counts as shown.
  in.BuildPyramid(window);
  const mesolens::CellVisibility found = mesolens::test_atom_visibility(
    in.Pyramid, view, atoms, boxes, cells, padding, history.Flags, vtkMesoParallelFor::Get());
  in.DrawAtoms(window, spheres, 1, atoms, history.Flags, mesolens::NEWLY_SEEN, cells,
               found.newly_seen);
  in.LastDrawnAtoms = static_cast<vtkIdType>(found.drawn_first + found.drawn_after);
  history.Seen = found.seen;
}

void vtkMesoAtomMapper::RenderPieceFinish(vtkRenderer* ren, vtkActor* act)
{
  Internals& in = *this->Internal;
  if (in.Colors.Texture->GetHandle() != 0)
  {
    in.Colors.Texture->Deactivate();
  }
  for (vtkTextureObject* texture :
       { in.Warp.Texture.Get(), in.PositionTexture.Get(), in.TypeTexture.Get(),
         in.MoleculeTexture.Get(), in.SlotTexture.Get(), in.MaskTexture.Get() })
  {
    if (texture->GetHandle() != 0)
    {
      texture->Deactivate();
    }
  }
  this->Superclass::RenderPieceFinish(ren, act);
}

void vtkMesoAtomMapper::ComputeBounds()
{
  // The padding (largest radius) and the warped tiles take passes over the atoms: keep the
  // bounds while the atoms, the warp and the style stay (the renderer asks every frame).
  Internals& in = *this->Internal;
  vtkPolyData* atoms = this->GetInput();
  // The warp is needed before the first render (a camera reset): brought up to date here too.
  if (this->GetNumberOfInputConnections(1) > 0 && !this->Static)
  {
    this->GetInputAlgorithm(1, 0)->Update(this->GetInputConnection(1, 0)->GetIndex());
  }
  vtkPolyData* warp = this->WarpInput();
  const vtkMTimeType key =
    std::max({ atoms ? atoms->GetMTime() : 0, this->GetMTime(), warp ? warp->GetMTime() : 0 });
  if (atoms && key == in.BoundsTime)
  {
    std::copy(in.Bounds, in.Bounds + 6, this->Bounds);
    return;
  }
  auto* floats = atoms && atoms->GetPoints()
    ? vtkFloatArray::FastDownCast(atoms->GetPoints()->GetData())
    : nullptr;
  if (floats && floats->GetNumberOfComponents() == 3)
  {
    // Every atom, in parallel: VTK 9.2's polydata bounds take only points used by cells (an
    // unbonded ion would be left out) and one slow thread.
    const auto box =
      mesolens::point_bounds({ floats->GetPointer(0), std::size_t(floats->GetNumberOfTuples()) },
                             vtkMesoParallelFor::Get());
    std::copy(box.begin(), box.end(), this->Bounds);
  }
  else
  {
    this->Superclass::ComputeBounds();
  }
  if (!atoms)
  {
    return;
  }
  vtkMesoAtomGPUData::Style style{ this->Style, this->RadiusScale, this->BallScale,
                                   this->BondRadius };
  vtkMesoAtomGPUData::PaddedBounds(atoms, warp, vtkMesoAtomGPUData::LargestRadius(atoms, style),
                                   this->Bounds);
  std::copy(this->Bounds, this->Bounds + 6, in.Bounds);
  in.BoundsTime = key;
}

double vtkMesoAtomMapper::GetBufferBytesPerAtom() const
{
  const vtkMesoAtomGPUData& data = this->Internal->Data;
  if (data.AtomCount == 0)
  {
    return 0;
  }
  const double bytes = 3.0 * sizeof(float) * double(data.AtomCount) + data.Types.size() +
    (data.UsesMoleculeSlots() ? sizeof(unsigned short) * data.MoleculeSlots.size() : 0);
  return bytes / static_cast<double>(data.AtomCount);
}

double vtkMesoAtomMapper::GetLastDrawListBytesPerAtom() const
{
  const vtkIdType atoms = this->Internal->Data.AtomCount;
  return atoms > 0 ? double(this->Internal->DrawListBytes) / double(atoms) : 0.0;
}

vtkIdType vtkMesoAtomMapper::GetLastDrawnAtomCount() const
{
  return this->Internal->LastDrawnAtoms;
}

vtkIdType vtkMesoAtomMapper::GetWarpBufferBytes() const
{
  const vtkMesoAtomGPUData& data = this->Internal->Data;
  return static_cast<vtkIdType>(sizeof(float) * data.WarpTexels.size() +
                                sizeof(std::uint32_t) * data.MoleculeMask.size());
}

vtkIdType vtkMesoAtomMapper::GetLastUploadBytes() const
{
  return this->Internal->LastUploadBytes;
}

void vtkMesoAtomMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  Internals& in = *this->Internal;
  in.Positions->ReleaseGraphicsResources();
  in.Types->ReleaseGraphicsResources();
  in.Molecules->ReleaseGraphicsResources();
  in.UploadedTypes = 0;
  in.UploadedPositions = 0;
  in.UploadedMolecules = 0;
  in.UploadedBonds = 0;
  in.Colors.Release(window);
  in.PositionTexture->ReleaseGraphicsResources(window);
  in.TypeTexture->ReleaseGraphicsResources(window);
  in.MoleculeTexture->ReleaseGraphicsResources(window);
  in.MaskTexture->ReleaseGraphicsResources(window);
  in.MaskBuffer->ReleaseGraphicsResources();
  in.UploadedMask = 0;
  in.Warp.Release(window);
  for (int which = 0; which < 2; ++which)
  {
    in.DrawListTextures[which]->ReleaseGraphicsResources(window);
    in.DrawLists[which]->ReleaseGraphicsResources();
  }
  in.Histories.clear();
  this->Superclass::ReleaseGraphicsResources(window);
}

void vtkMesoAtomMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  static const char* styles[] = { "SPACE_FILLING", "BALL_AND_STICK", "STICKS" };
  os << indent << "Style: " << styles[this->Style] << "\n";
  os << indent << "RadiusScale: " << this->RadiusScale << "\n";
  os << indent << "BallScale: " << this->BallScale << "\n";
  os << indent << "BondRadius: " << this->BondRadius << "\n";
  os << indent << "OcclusionCulling: " << (this->OcclusionCulling ? "on" : "off") << "\n";
  os << indent << "AtomsPerCell: " << this->AtomsPerCell << "\n";
  os << indent << "CellPaddingFactor: " << this->CellPaddingFactor << "\n";
  os << indent << "VisibilityArrayName: "
     << (this->VisibilityArrayName ? this->VisibilityArrayName : "(none)") << "\n";
  os << indent
     << "AtomSelection: " << (this->AtomSelection.empty() ? "(all atoms)" : this->AtomSelection)
     << "\n";
  os << indent << "Warp: " << (this->GetNumberOfInputConnections(1) ? "connected" : "none") << "\n";
}
