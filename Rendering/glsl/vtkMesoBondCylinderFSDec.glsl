// SPDX-License-Identifier: GPL-3.0-or-later
// Atom impostors, bond pass, fragment declarations.
uniform float invertedDepth;
uniform float bondRadius;
uniform mat4 VCDCMatrix;
flat in vec3 bondStartVCGSOutput;
flat in vec3 bondEndVCGSOutput;
flat in vec4 bondStartColorGSOutput;
flat in vec4 bondEndColorGSOutput;
