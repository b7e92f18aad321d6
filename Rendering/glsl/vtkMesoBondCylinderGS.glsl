//VTK::System::Dec
// SPDX-License-Identifier: GPL-3.0-or-later
// Atom impostors, bond pass, geometry stage: each bond becomes a quad facing the eye that covers
// the cylinder: the corners of the cylinder's bounding box are projected from the eye onto a
// plane in front of it and the quad spans their extent.

//VTK::PrimID::Dec

layout(lines) in;
layout(triangle_strip, max_vertices = 4) out;

uniform int cameraParallel;
uniform mat4 VCDCMatrix;
uniform float bondRadius;

in vec4 atomColorVSOutput[];
in float atomHiddenVSOutput[];

out vec4 vertexVCGSOutput;
flat out vec3 bondStartVCGSOutput;
flat out vec3 bondEndVCGSOutput;
flat out vec4 bondStartColorGSOutput;
flat out vec4 bondEndColorGSOutput;

//VTK::Clip::Dec

//VTK::Picking::Dec

void main()
{
  vec3 start = gl_in[0].gl_Position.xyz;
  vec3 end = gl_in[1].gl_Position.xyz;
  vec3 axis = end - start;
  float length2 = dot(axis, axis);
  if (length2 <= 0.0 || bondRadius <= 0.0 || atomHiddenVSOutput[0] + atomHiddenVSOutput[1] > 0.0)
  {
    return;
  }
  axis /= sqrt(length2);
  vec3 helper = abs(axis.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
  vec3 side = normalize(cross(axis, helper));
  vec3 third = cross(axis, side);

  // The bounding box's corners projected onto the plane z = nearest, towards the eye.
  float nearest = max(start.z, end.z) + bondRadius * 1.8;
  if (cameraParallel == 0 && nearest >= 0.0)
  {
    return; // the bond reaches behind the eye
  }
  vec2 lower = vec2(1e38);
  vec2 upper = vec2(-1e38);
  for (int corner = 0; corner < 8; ++corner)
  {
    vec3 p = ((corner & 1) == 0 ? start - bondRadius * axis : end + bondRadius * axis) +
      bondRadius * ((corner & 2) == 0 ? -side : side) +
      bondRadius * ((corner & 4) == 0 ? -third : third);
    vec2 projected = cameraParallel == 0 ? p.xy * (nearest / p.z) : p.xy;
    lower = min(lower, projected);
    upper = max(upper, projected);
  }

  //VTK::PrimID::Impl

  //VTK::Clip::Impl

  for (int corner = 0; corner < 4; ++corner)
  {
    int i = 0; // VTK's point picking passes on the id of vertex i (the first atom)
    //VTK::Picking::Impl
    bondStartVCGSOutput = start;
    bondEndVCGSOutput = end;
    bondStartColorGSOutput = atomColorVSOutput[0];
    bondEndColorGSOutput = atomColorVSOutput[1];
    vertexVCGSOutput = vec4(corner == 1 || corner == 3 ? upper.x : lower.x,
                            corner >= 2 ? upper.y : lower.y, nearest, 1.0);
    gl_Position = VCDCMatrix * vertexVCGSOutput;
    EmitVertex();
  }
  EndPrimitive();
}
