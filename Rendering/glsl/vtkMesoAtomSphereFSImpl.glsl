  // SPDX-License-Identifier: GPL-3.0-or-later
  // Atom impostors, sphere pass: the ray through this fragment against the atom's sphere. The
  // discriminant comes from the ray's closest approach to the centre, r² - |q|², not b² - c:
  // atoms tiny next to their distance from the eye (Å in a µm scene) keep their precision.
  // C++ twin: mesolens::ray_sphere_normal_float. invertedDepth = -1 takes the far side (the
  // back halves of translucent atoms).
  vec3 rayOrigin = vec3(0.0);
  vec3 rayDirection = normalize(vertexVC.xyz);
  if (cameraParallel != 0)
  {
    rayOrigin = vec3(vertexVC.xy, centerVCGSOutput.z + 2.0 * radiusVCGSOutput);
    rayDirection = vec3(0.0, 0.0, -1.0);
  }
  vec3 toCentre = centerVCGSOutput - rayOrigin;
  float along = dot(toCentre, rayDirection);
  vec3 offsetFromRay = toCentre - along * rayDirection;
  float halfChord2 = radiusVCGSOutput * radiusVCGSOutput - dot(offsetFromRay, offsetFromRay);
  if (halfChord2 < 0.0)
  {
    discard;
  }
  vec3 fromCentre = -offsetFromRay - invertedDepth * sqrt(halfChord2) * rayDirection;
  vec3 normalVCVSOutput = invertedDepth * fromCentre / radiusVCGSOutput;
  vertexVC.xyz = centerVCGSOutput + fromCentre;
  vec4 impostorColor = atomColorGSOutput;
  vec4 depthDC = VCDCMatrix * vertexVC;
  gl_FragDepth = (depthDC.z / depthDC.w + 1.0) / 2.0;
