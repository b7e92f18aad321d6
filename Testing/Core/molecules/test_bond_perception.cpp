// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/molecules/bond_perception.h"

#include "mesolens/molecules/bond_consensus.h"

#include "mesolens/molecules/elements.h"
#include "mesolens/common/errors.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace {
struct Atoms
{
  std::vector<float> positions;
  std::vector<std::uint8_t> elements;
  std::vector<int> molecules;
  std::vector<char> alt_locs;

  void add(float x, float y, float z, int element, int molecule = 0, char alt = ' ')
  {
    positions.insert(positions.end(), { x, y, z });
    elements.push_back(std::uint8_t(element));
    molecules.push_back(molecule);
    alt_locs.push_back(alt);
  }
  mesolens::BondPerceptionInput input() const
  {
    mesolens::BondPerceptionInput in;
    in.positions = positions;
    in.atomic_numbers = elements.data();
    in.molecule_ids = molecules.data();
    in.alt_locs = alt_locs.data();
    return in;
  }
};

/// Reference: every pair, same criterion.
std::vector<mesolens::Bond> brute_force(const Atoms& atoms, float tolerance)
{
  std::vector<mesolens::Bond> bonds;
  const std::size_t n = atoms.elements.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
    {
      if (atoms.molecules[i] != atoms.molecules[j])
        continue;
      double d2 = 0;
      for (int k = 0; k < 3; ++k)
      {
        const double d = double(atoms.positions[3 * i + k]) - atoms.positions[3 * j + k];
        d2 += d * d;
      }
      const double limit = double(mesolens::covalent_radius(atoms.elements[i])) +
        mesolens::covalent_radius(atoms.elements[j]) + tolerance;
      if (d2 < limit * limit && d2 >= 0.4 * 0.4)
        bonds.push_back({ std::uint32_t(i), std::uint32_t(j) });
    }
  return bonds;
}
} // namespace

TEST(BondPerception, CarbonCarbonDistances)
{
  Atoms atoms;
  atoms.add(0, 0, 0, 6);
  atoms.add(1.54f, 0, 0, 6); // single bond
  atoms.add(3.54f, 0, 0, 6); // 2.0 Å from the previous: beyond 0.73 + 0.73 + 0.45
  const auto bonds = mesolens::perceive_bonds(atoms.input());
  ASSERT_EQ(bonds.size(), 1u);
  EXPECT_EQ(bonds[0].first, 0u);
  EXPECT_EQ(bonds[0].second, 1u);
}

TEST(BondPerception, OnlyWithinOneMolecule)
{
  Atoms atoms;
  atoms.add(0, 0, 0, 6, 0);
  atoms.add(1.5f, 0, 0, 6, 1);
  EXPECT_TRUE(mesolens::perceive_bonds(atoms.input()).empty());
}

TEST(BondPerception, AlternateLocationsDoNotBondEachOther)
{
  Atoms atoms;
  atoms.add(0, 0, 0, 6, 0, 'A');
  atoms.add(1.5f, 0, 0, 6, 0, 'B');
  atoms.add(0.75f, 1.3f, 0, 6, 0, ' '); // 1.5 Å from both
  const auto bonds = mesolens::perceive_bonds(atoms.input());
  ASSERT_EQ(bonds.size(), 2u); // A-blank and B-blank, not A-B
  EXPECT_EQ(bonds[0].second, 2u);
  EXPECT_EQ(bonds[1].second, 2u);
}

TEST(BondPerception, NonFiniteAtomsNeverBond)
{
  Atoms atoms;
  atoms.add(0, 0, 0, 6);
  atoms.add(std::numeric_limits<float>::quiet_NaN(), 0, 0, 6);
  atoms.add(1.5f, 0, 0, 6);
  const auto bonds = mesolens::perceive_bonds(atoms.input());
  ASSERT_EQ(bonds.size(), 1u);
  EXPECT_EQ(bonds[0].second, 2u);
}

// Found by fuzz_gro: atoms 5e30 Å apart overflowed the neighbour grid's integer cell count.
TEST(BondPerception, AtomsFarApartStillBondTheirNeighbours)
{
  Atoms atoms;
  atoms.add(0, 0, 0, 6);
  atoms.add(1.5f, 0, 0, 6);
  atoms.add(5.2e30f, 0, -3e38f, 6);
  const auto bonds = mesolens::perceive_bonds(atoms.input());
  ASSERT_EQ(bonds.size(), 1u);
  EXPECT_EQ(bonds[0].first, 0u);
  EXPECT_EQ(bonds[0].second, 1u);
}

TEST(BondPerception, GridMatchesBruteForceOnRandomCloud)
{
  std::mt19937 random(42);
  std::uniform_real_distribution<float> coordinate(0.0f, 25.0f);
  std::uniform_int_distribution<int> element(0, 3);
  const int elements[] = { 1, 6, 7, 8 };
  Atoms atoms;
  for (int i = 0; i < 3000; ++i)
  {
    atoms.add(coordinate(random), coordinate(random), coordinate(random), elements[element(random)],
              i % 3);
  }
  const auto grid = mesolens::perceive_bonds(atoms.input());
  const auto reference = brute_force(atoms, 0.45f);
  EXPECT_GT(reference.size(), 100u);
  EXPECT_EQ(grid, reference);
}

TEST(BondPerception, CoarseGrainedBeadCutoff)
{
  Atoms atoms;
  atoms.add(0, 0, 0, 0);
  atoms.add(4.7f, 0, 0, 0);  // Martini bond length
  atoms.add(10.0f, 0, 0, 0); // 5.3 Å away: beyond the default 5 Å cutoff
  mesolens::BondPerceptionParams params;
  params.coarse_grained = true;
  const auto bonds = mesolens::perceive_bonds(atoms.input(), params);
  ASSERT_EQ(bonds.size(), 1u);
  EXPECT_TRUE(
    mesolens::looks_coarse_grained(atoms.input(), mesolens::perceive_bonds(atoms.input())));
  Atoms atomistic;
  atomistic.add(0, 0, 0, 6);
  atomistic.add(1.5f, 0, 0, 6);
  EXPECT_FALSE(
    mesolens::looks_coarse_grained(atomistic.input(), mesolens::perceive_bonds(atomistic.input())));
}

TEST(BondPerception, RejectsBadParameters)
{
  Atoms atoms;
  atoms.add(0, 0, 0, 6);
  mesolens::BondPerceptionParams params;
  params.tolerance = -1;
  EXPECT_THROW(mesolens::perceive_bonds(atoms.input(), params), mesolens::InvalidInput);
  params.tolerance = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(mesolens::perceive_bonds(atoms.input(), params), mesolens::InvalidInput);
  params = {};
  params.bead_cutoff = 0;
  EXPECT_THROW(mesolens::perceive_bonds(atoms.input(), params), mesolens::InvalidInput);
  mesolens::BondPerceptionInput missing = atoms.input();
  missing.atomic_numbers = nullptr;
  EXPECT_THROW(mesolens::perceive_bonds(missing), mesolens::InvalidInput);
}

TEST(BondPerception, EmptyInput)
{
  const mesolens::BondPerceptionInput empty;
  EXPECT_TRUE(mesolens::perceive_bonds(empty).empty());
  EXPECT_FALSE(mesolens::looks_coarse_grained(empty, {}));
}

TEST(BondPerception, MergeKeepsSortedUnion)
{
  const std::vector<mesolens::Bond> a = { { 0, 1 }, { 2, 3 } };
  const std::vector<mesolens::Bond> b = { { 0, 1 }, { 1, 2 } };
  const std::vector<mesolens::Bond> expected = { { 0, 1 }, { 1, 2 }, { 2, 3 } };
  EXPECT_EQ(mesolens::merge_bonds(a, b), expected);
}

TEST(BondConsensus, CopiesOfAMoleculeTypeShareTheirBonds)
{
  // Four copies of a three-bead molecule A-B-C: one copy lacks B-C, another has an extra A-C.
  mesolens::AtomTable table;
  for (int copy = 0; copy < 4; ++copy)
  {
    for (const char* name : { "A", "B", "C" })
    {
      table.append_atom(name, 0, 0, 0);
      table.residue_names.back() = "LIP";
      table.molecule_ids.back() = copy;
    }
  }
  table.append_atom("X", 0, 0, 0); // a different type with one copy keeps its own bonds
  table.append_atom("Y", 0, 0, 0);
  table.molecule_ids[12] = table.molecule_ids[13] = 4;
  const std::vector<mesolens::Bond> perceived = { { 0, 1 },  { 1, 2 },   { 3, 4 },
                                                  { 6, 7 },  { 7, 8 },   { 6, 8 },
                                                  { 9, 10 }, { 10, 11 }, { 12, 13 } };
  const std::vector<mesolens::Bond> expected = { { 0, 1 },  { 1, 2 },   { 3, 4 },
                                                 { 4, 5 },  { 6, 7 },   { 7, 8 },
                                                 { 9, 10 }, { 10, 11 }, { 12, 13 } };
  EXPECT_EQ(mesolens::consensus_bonds(table, perceived), expected);
  mesolens::BondConsensusParams strict;
  strict.min_fraction = 0;
  EXPECT_THROW(mesolens::consensus_bonds(table, perceived, strict), mesolens::InvalidInput);
}

TEST(BondPerception, SameBondsWhateverTheSplit)
{
  std::mt19937 random(3);
  std::uniform_real_distribution<float> coordinate(0.0f, 40.0f);
  Atoms atoms;
  for (int i = 0; i < 5000; ++i)
  {
    atoms.add(coordinate(random), coordinate(random), coordinate(random), 6, i % 4);
  }
  const auto sequential = mesolens::perceive_bonds(atoms.input());
  // A splitter that runs the ranges in reverse order, in chunks of 3 planes.
  const mesolens::ParallelFor reversed = [](std::size_t count,
                                            const mesolens::RangeKernel& kernel) {
    for (std::size_t end = count; end > 0;)
    {
      const std::size_t begin = end >= 3 ? end - 3 : 0;
      kernel(begin, end);
      end = begin;
    }
  };
  EXPECT_EQ(mesolens::perceive_bonds(atoms.input(), {}, reversed), sequential);
  EXPECT_GT(sequential.size(), 1000u);
}
