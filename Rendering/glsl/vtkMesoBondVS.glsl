//VTK::System::Dec
// SPDX-License-Identifier: GPL-3.0-or-later
// Atom impostors, bond pass, vertex stage: one vertex per atom, the bonds index them. Its
// position goes to view coordinates, directly or through the membrane warp of the current
// instance (tile); its colour comes from the table indexed by its type.

in vec3 atomPosition;
in vec2 atomType; // (element, colour index)
in float atomMolecule; // molecule slot, molecule instancing only

uniform mat4 MCVCMatrix;
uniform samplerBuffer atomColorTable;

out vec4 atomColorVSOutput;
out float atomHiddenVSOutput; // 1: hidden by a visibility mask (element 127)

//MESO::Warp::Dec
//MESO::MoleculeMask::Dec

// clipping plane vars
//VTK::Clip::Dec

// picking support
//VTK::Picking::Dec

void main()
{
  atomColorVSOutput = texelFetch(atomColorTable, int(atomType.y + 0.5));
  atomHiddenVSOutput = atomType.x > 126.5 ? 1.0 : 0.0;
  vec4 vertexMC = vec4(atomPosition, 1.0);

  //MESO::Warp::Impl
  //MESO::MoleculeMask::Impl

  //VTK::Clip::Impl

  //VTK::Picking::Impl
}
