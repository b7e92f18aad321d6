  // SPDX-License-Identifier: GPL-3.0-or-later
  // Atom impostors, bond pass: the ray through this fragment against the bond's open cylinder
  // (the atoms close its ends). The ray starts at its closest approach to the bond's middle, so
  // Å bonds in a µm scene keep their precision. The half nearer the start takes the start atom's
  // colour. C++ twin: mesolens::ray_cylinder_float.
  vec3 rayDirection = normalize(vertexVC.xyz);
  vec3 rayOrigin = vec3(0.0);
  if (cameraParallel != 0)
  {
    rayDirection = vec3(0.0, 0.0, -1.0);
    rayOrigin = vec3(vertexVC.xy, 0.0);
  }
  vec3 middle = 0.5 * (bondStartVCGSOutput + bondEndVCGSOutput);
  float shift = dot(middle - rayOrigin, rayDirection);
  rayOrigin += shift * rayDirection;
  vec3 bondAxis = bondEndVCGSOutput - bondStartVCGSOutput;
  vec3 fromStart = rayOrigin - bondStartVCGSOutput;
  float axis2 = dot(bondAxis, bondAxis);
  float axisRay = dot(bondAxis, rayDirection);
  float axisStart = dot(bondAxis, fromStart);
  float k2 = axis2 - axisRay * axisRay;
  float k1 = axis2 * dot(fromStart, rayDirection) - axisStart * axisRay;
  float k0 = axis2 * dot(fromStart, fromStart) - axisStart * axisStart -
    bondRadius * bondRadius * axis2;
  float discriminant = k1 * k1 - k2 * k0;
  if (k2 <= 0.0 || discriminant < 0.0)
  {
    discard;
  }
  float hitAlong = (-k1 - invertedDepth * sqrt(discriminant)) / k2;
  float axial = (axisStart + hitAlong * axisRay) / axis2;
  if (axial < 0.0 || axial > 1.0)
  {
    discard;
  }
  vec3 hit = rayOrigin + hitAlong * rayDirection;
  vec3 normalVCVSOutput =
    invertedDepth * (hit - bondStartVCGSOutput - axial * bondAxis) / bondRadius;
  vertexVC.xyz = hit;
  vec4 impostorColor = axial < 0.5 ? bondStartColorGSOutput : bondEndColorGSOutput;
  vec4 depthDC = VCDCMatrix * vertexVC;
  gl_FragDepth = (depthDC.z / depthDC.w + 1.0) / 2.0;
