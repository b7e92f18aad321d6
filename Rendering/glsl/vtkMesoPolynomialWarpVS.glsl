// SPDX-License-Identifier: GPL-3.0-or-later
// Atom impostors, the membrane-mapping warp (Waltemate et al. 2014): one quadratic x(s, t, h)
// per piece of a tile split m_t x m_t, the tile being the draw call's instance. The buffer
// starts with one texel per tile (polynomialTiles of them): its first piece and m_t; then 10
// texels per piece, one per monomial (1, s, t, h, s², st, sh, t², th, h²) holding its (x, y, z)
// coefficients (mesh coordinates); the tile's piece (i, j) is its first + j m_t + i. (s, t) =
// 2 f - 1 from the fractional coordinates f of the patch atom in its piece, h = (z - centre) /
// e. C++ twins: mesolens::polynomial_coordinates, mesolens::polynomial_piece and
// mesolens::evaluate_tile_polynomial.
uniform samplerBuffer warpCoefficients;
uniform vec2 patchOrigin;
uniform vec4 patchToFractional; // the 2 x 2 inverse of the cell (a, b), column-major
uniform float patchCentreHeight;
uniform float inverseLayerHalfThickness;
uniform int polynomialTiles;

vec3 warpedPosition(vec3 patchPosition, float moleculeSlot, int tile) // slot unused
{
  vec2 st = 2.0 * (mat2(patchToFractional) * (patchPosition.xy - patchOrigin)) - 1.0;
  float h = (patchPosition.z - patchCentreHeight) * inverseLayerHalfThickness;
  vec4 header = texelFetch(warpCoefficients, tile);
  int first = int(header.x + 0.5);
  int splits = int(header.y + 0.5);
  vec2 f = 0.5 * (st + 1.0) * float(splits);
  ivec2 piece = clamp(ivec2(floor(f)), ivec2(0), ivec2(splits - 1));
  st = 2.0 * (f - vec2(piece)) - 1.0;
  int base = polynomialTiles + 10 * (first + piece.y * splits + piece.x);
  vec3 position = texelFetch(warpCoefficients, base).xyz;
  position += st.x * texelFetch(warpCoefficients, base + 1).xyz;
  position += st.y * texelFetch(warpCoefficients, base + 2).xyz;
  position += h * texelFetch(warpCoefficients, base + 3).xyz;
  position += st.x * st.x * texelFetch(warpCoefficients, base + 4).xyz;
  position += st.x * st.y * texelFetch(warpCoefficients, base + 5).xyz;
  position += st.x * h * texelFetch(warpCoefficients, base + 6).xyz;
  position += st.y * st.y * texelFetch(warpCoefficients, base + 7).xyz;
  position += st.y * h * texelFetch(warpCoefficients, base + 8).xyz;
  position += h * h * texelFetch(warpCoefficients, base + 9).xyz;
  return position;
}
