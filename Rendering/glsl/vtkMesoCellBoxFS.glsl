//VTK::System::Dec
// SPDX-License-Identifier: GPL-3.0-or-later
// Occlusion test of the atom mapper's cells, fragment stage: nothing is written (colour and
// depth writes are off); the query counts the fragments that pass the depth test.

//VTK::Output::Dec

void main()
{
  gl_FragData[0] = vec4(1.0);
}
