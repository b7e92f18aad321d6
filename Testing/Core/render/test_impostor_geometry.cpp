// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/render/impostor_geometry.h"

#include <gtest/gtest.h>

#include <cmath>

TEST(ImpostorGeometry, SphereHitsAndMisses)
{
  const auto hit = mesolens::ray_sphere({ 0, 0, 10 }, { 0, 0, -1 }, { 0, 0, 0 }, 2.0);
  ASSERT_TRUE(hit);
  EXPECT_DOUBLE_EQ(hit->t, 8.0);
  EXPECT_DOUBLE_EQ(hit->point[2], 2.0);
  EXPECT_DOUBLE_EQ(hit->normal[2], 1.0);
  // Grazing ray at distance 1.9 from the centre.
  const auto graze = mesolens::ray_sphere({ 1.9, 0, 10 }, { 0, 0, -1 }, { 0, 0, 0 }, 2.0);
  ASSERT_TRUE(graze);
  EXPECT_NEAR(graze->point[2], std::sqrt(4.0 - 1.9 * 1.9), 1e-12);
  EXPECT_FALSE(mesolens::ray_sphere({ 2.1, 0, 10 }, { 0, 0, -1 }, { 0, 0, 0 }, 2.0));
  EXPECT_FALSE(mesolens::ray_sphere({ 0, 0, 10 }, { 0, 0, 1 }, { 0, 0, 0 }, 2.0)); // behind
}

TEST(ImpostorGeometry, TinySphereFarAwayKeepsItsPrecisionInFloat)
{
  // An atom of radius 1.5e-4 (Å in µm) 1 unit from the eye, hit 70 % of the way to its rim.
  const float r = 1.5e-4f;
  const auto normal =
    mesolens::ray_sphere_normal_float({ 0.7f * r, 0, 0 }, { 0, 0, -1 }, { 0, 0, -1 }, r);
  ASSERT_TRUE(normal);
  EXPECT_NEAR((*normal)[0], 0.7f, 1e-4f);
  EXPECT_NEAR((*normal)[2], std::sqrt(1 - 0.49f), 1e-4f);
  // The textbook b² - c form of the same discriminant is all rounding error in float.
  const float b = -1.0f;
  const float c = 1.0f + 0.49f * r * r - r * r;
  EXPECT_GT(std::abs((b * b - c) - 0.51f * r * r), 0.5f * 0.51f * r * r);
}

TEST(ImpostorGeometry, CylinderSideAndEnds)
{
  // Axis along x from 0 to 4, radius 1; a ray down the z axis at x = 2 hits the top at z = 1.
  const auto hit =
    mesolens::ray_cylinder({ 2, 0, 10 }, { 0, 0, -1 }, { 0, 0, 0 }, { 4, 0, 0 }, 1.0);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 9.0, 1e-12);
  EXPECT_NEAR(hit->normal[2], 1.0, 1e-12);
  // Off the segment's ends, the open cylinder is missed.
  EXPECT_FALSE(mesolens::ray_cylinder({ 5, 0, 10 }, { 0, 0, -1 }, { 0, 0, 0 }, { 4, 0, 0 }, 1.0));
  // An oblique ray: compare with the implicit equation y² + z² = 1 at the hit.
  const double s = 1 / std::sqrt(3.0);
  const auto oblique =
    mesolens::ray_cylinder({ 1, -3, 3 }, { s, s, -s }, { 0, 0, 0 }, { 10, 0, 0 }, 1.0);
  ASSERT_TRUE(oblique);
  EXPECT_NEAR(oblique->point[1] * oblique->point[1] + oblique->point[2] * oblique->point[2], 1.0,
              1e-12);
  EXPECT_FALSE(mesolens::ray_cylinder({ 0, 0, 10 }, { 1, 0, 0 }, { 0, 0, 0 }, { 4, 0, 0 }, 1.0));
}

TEST(ImpostorGeometry, FloatCylinderTwinAgreesWithTheReference)
{
  const mesolens::Vector3 origin{ 1.3, 0.4, 10 };
  const mesolens::Vector3 direction{ 0, 0, -1 };
  const auto reference = mesolens::ray_cylinder(origin, direction, { 0, 0, 0 }, { 4, 0, 0 }, 1.0);
  const auto twin =
    mesolens::ray_cylinder_float({ 1.3f, 0.4f, 10 }, { 0, 0, -1 }, { 0, 0, 0 }, { 4, 0, 0 }, 1.0f);
  ASSERT_TRUE(reference);
  ASSERT_TRUE(twin);
  for (int d = 0; d < 3; ++d)
  {
    EXPECT_NEAR(twin->normal[std::size_t(d)], reference->normal[std::size_t(d)], 1e-5);
  }
  EXPECT_NEAR(twin->axial, 1.3 / 4, 1e-6);
  // Past the ends, and along the axis: no hit.
  EXPECT_FALSE(
    mesolens::ray_cylinder_float({ 4.5f, 0, 10 }, { 0, 0, -1 }, { 0, 0, 0 }, { 4, 0, 0 }, 1.0f));
  EXPECT_FALSE(
    mesolens::ray_cylinder_float({ -10, 0, 0 }, { 1, 0, 0 }, { 0, 0, 0 }, { 4, 0, 0 }, 1.0f));
}

TEST(ImpostorGeometry, TinyBondFarAwayKeepsItsPrecisionInFloat)
{
  // A bond of radius 2e-5 and length 1.5e-4 (Å in µm) one unit from the eye, seen from the
  // side: the normal at a hit 60 % of the way to its silhouette.
  const float r = 2e-5f;
  const float length = 1.5e-4f;
  const auto hit = mesolens::ray_cylinder_float({ 0.3f * length, 0.6f * r, 0 }, { 0, 0, -1 },
                                                { 0, 0, -1 }, { length, 0, -1 }, r);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->normal[1], 0.6f, 2e-3f);
  EXPECT_NEAR(hit->normal[2], 0.8f, 2e-3f);
  EXPECT_NEAR(hit->axial, 0.3f, 1e-3f);
}
