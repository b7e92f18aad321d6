// SPDX-License-Identifier: GPL-3.0-or-later
// A synthetic bilayer patch for membrane-mapping tests.
#pragma once

#include "mesolens/mapping/membrane_mapping.h"

#include <random>
#include <vector>

namespace mesolens_test {

/// Molecules of 5 atoms in a 20 x 20 cell centred on the origin, alternately in the upper and
/// the lower leaflet, heights from 15 to 3 away from `centre_height` (seeded).
struct SyntheticPatch
{
  std::vector<float> positions;
  std::vector<int> molecule_ids;
  float centre_height = 0;

  mesolens::MembranePatch view() const
  {
    mesolens::MembranePatch patch;
    patch.positions = this->positions;
    patch.molecule_ids = this->molecule_ids.data();
    patch.origin = { -10, -10 };
    patch.a = { 20, 0 };
    patch.b = { 0, 20 };
    patch.centre_height = this->centre_height;
    return patch;
  }
};

inline SyntheticPatch synthetic_patch(int molecules, float centre_height = 0)
{
  std::mt19937 random(11);
  std::uniform_real_distribution<float> position(-9.0f, 9.0f);
  std::uniform_real_distribution<float> jitter(-1.5f, 1.5f);
  SyntheticPatch patch;
  patch.centre_height = centre_height;
  for (int m = 0; m < molecules; ++m)
  {
    const float x = position(random);
    const float y = position(random);
    const float sign = (m % 2) ? 1.0f : -1.0f; // upper or lower leaflet
    for (int a = 0; a < 5; ++a)
    {
      patch.positions.insert(patch.positions.end(),
                             { x + jitter(random), y + jitter(random),
                               centre_height + sign * (15.0f - 3.0f * float(a)) });
      patch.molecule_ids.push_back(m);
    }
  }
  return patch;
}

} // namespace mesolens_test
