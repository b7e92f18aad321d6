// SPDX-License-Identifier: GPL-3.0-or-later
#include "vtkMesoAtomMapper.h"

#include "vtkMesoAtomGPUData.h"

#include "vtkMesoAtomColorFS.h"
#include "vtkMesoAtomSphereFSDec.h"
#include "vtkMesoAtomSphereFSImpl.h"
#include "vtkMesoAtomSphereVS.h"
#include "vtkMesoBondCylinderFSDec.h"
#include "vtkMesoBondCylinderFSImpl.h"
#include "vtkMesoBondCylinderGS.h"
#include "vtkMesoBondVS.h"
#include "vtkMesoCellBoxFS.h"
#include "vtkMesoCellBoxVS.h"
#include "vtkMesoMoleculeInstancingVS.h"
#include "vtkMesoPolynomialWarpVS.h"

#include "mesolens/atom_cells.h"

#include <vtkHardwareSelector.h>
#include <vtkOpenGLActor.h>
#include <vtkOpenGLShaderCache.h>
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
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>

#include <vtk_glew.h>

#include <algorithm>
#include <cstdint>
#include <unordered_map>

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

/// Which cells a camera saw in its last frame.
struct CellHistory
{
  unsigned long CellsVersion = 0;
  bool Known = false;
  std::vector<unsigned char> Visible; // per cell
};

struct vtkMesoAtomMapper::Internals
{
  vtkMesoAtomGPUData Data;
  vtkNew<vtkOpenGLBufferObject> Positions;
  vtkNew<vtkOpenGLBufferObject> Types;
  vtkNew<vtkOpenGLBufferObject> Molecules;
  // The atom buffers seen as texture buffers by the sphere pass (vertex pulling).
  vtkNew<vtkTextureObject> PositionTexture;
  vtkNew<vtkTextureObject> TypeTexture;
  vtkNew<vtkTextureObject> MoleculeTexture;
  unsigned long UploadedTypes = 0;     // TypesVersion on the GPU, 0: none
  unsigned long UploadedMolecules = 0; // WarpVersion of the molecule slots on the GPU
  unsigned long UploadedBonds = 0;
  TexelBuffer Colors;
  TexelBuffer Warp;
  TexelBuffer CellBoxes;                // 2 texels per cell: min, max corner
  unsigned long CellBoxesVersion = 0;   // counts position updates of grouped atoms
  std::vector<unsigned int> Queries;    // one occlusion query per cell of a wave
  vtkNew<vtkOpenGLBufferObject> Slots;  // picking: the slot of each input atom
  vtkNew<vtkTextureObject> SlotTexture; // ... as an R32UI texture buffer
  unsigned long UploadedSlots = 0;      // CellsVersion of the slots on the GPU, 0: none
  vtkIdType LastDrawnAtoms = 0;
  // Keyed by camera: only compared, never dereferenced (a stale entry costs time, not pixels).
  std::unordered_map<const vtkCamera*, CellHistory> Histories;

  CellHistory& History(const vtkCamera* camera, unsigned long version, std::size_t cells)
  {
    if (this->Histories.size() > 16 && !this->Histories.count(camera))
    {
      this->Histories.clear();
    }
    CellHistory& history = this->Histories[camera];
    if (history.CellsVersion != version || history.Visible.size() != cells)
    {
      history = CellHistory{ version, false, std::vector<unsigned char>(cells, 0) };
    }
    return history;
  }

  void ReserveQueries(std::size_t count)
  {
    if (this->Queries.size() < count)
    {
      const std::size_t old = this->Queries.size();
      this->Queries.resize(count);
      glGenQueries(static_cast<GLsizei>(count - old), this->Queries.data() + old);
    }
  }

  /// The entries of `tested` (indices into `cells`) whose boxes, grown by `padding`, pass the
  /// depth test somewhere; nothing is written to the framebuffer.
  std::vector<std::size_t> TestBoxes(vtkOpenGLRenderWindow* window, vtkMatrix4x4* mcdc,
                                     double padding, const std::vector<mesolens::CellInView>& cells,
                                     const std::vector<std::size_t>& tested)
  {
    std::vector<std::size_t> visible;
    if (tested.empty())
    {
      return visible;
    }
    this->ReserveQueries(tested.size());
    {
      vtkOpenGLState* state = window->GetState();
      vtkOpenGLState::ScopedglColorMask colors(state);
      vtkOpenGLState::ScopedglDepthMask depths(state);
      vtkOpenGLState::ScopedglEnableDisable culling(state, GL_CULL_FACE);
      state->vtkglColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
      state->vtkglDepthMask(GL_FALSE);
      state->vtkglDisable(GL_CULL_FACE);
      vtkShaderProgram* boxes =
        window->GetShaderCache()->ReadyShaderProgram(vtkMesoCellBoxVS, vtkMesoCellBoxFS, "");
      boxes->SetUniformMatrix("MCDCMatrix", mcdc);
      boxes->SetUniformf("cellPadding", static_cast<float>(padding));
      boxes->SetUniformi("cellBoxes", this->CellBoxes.Texture->GetTextureUnit());
      for (std::size_t q = 0; q < tested.size(); ++q)
      {
        glBeginQuery(GL_SAMPLES_PASSED, this->Queries[q]);
        glDrawArrays(GL_TRIANGLES, static_cast<GLint>(36 * cells[tested[q]].cell), 36);
        glEndQuery(GL_SAMPLES_PASSED);
      }
    }
    for (std::size_t q = 0; q < tested.size(); ++q)
    {
      GLuint samples = 0;
      glGetQueryObjectuiv(this->Queries[q], GL_QUERY_RESULT, &samples);
      if (samples > 0)
      {
        visible.push_back(tested[q]);
      }
    }
    return visible;
  }
  vtkTimeStamp BufferTime;    // the buffers behind the vertex attributes changed
  vtkTimeStamp ShaderKeyTime; // the warp method changed
  int ShaderWarpMethod = -1;
  vtkIdType LastUploadBytes = 0;
  double Bounds[6] = { 0, 0, 0, 0, 0, 0 }; // the last ComputeBounds
  vtkMTimeType BoundsTime = 0;             // of the inputs and settings at this time
  Pass Current = Pass::Atoms;
  bool Inverted = false;
};

vtkMesoAtomMapper::vtkMesoAtomMapper()
  : Internal(std::make_unique<Internals>())
{
  this->SetNumberOfInputPorts(2);
}

vtkMesoAtomMapper::~vtkMesoAtomMapper() = default;

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
  const vtkIdType input_atoms = this->CurrentInput ? this->CurrentInput->GetNumberOfPoints() : 0;
  if (this->OcclusionCulling && this->AtomsPerCell > 0)
  {
    atoms_per_cell = static_cast<std::size_t>(this->AtomsPerCell);
  }
  else if (this->OcclusionCulling && input_atoms >= minimum_culled_atoms)
  {
    atoms_per_cell = static_cast<std::size_t>(std::clamp<vtkIdType>(input_atoms / 1024, 256, 2048));
  }
  if (!in.Data.Update(this->CurrentInput, this->WarpInput(), style, this, atoms_per_cell))
  {
    this->VBOBuildTime.Modified();
    return;
  }
  vtkOpenGLRenderWindow* window = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  const vtkMesoAtomGPUData& data = in.Data;

  const std::size_t position_values = 3 * static_cast<std::size_t>(data.AtomCount);
  in.Positions->Upload(data.PositionData, position_values, vtkOpenGLBufferObject::ArrayBuffer);
  in.LastUploadBytes += static_cast<vtkIdType>(sizeof(float) * position_values);
  if (data.TypesVersion != in.UploadedTypes)
  {
    in.Types->Upload(data.Types, vtkOpenGLBufferObject::ArrayBuffer);
    in.UploadedTypes = data.TypesVersion;
    in.LastUploadBytes += static_cast<vtkIdType>(data.Types.size());
  }
  if (!data.MoleculeSlots.empty() && data.WarpVersion != in.UploadedMolecules)
  {
    in.Molecules->Upload(data.MoleculeSlots, vtkOpenGLBufferObject::ArrayBuffer);
    in.UploadedMolecules = data.WarpVersion;
    in.LastUploadBytes +=
      static_cast<vtkIdType>(sizeof(unsigned short) * data.MoleculeSlots.size());
  }
  const auto atoms = static_cast<unsigned int>(data.AtomCount);
  in.PositionTexture->SetContext(window);
  in.PositionTexture->CreateTextureBuffer(atoms, 3, VTK_FLOAT, in.Positions);
  in.TypeTexture->SetContext(window);
  in.TypeTexture->CreateTextureBuffer(atoms, 2, VTK_UNSIGNED_CHAR, in.Types);
  if (!data.MoleculeSlots.empty())
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
  if (!data.CellBoxes.empty())
  {
    std::vector<float> texels(8 * data.Cells.cell_count(), 0.0f);
    for (std::size_t c = 0; c < data.Cells.cell_count(); ++c)
    {
      std::copy_n(&data.CellBoxes[6 * c], 3, &texels[8 * c]);
      std::copy_n(&data.CellBoxes[6 * c + 3], 3, &texels[8 * c + 4]);
    }
    in.CellBoxes.Upload(window, texels, ++in.CellBoxesVersion);
  }
  if (!data.WarpTexels.empty())
  {
    in.Warp.Upload(window, data.WarpTexels, data.WarpVersion);
  }
  if (data.WarpMethod != in.ShaderWarpMethod)
  {
    in.ShaderWarpMethod = data.WarpMethod;
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
  if (warp >= 0)
  {
    vtkShaderProgram::Substitute(vertex, "//MESO::Warp::Dec",
                                 warp == vtkMesoAtomGPUData::POLYNOMIAL
                                   ? vtkMesoPolynomialWarpVS
                                   : vtkMesoMoleculeInstancingVS);
    // Bonds read the molecule slot as an attribute, atoms pull it like the rest of the atom.
    const std::string slot = warp != vtkMesoAtomGPUData::MOLECULE_INSTANCING ? "0.0"
      : atoms ? "floor(texelFetch(atomMolecules, slot).x * 65535.0 + 0.5)"
              : "atomMolecule";
    position = "vertexMC = vec4(warpedPosition(atomPosition, " + slot +
      ", gl_InstanceID), 1.0);\n  " + position;
  }
  vtkShaderProgram::Substitute(vertex, "//MESO::Warp::Impl", position);
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
    if (data.WarpMethod == vtkMesoAtomGPUData::MOLECULE_INSTANCING)
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
    if (data.WarpMethod == vtkMesoAtomGPUData::MOLECULE_INSTANCING)
    {
      set_uniform_int(program, "atomMolecules", in.MoleculeTexture->GetTextureUnit());
    }
  }
  if (data.WarpMethod >= 0)
  {
    const char* buffer =
      data.WarpMethod == vtkMesoAtomGPUData::POLYNOMIAL ? "warpCoefficients" : "moleculeMotions";
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
  if (data.WarpMethod >= 0)
  {
    in.Warp.Texture->Activate();
  }
  if (data.WarpMethod == vtkMesoAtomGPUData::MOLECULE_INSTANCING)
  {
    in.MoleculeTexture->Activate();
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

  in.Current = Pass::Atoms;
  this->PrimitiveIDOffset = 0;
  vtkOpenGLHelper& spheres = this->Primitives[PrimitiveTris];
  this->UpdateShaders(spheres, ren, act);
  const bool translucent = act->GetProperty()->GetOpacity() < 1.0;
  if (grouped && this->OcclusionCulling && !picking && !translucent)
  {
    this->DrawVisibleCells(ren, act, spheres.Program);
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
  Internals& in = *this->Internal;
  const vtkMesoAtomGPUData& data = in.Data;
  auto* window = static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow());
  vtkOpenGLShaderCache* programs = window->GetShaderCache();

  // Model to clip coordinates, as the shaders see it (VTK keeps its matrices transposed).
  vtkMatrix4x4* wcvc = nullptr;
  vtkMatrix3x3* normals = nullptr;
  vtkMatrix4x4* vcdc = nullptr;
  vtkMatrix4x4* wcdc = nullptr;
  vtkCamera* camera = ren->GetActiveCamera();
  static_cast<vtkOpenGLCamera*>(camera)->GetKeyMatrices(ren, wcvc, normals, vcdc, wcdc);
  vtkNew<vtkMatrix4x4> mcdc;
  mcdc->DeepCopy(wcdc);
  if (!act->GetIsIdentity())
  {
    vtkMatrix4x4* mcwc = nullptr;
    vtkMatrix3x3* actor_normals = nullptr;
    static_cast<vtkOpenGLActor*>(act)->GetKeyMatrices(mcwc, actor_normals);
    vtkMatrix4x4::Multiply4x4(mcwc, wcdc, mcdc);
  }
  double model_to_clip[16];
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      model_to_clip[4 * r + c] = mcdc->GetElement(c, r);
    }
  }
  const double padding = 1.01 * data.LargestPresentRadius;
  const std::vector<mesolens::CellInView> cells =
    mesolens::cells_in_view(data.CellBoxes, padding, model_to_clip);

  // What each camera saw last time (the shadow pass's light camera sees other cells).
  CellHistory& history = in.History(camera, data.CellsVersion, data.Cells.cell_count());
  const bool known = history.Known;
  in.CellBoxes.Texture->Activate();
  in.LastDrawnAtoms = 0;
  std::vector<std::size_t> tested; // indices into cells
  std::vector<std::size_t> drawn;
  std::vector<GLint> firsts;
  std::vector<GLsizei> counts;
  auto add = [&](std::size_t k) {
    const std::uint32_t cell = cells[k].cell;
    const std::uint32_t first = data.Cells.cell_start[cell];
    const std::uint32_t count = data.Cells.cell_start[cell + 1] - first;
    firsts.push_back(static_cast<GLint>(3 * first));
    counts.push_back(static_cast<GLsizei>(3 * count));
    in.LastDrawnAtoms += count;
    drawn.push_back(k);
  };
  auto draw = [&]() {
    if (!firsts.empty())
    {
      programs->ReadyShaderProgram(spheres);
      glMultiDrawArrays(GL_TRIANGLES, firsts.data(), counts.data(),
                        static_cast<GLsizei>(firsts.size()));
      firsts.clear();
      counts.clear();
    }
  };

  if (known)
  {
    // The cells seen last time first, then the others whose boxes show past that depth.
    for (std::size_t k = 0; k < cells.size(); ++k)
    {
      if (cells[k].must_draw || history.Visible[cells[k].cell])
      {
        add(k);
      }
      else
      {
        tested.push_back(k);
      }
    }
    draw();
    for (std::size_t k : in.TestBoxes(window, mcdc, padding, cells, tested))
    {
      add(k);
    }
    draw();
  }
  else
  {
    // No history: waves, nearest first, doubling in size; each wave's boxes are tested against
    // the depth of the waves before it.
    std::size_t wave = std::max<std::size_t>(8, cells.size() / 32);
    for (std::size_t begin = 0; begin < cells.size(); begin += wave, wave *= 2)
    {
      tested.clear();
      for (std::size_t k = begin; k < std::min(cells.size(), begin + wave); ++k)
      {
        if (cells[k].must_draw)
        {
          add(k);
        }
        else
        {
          tested.push_back(k);
        }
      }
      for (std::size_t k : in.TestBoxes(window, mcdc, padding, cells, tested))
      {
        add(k);
      }
      draw();
    }
  }
  // What the next frame draws first: the drawn cells whose boxes still show past the final
  // depth (a cell hidden by cells drawn after it drops out). A wrong guess costs time only: the
  // cells left out are tested next time.
  std::fill(history.Visible.begin(), history.Visible.end(), 0);
  for (std::size_t k : in.TestBoxes(window, mcdc, padding, cells, drawn))
  {
    history.Visible[cells[k].cell] = 1;
  }
  history.Known = true;
  programs->ReadyShaderProgram(spheres);
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
         in.MoleculeTexture.Get(), in.CellBoxes.Texture.Get(), in.SlotTexture.Get() })
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
  vtkPolyData* warp = this->WarpInput();
  const vtkMTimeType key =
    std::max({ atoms ? atoms->GetMTime() : 0, this->GetMTime(), warp ? warp->GetMTime() : 0 });
  if (atoms && key == in.BoundsTime)
  {
    std::copy(in.Bounds, in.Bounds + 6, this->Bounds);
    return;
  }
  this->Superclass::ComputeBounds();
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
    sizeof(unsigned short) * data.MoleculeSlots.size();
  return bytes / static_cast<double>(data.AtomCount);
}

vtkIdType vtkMesoAtomMapper::GetLastDrawnAtomCount() const
{
  return this->Internal->LastDrawnAtoms;
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
  in.UploadedMolecules = 0;
  in.UploadedBonds = 0;
  in.Colors.Release(window);
  in.PositionTexture->ReleaseGraphicsResources(window);
  in.TypeTexture->ReleaseGraphicsResources(window);
  in.MoleculeTexture->ReleaseGraphicsResources(window);
  in.Warp.Release(window);
  in.CellBoxes.Release(window);
  in.SlotTexture->ReleaseGraphicsResources(window);
  in.Slots->ReleaseGraphicsResources();
  in.UploadedSlots = 0;
  if (!in.Queries.empty())
  {
    // Query objects belong to the context of the window being released.
    if (auto* context = vtkOpenGLRenderWindow::SafeDownCast(window))
    {
      context->MakeCurrent();
      glDeleteQueries(static_cast<GLsizei>(in.Queries.size()), in.Queries.data());
    }
    in.Queries.clear();
  }
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
  os << indent << "Warp: " << (this->GetNumberOfInputConnections(1) ? "connected" : "none") << "\n";
}
