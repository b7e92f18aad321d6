// SPDX-License-Identifier: GPL-3.0-or-later
// Atom impostors, molecule instancing of the membrane mapping: one rigid motion per molecule and
// tile (the draw call's instance), 3 texels (the rows of a 3 x 4 matrix, patch to mesh
// coordinates) per motion; the atom's molecule slot selects its motion within the tile.
uniform samplerBuffer moleculeMotions;
uniform int moleculesPerTile;

vec3 warpedPosition(vec3 patchPosition, float moleculeSlot, int tile)
{
  int motion = 3 * (tile * moleculesPerTile + int(moleculeSlot + 0.5));
  vec4 p = vec4(patchPosition, 1.0);
  return vec3(dot(texelFetch(moleculeMotions, motion), p),
              dot(texelFetch(moleculeMotions, motion + 1), p),
              dot(texelFetch(moleculeMotions, motion + 2), p));
}
