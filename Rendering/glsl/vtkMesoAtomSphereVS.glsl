//VTK::System::Dec
// SPDX-License-Identifier: GPL-3.0-or-later
// Atom impostors, sphere pass, vertex stage: three vertices per atom (gl_VertexID = 3 atom +
// corner), no geometry stage. Each vertex fetches its atom from the atom buffers (position,
// type), takes it to view coordinates (directly or through the membrane warp of the current
// instance, the tile) and places its corner of one triangle that faces the eye around the
// sphere's silhouette (in perspective the tangent cone's circle, of radius r d / sqrt(d² - r²)
// at distance d). One triangle, not a quad: for the many small atoms of a large scene the cost
// per primitive outweighs the pixels. The atom's radius and colour come from tables indexed by
// its type. The buffers hold the atoms in slot order (grouped into cells for culling, drawn
// cell by cell); picking draws them in input order, so that atom i is primitive i, and finds
// each atom's slot in atomSlots. Culling draws lists of the slots of the atoms that may show.

uniform samplerBuffer atomPositions; // RGB32F, the vertex buffer itself
uniform samplerBuffer atomTypes;     // RG8: element, colour index (normalised)
uniform samplerBuffer atomMolecules; // R16: molecule slot (normalised), molecule instancing only
uniform samplerBuffer atomColorTable;
//MESO::AtomSlot::Dec
uniform float atomRadii[128];
uniform mat4 MCVCMatrix;
uniform mat4 VCDCMatrix;
uniform int cameraParallel;

// Named like the bond pass's geometry-stage outputs: both passes share the fragment code.
out vec4 vertexVCGSOutput;
flat out float radiusVCGSOutput;
flat out vec3 centerVCGSOutput;
flat out vec4 atomColorGSOutput;

//MESO::Warp::Dec
//MESO::MoleculeMask::Dec

// clipping plane vars
//VTK::Clip::Dec

// picking support
//VTK::Picking::Dec

// The equilateral triangle around the unit circle: corners at distance 2 from its centre.
const vec2 triangleCorners[3] = vec2[3](vec2(-1.7320508, -1.0), vec2(1.7320508, -1.0),
                                        vec2(0.0, 2.0));

void main()
{
  int drawn = gl_VertexID / 3;
  int corner = gl_VertexID - 3 * drawn;
  int atom = drawn;
  int slot = atom;
  int tile = gl_InstanceID; // of a warp

  //MESO::AtomSlot::Impl
  vec3 atomPosition = texelFetch(atomPositions, slot).xyz;
  vec2 type = floor(texelFetch(atomTypes, slot).xy * 255.0 + 0.5);
  float radius = atomRadii[min(int(type.x), 127)];
  atomColorGSOutput = texelFetch(atomColorTable, int(type.y));
  vec4 vertexMC = vec4(atomPosition, 1.0);

  //MESO::Warp::Impl
  //MESO::MoleculeMask::Impl

  vec3 centre = gl_Position.xyz;
  vec3 across = vec3(1.0, 0.0, 0.0);
  vec3 up = vec3(0.0, 1.0, 0.0);
  float size = radius;
  if (cameraParallel == 0)
  {
    float distance = length(centre);
    // The eye inside the atom: a degenerate triangle, nothing drawn.
    size = distance > radius ? radius * distance / sqrt(distance * distance - radius * radius)
                             : 0.0;
    vec3 towardsEye = -centre / distance;
    vec3 helper = abs(towardsEye.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
    up = normalize(cross(towardsEye, helper));
    across = cross(up, towardsEye);
  }
  size *= 1.01; // a margin for rasterisation
  vec2 offset = triangleCorners[corner];
  radiusVCGSOutput = radius;
  centerVCGSOutput = centre;
  vertexVCGSOutput = vec4(centre + size * (offset.x * across + offset.y * up), 1.0);
  gl_Position = VCDCMatrix * vertexVCGSOutput;

  //VTK::Clip::Impl

  //VTK::Picking::Impl
}
