// SPDX-License-Identifier: GPL-3.0-or-later
// Atom impostors, sphere pass, fragment declarations.
uniform float invertedDepth;
uniform mat4 VCDCMatrix;
flat in float radiusVCGSOutput;
flat in vec3 centerVCGSOutput;
flat in vec4 atomColorGSOutput;
