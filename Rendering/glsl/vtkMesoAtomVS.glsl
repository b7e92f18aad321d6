//VTK::System::Dec
// SPDX-License-Identifier: GPL-3.0-or-later
// Atom impostors, vertex stage, shared by the atom (sphere) and bond (cylinder) passes: one
// vertex per atom. Its position goes to view coordinates, directly or through the membrane warp
// of the current instance (tile); its radius and colour come from tables indexed by its type.

in vec3 atomPosition;
in vec2 atomType; // (element for the radius, colour index)

uniform mat4 MCVCMatrix;
uniform float atomRadii[128];
uniform samplerBuffer atomColorTable;

out float radiusVCVSOutput;
out vec4 atomColorVSOutput;

//MESO::Warp::Dec

// clipping plane vars
//VTK::Clip::Dec

// picking support
//VTK::Picking::Dec

void main()
{
  radiusVCVSOutput = atomRadii[clamp(int(atomType.x + 0.5), 0, 127)];
  atomColorVSOutput = texelFetch(atomColorTable, int(atomType.y + 0.5));
  vec4 vertexMC = vec4(atomPosition, 1.0);

  //MESO::Warp::Impl

  //VTK::Clip::Impl

  //VTK::Picking::Impl
}
