// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/molecules/molecule_assignment.h"

#include <gtest/gtest.h>

namespace {
void add(mesolens::AtomTable& t, const char* name, const char* residue, int number,
         const char* chain, float x)
{
  t.append_atom(name, x, 0, 0);
  t.residue_names.back() = residue;
  t.residue_numbers.back() = number;
  t.chain_ids.back() = chain;
}
} // namespace

TEST(MoleculeAssignment, PolymerChainIsOneMoleculeLigandsAndWatersAreSeparate)
{
  mesolens::AtomTable t;
  add(t, "N", "ALA", 1, "A", 0);
  add(t, "C", "ALA", 1, "A", 1);
  add(t, "N", "GLY", 2, "A", 2);
  add(t, "C", "GLY", 2, "A", 3);
  add(t, "C1", "NAG", 3, "A", 4);
  add(t, "O", "HOH", 4, "A", 5);
  add(t, "O", "HOH", 5, "A", 6);
  add(t, "N", "ALA", 1, "B", 7);
  mesolens::assign_residues(t);
  mesolens::assign_molecules(t);
  EXPECT_EQ(t.residue_indices, (std::vector<int>{ 0, 0, 1, 1, 2, 3, 4, 5 }));
  EXPECT_EQ(t.molecule_ids, (std::vector<int>{ 0, 0, 0, 0, 1, 2, 3, 4 }));
}

TEST(MoleculeAssignment, WithoutChainIdsBackboneDistanceDecides)
{
  // GRO files have no chains: two peptides, linked C-N at 1.33 Å, then a 20 Å gap.
  mesolens::AtomTable t;
  add(t, "N", "ALA", 1, "", 0);
  add(t, "C", "ALA", 1, "", 1.0f);
  add(t, "N", "GLY", 2, "", 2.33f);
  add(t, "C", "GLY", 2, "", 3.3f);
  add(t, "N", "SER", 3, "", 23.3f);
  add(t, "NC3", "DPPC", 4, "", 40.0f);
  add(t, "PO4", "DPPC", 4, "", 44.0f);
  add(t, "NC3", "DPPC", 5, "", 50.0f);
  mesolens::assign_residues(t);
  mesolens::assign_molecules(t);
  EXPECT_EQ(t.molecule_ids, (std::vector<int>{ 0, 0, 0, 0, 1, 2, 2, 3 }));
}

TEST(MoleculeAssignment, BackboneLinkAcrossPeriodicBoundary)
{
  mesolens::AtomTable t;
  add(t, "C", "ALA", 1, "", 49.5f);
  add(t, "N", "GLY", 2, "", 0.5f); // 1.0 Å away through the boundary of a 50 Å box
  t.box.vectors = { { { 50, 0, 0 }, { 0, 50, 0 }, { 0, 0, 50 } } };
  mesolens::assign_residues(t);
  mesolens::assign_molecules(t);
  EXPECT_EQ(t.molecule_ids, (std::vector<int>{ 0, 0 }));
}

TEST(MoleculeAssignment, ResidueNames)
{
  EXPECT_TRUE(mesolens::is_amino_acid_residue("ALA"));
  EXPECT_TRUE(mesolens::is_amino_acid_residue("MSE"));
  EXPECT_TRUE(mesolens::is_amino_acid_residue("HSD"));
  EXPECT_TRUE(mesolens::is_amino_acid_residue("NALA"));
  EXPECT_FALSE(mesolens::is_amino_acid_residue("DPPC"));
  EXPECT_TRUE(mesolens::is_nucleotide_residue("DA"));
  EXPECT_TRUE(mesolens::is_nucleotide_residue("U"));
  EXPECT_FALSE(mesolens::is_nucleotide_residue("HOH"));
  EXPECT_TRUE(mesolens::is_water_residue("SOL"));
  EXPECT_TRUE(mesolens::is_water_residue("hoh"));
  EXPECT_FALSE(mesolens::is_water_residue("POPE"));
}

TEST(AtomTable, FilterRemapsBondsAndRenumbers)
{
  mesolens::AtomTable t;
  for (int i = 0; i < 4; ++i)
  {
    add(t, "C", "LIG", i, "", float(i));
  }
  mesolens::assign_residues(t);
  mesolens::assign_molecules(t);
  t.bonds = { { 0, 1 }, { 1, 2 }, { 2, 3 } };
  t.filter({ true, false, true, true });
  ASSERT_EQ(t.size(), 3u);
  EXPECT_EQ(t.bonds, (std::vector<mesolens::Bond>{ { 1, 2 } }));
  EXPECT_EQ(t.molecule_ids, (std::vector<int>{ 0, 1, 2 }));
  EXPECT_NO_THROW(t.check_consistent());
  t.residue_names.pop_back();
  EXPECT_THROW(t.check_consistent(), std::exception);
}
