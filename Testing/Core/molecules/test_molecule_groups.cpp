// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/molecules/molecule_groups.h"

#include "mesolens/common/errors.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace {

TEST(MoleculeGroups, MoleculesInOrderOfFirstAppearanceWithTheirAtoms)
{
  // Molecule 7's atoms are not consecutive; ids may be negative or far apart.
  const std::vector<int> ids = { 7, 7, -3, 7, 2000000000, -3 };
  const auto groups = mesolens::group_molecules(ids.data(), ids.size());
  ASSERT_EQ(groups.count(), 3u);
  EXPECT_EQ(groups.ids, (std::vector<int>{ 7, -3, 2000000000 }));
  EXPECT_EQ(groups.of_atom, (std::vector<std::uint32_t>{ 0, 0, 1, 0, 2, 1 }));
  EXPECT_EQ(groups.first, (std::vector<std::size_t>{ 0, 3, 5, 6 }));
  EXPECT_EQ(groups.atoms, (std::vector<std::uint32_t>{ 0, 1, 3, 2, 5, 4 }));
  EXPECT_EQ(groups.size_of(1), 2u);
  std::vector<std::uint32_t> of_first;
  for (const std::uint32_t a : groups.atoms_of(0))
  {
    of_first.push_back(a);
  }
  EXPECT_EQ(of_first, (std::vector<std::uint32_t>{ 0, 1, 3 }));
}

TEST(MoleculeGroups, WithoutIdsEveryAtomIsAMolecule)
{
  const auto groups = mesolens::group_molecules(nullptr, 4);
  EXPECT_EQ(groups.count(), 4u);
  EXPECT_EQ(groups.ids, (std::vector<int>{ 0, 1, 2, 3 }));
  const auto none = mesolens::group_molecules(nullptr, 0);
  EXPECT_EQ(none.count(), 0u);
  EXPECT_EQ(none.first, (std::vector<std::size_t>{ 0 }));
}

TEST(MoleculeGroups, CentresAreMeansOrCentresOfMass)
{
  const std::vector<int> ids = { 1, 2, 1 };
  const auto groups = mesolens::group_molecules(ids.data(), ids.size());
  const std::vector<float> positions = { 0, 0, 0, 5, 5, 5, 2, 4, 6 };
  EXPECT_EQ(mesolens::molecule_centres(groups, positions),
            (std::vector<double>{ 1, 2, 3, 5, 5, 5 }));
  const std::vector<float> masses = { 3, 1, 1 };
  EXPECT_EQ(mesolens::molecule_centres(groups, positions, masses.data()),
            (std::vector<double>{ 0.5, 1, 1.5, 5, 5, 5 }));
  const std::vector<double> doubles(positions.begin(), positions.end());
  EXPECT_EQ(mesolens::molecule_centres(groups, doubles), (std::vector<double>{ 1, 2, 3, 5, 5, 5 }));
}

TEST(MoleculeGroups, NonFinitePositionsAreNamed)
{
  const auto groups = mesolens::group_molecules(nullptr, 2);
  const std::vector<float> positions = { 0, 0, 0, 1, std::nanf(""), 1 };
  try
  {
    mesolens::molecule_centres(groups, positions);
    ADD_FAILURE() << "a NaN coordinate was accepted";
  }
  catch (const mesolens::InvalidInput& e)
  {
    EXPECT_NE(std::string(e.what()).find("atom 1"), std::string::npos) << e.what();
  }
}

TEST(MoleculeGroups, CentresNeedOnePositionPerGroupedAtom)
{
  const auto groups = mesolens::group_molecules(nullptr, 3);
  const std::vector<float> two_atoms = { 0, 0, 0, 1, 1, 1 };
  EXPECT_THROW(mesolens::molecule_centres(groups, two_atoms), mesolens::InvalidInput);
}

} // namespace
