//VTK::System::Dec
// SPDX-License-Identifier: GPL-3.0-or-later
// Atom impostors, sphere pass, geometry stage: each atom becomes a quad in view coordinates that
// covers the sphere's silhouette (in perspective the tangent cone's: half size r d / sqrt(d² -
// r²) at distance d).

//VTK::PrimID::Dec

layout(points) in;
layout(triangle_strip, max_vertices = 4) out;

uniform int cameraParallel;
uniform mat4 VCDCMatrix;

in float radiusVCVSOutput[];
in vec4 atomColorVSOutput[];

out vec4 vertexVCGSOutput;
flat out float radiusVCGSOutput;
flat out vec3 centerVCGSOutput;
flat out vec4 atomColorGSOutput;

//VTK::Clip::Dec

//VTK::Picking::Dec

void main()
{
  float radius = radiusVCVSOutput[0];
  if (radius <= 0.0)
  {
    return;
  }
  vec3 centre = gl_in[0].gl_Position.xyz;

  vec3 across = vec3(1.0, 0.0, 0.0);
  vec3 up = vec3(0.0, 1.0, 0.0);
  float halfSize = radius;
  if (cameraParallel == 0)
  {
    float distance = length(centre);
    if (distance <= radius)
    {
      return; // the eye is inside this atom
    }
    vec3 towardsEye = -centre / distance;
    vec3 helper = abs(towardsEye.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
    up = normalize(cross(towardsEye, helper));
    across = cross(up, towardsEye);
    halfSize = radius * distance / sqrt(distance * distance - radius * radius);
  }
  halfSize *= 1.01; // a margin for rasterisation

  //VTK::PrimID::Impl

  //VTK::Clip::Impl

  for (int corner = 0; corner < 4; ++corner)
  {
    int i = 0; // VTK's point picking passes on the id of vertex i (the first atom)
    //VTK::Picking::Impl
    vec2 offset = vec2(corner == 1 || corner == 3 ? 1.0 : -1.0, corner >= 2 ? 1.0 : -1.0);
    radiusVCGSOutput = radius;
    atomColorGSOutput = atomColorVSOutput[0];
    centerVCGSOutput = centre;
    vertexVCGSOutput = vec4(centre + halfSize * (offset.x * across + offset.y * up), 1.0);
    gl_Position = VCDCMatrix * vertexVCGSOutput;
    EmitVertex();
  }
  EndPrimitive();
}
