// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/molecules/elements.h"

#include <gtest/gtest.h>

TEST(Elements, SymbolsRoundTrip)
{
  for (int z = 1; z <= mesolens::max_atomic_number; ++z)
  {
    EXPECT_EQ(mesolens::atomic_number_from_symbol(mesolens::element_symbol(z)), z) << z;
  }
  EXPECT_STREQ(mesolens::element_symbol(26), "Fe");
  EXPECT_STREQ(mesolens::element_symbol(0), "X");
  EXPECT_STREQ(mesolens::element_symbol(500), "X");
  EXPECT_EQ(mesolens::atomic_number_from_symbol("FE"), 26);
  EXPECT_EQ(mesolens::atomic_number_from_symbol(" d"), 1);
  EXPECT_EQ(mesolens::atomic_number_from_symbol("Qq"), 0);
  EXPECT_EQ(mesolens::atomic_number_from_symbol(""), 0);
}

TEST(Elements, RadiiOfCommonElements)
{
  EXPECT_FLOAT_EQ(mesolens::covalent_radius(6), 0.73f); // Cordero 2008, sp3 carbon
  EXPECT_FLOAT_EQ(mesolens::covalent_radius(1), 0.31f);
  EXPECT_FLOAT_EQ(mesolens::van_der_waals_radius(6), 1.70f); // Bondi 1964
  EXPECT_FLOAT_EQ(mesolens::van_der_waals_radius(8), 1.52f);
  EXPECT_GT(mesolens::covalent_radius(0), 0.0f);
}

TEST(Elements, GuessFromAtomNames)
{
  EXPECT_EQ(mesolens::guess_atomic_number("CA", "ALA"), 6); // C-alpha, not calcium
  EXPECT_EQ(mesolens::guess_atomic_number("CA", "CA"), 20); // calcium ion
  EXPECT_EQ(mesolens::guess_atomic_number("NA", "NA"), 11);
  EXPECT_EQ(mesolens::guess_atomic_number("CLA", "CLA"), 17);
  EXPECT_EQ(mesolens::guess_atomic_number("SOD", "SOD"), 11);
  EXPECT_EQ(mesolens::guess_atomic_number("1HB", "ALA"), 1);
  EXPECT_EQ(mesolens::guess_atomic_number("H12X", "POPE"), 1);
  EXPECT_EQ(mesolens::guess_atomic_number("P", "DPPC"), 15);
  EXPECT_EQ(mesolens::guess_atomic_number("O11", "DPPC"), 8);
  EXPECT_EQ(mesolens::guess_atomic_number("GL1", "DPPC"), 0); // Martini bead: no element
  EXPECT_EQ(mesolens::guess_atomic_number("", "X"), 0);
}
