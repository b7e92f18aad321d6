//VTK::System::Dec
// SPDX-License-Identifier: GPL-3.0-or-later
// Occlusion test of the atom mapper's cells, vertex stage: the 12 triangles of cell
// gl_VertexID / 36's box of atom centres, grown by the largest atom radius, without vertex
// buffers (the boxes are a texture buffer). Drawn without colour or depth writes inside an
// occlusion query: any fragment that passes the depth test means the cell may be visible.

uniform samplerBuffer cellBoxes; // RGBA32F, 2 texels per cell: min corner, max corner
uniform mat4 MCDCMatrix;
uniform float cellPadding;

// Corner bits: 1 = max x, 2 = max y, 4 = max z; two triangles per face.
const int boxCorners[36] = int[36](0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6,
                                   3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5);

void main()
{
  int cell = gl_VertexID / 36;
  int corner = boxCorners[gl_VertexID - 36 * cell];
  vec3 low = texelFetch(cellBoxes, 2 * cell).xyz - vec3(cellPadding);
  vec3 high = texelFetch(cellBoxes, 2 * cell + 1).xyz + vec3(cellPadding);
  vec3 position = vec3((corner & 1) != 0 ? high.x : low.x, (corner & 2) != 0 ? high.y : low.y,
                       (corner & 4) != 0 ? high.z : low.z);
  gl_Position = MCDCMatrix * vec4(position, 1.0);
}
