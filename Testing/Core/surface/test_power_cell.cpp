// SPDX-License-Identifier: GPL-3.0-or-later
// The planes bounding a sphere's power cell near it (a private part of MesoLensCore, which
// keeps only those neighbours' caps where a sphere has many): simple cases, the exposed area
// unchanged by dropping the others, and an empty cell.
#include "surface/detail/power_cell.h"
#include "surface/detail/sas_boundary.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <random>

namespace {
using Vec = Eigen::Vector3d;
using mesolens::PowerPlane;

std::vector<char> faces(const std::vector<PowerPlane>& planes, int expected_state = 1)
{
  mesolens::PowerCellWork work;
  std::vector<char> bounding;
  EXPECT_EQ(mesolens::power_cell_faces(planes, bounding, work), expected_state);
  return bounding;
}
} // namespace

TEST(PowerCell, ANearerParallelPlaneHidesAFartherOne)
{
  const Vec axis = Vec(0.2, -0.4, 0.9).normalized();
  EXPECT_EQ(faces({ { axis, 0.3 }, { axis, 0.6 } }), (std::vector<char>{ 1, 0 }));
  // Taken the other way round, the farther one cuts first and is cut away by the nearer.
  EXPECT_EQ(faces({ { axis, 0.6 }, { axis, 0.3 } }), (std::vector<char>{ 0, 1 }));
  // Opposite planes both bound the slab between them.
  EXPECT_EQ(faces({ { axis, 0.3 }, { -axis, 0.2 } }), (std::vector<char>{ 1, 1 }));
}

TEST(PowerCell, PlanesLeavingNothingMakeAnEmptyCell)
{
  // x >= 0.5 and x <= -0.5.
  faces({ { -Vec::UnitX(), -0.5 }, { Vec::UnitX(), -0.5 } }, 0);
  // A plane through a corner of the cube touches it: bounding, not empty.
  const Vec diagonal = Vec::Ones().normalized();
  EXPECT_EQ(faces({ { diagonal, std::sqrt(3.0) } }), (std::vector<char>{ 1 }));
}

TEST(PowerCell, DroppingTheOtherPlanesLeavesTheExposedAreaAsItWas)
{
  // Spheres of the unit sphere's radius around it, 0.6 to 1.9 away, their caps' planes largest
  // first, as the accessible boundary takes them.
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), distance(0.6, 1.9);
  std::size_t planes_seen = 0, planes_kept = 0;
  for (int trial = 0; trial < 200; ++trial)
  {
    std::vector<mesolens::UnitCap> caps;
    const int count = 5 + trial % 60;
    while (int(caps.size()) < count)
    {
      const Vec axis(unit(random), unit(random), unit(random));
      if (axis.norm() < 0.1 || axis.norm() > 1)
      {
        continue;
      }
      const double d = distance(random);
      caps.push_back({ axis.normalized(), d / 2.0 }); // (1 + d^2 - 1) / 2d
    }
    std::sort(caps.begin(), caps.end(),
              [](const auto& a, const auto& b) { return a.height < b.height; });
    std::vector<PowerPlane> planes;
    for (const auto& cap : caps)
    {
      planes.push_back({ cap.axis, cap.height });
    }
    mesolens::PowerCellWork work;
    std::vector<char> bounding;
    const int state = mesolens::power_cell_faces(planes, bounding, work);
    ASSERT_NE(state, 2) << "trial " << trial;
    double all_area = -1, kept_area = -1;
    Vec all_direction = Vec::Zero(), kept_direction = Vec::Zero();
    if (!mesolens::uncovered_unit_area(caps, all_area, all_direction))
    {
      continue; // a degenerate arrangement (rare)
    }
    if (state == 0)
    {
      EXPECT_NEAR(all_area, 0.0, 1e-12) << "trial " << trial;
      continue;
    }
    std::vector<mesolens::UnitCap> kept;
    for (std::size_t k = 0; k < caps.size(); ++k)
    {
      if (bounding[k])
      {
        kept.push_back(caps[k]);
      }
    }
    planes_seen += caps.size();
    planes_kept += kept.size();
    ASSERT_TRUE(mesolens::uncovered_unit_area(kept, kept_area, kept_direction));
    EXPECT_NEAR(kept_area, all_area, 1e-9) << "trial " << trial;
    EXPECT_NEAR((kept_direction - all_direction).norm(), 0.0, 1e-9) << "trial " << trial;
  }
  // The test means something only when planes are dropped: many are.
  EXPECT_LT(2 * planes_kept, planes_seen);
}
