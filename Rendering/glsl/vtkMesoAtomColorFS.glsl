  // SPDX-License-Identifier: GPL-3.0-or-later
  // Atom impostors: the colour of the atom (or of the bond half) modulates the material's.
  ambientColor *= impostorColor.rgb;
  diffuseColor *= impostorColor.rgb;
  opacity *= impostorColor.a;
