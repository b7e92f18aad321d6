// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/molecules/atom_selection.h"

#include "mesolens/molecules/molecule_assignment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace {
using mesolens::AtomSelection;
using mesolens::AtomTable;
using mesolens::select_atoms;
using mesolens::SelectionError;

struct TestAtom
{
  const char* name;
  const char* residue;
  int number;
  const char* chain;
  int element;
};

/// Atoms on the x axis, 1 Å apart (atom i at x = i), in the given residues.
AtomTable table_of(const std::vector<TestAtom>& atoms)
{
  AtomTable table;
  for (std::size_t i = 0; i < atoms.size(); ++i)
  {
    table.append_atom(atoms[i].name, float(i), 0.0f, 0.0f);
    table.residue_names.back() = atoms[i].residue;
    table.residue_numbers.back() = atoms[i].number;
    table.chain_ids.back() = atoms[i].chain;
    table.atomic_numbers.back() = std::uint8_t(atoms[i].element);
    table.serials.back() = int(i) + 101;
  }
  mesolens::assign_residues(table);
  mesolens::assign_molecules(table);
  return table;
}

/// A peptide of two residues, a water, a lipid atom and a ligand.
AtomTable small_system()
{
  AtomTable table = table_of({ { "N", "ALA", 1, "A", 7 },
                               { "CA", "ALA", 1, "A", 6 },
                               { "C", "ALA", 1, "A", 6 },
                               { "O", "ALA", 1, "A", 8 },
                               { "CB", "ALA", 1, "A", 6 },
                               { "H", "ALA", 1, "A", 1 },
                               { "N", "GLY", 2, "A", 7 },
                               { "CA", "GLY", 2, "A", 6 },
                               { "OW", "HOH", 3, "B", 8 },
                               { "P", "POPC", 4, "B", 15 },
                               { "C1", "LIG", -2, "C", 6 } });
  table.is_hetero[8] = table.is_hetero[10] = 1;
  table.b_factors = { 10, 20, 30, 40, 50, 60, 70, 80, 90, 100, 110 };
  table.alt_locs[4] = 'A';
  table.insertion_codes[7] = 'B';
  return table;
}

/// The indices of the selected atoms.
std::vector<int> selected(const std::string& expression, const AtomTable& table,
                          const mesolens::SelectionArrays& arrays = {})
{
  const auto mask = AtomSelection(expression).evaluate(table, arrays);
  EXPECT_EQ(mask.size(), table.size());
  std::vector<int> indices;
  for (std::size_t i = 0; i < mask.size(); ++i)
  {
    if (mask[i])
    {
      indices.push_back(int(i));
    }
  }
  return indices;
}

using Indices = std::vector<int>;

TEST(AtomSelection, KeywordsSelectTheirAtoms)
{
  const AtomTable t = small_system();
  EXPECT_EQ(selected("all", t).size(), t.size());
  EXPECT_EQ(selected("none", t), Indices{});
  EXPECT_EQ(selected("protein", t), (Indices{ 0, 1, 2, 3, 4, 5, 6, 7 }));
  EXPECT_EQ(selected("backbone", t), (Indices{ 0, 1, 2, 3, 6, 7 }));
  EXPECT_EQ(selected("water", t), Indices{ 8 });
  EXPECT_EQ(selected("lipid", t), Indices{ 9 });
  EXPECT_EQ(selected("hydrogen", t), Indices{ 5 });
  EXPECT_EQ(selected("hetero", t), (Indices{ 8, 10 }));
  EXPECT_EQ(selected("nucleic", t), Indices{});
  EXPECT_EQ(selected("name CA", t), (Indices{ 1, 7 }));
  EXPECT_EQ(selected("name N O", t), (Indices{ 0, 3, 6 }));
  EXPECT_EQ(selected("resname GLY LIG", t), (Indices{ 6, 7, 10 }));
  EXPECT_EQ(selected("chain B", t), (Indices{ 8, 9 }));
  EXPECT_EQ(selected("chainid C", t), Indices{ 10 });
  EXPECT_EQ(selected("element O P", t), (Indices{ 3, 8, 9 }));
  EXPECT_EQ(selected("element o", t), (Indices{ 3, 8 }));
  EXPECT_EQ(selected("altloc A", t), Indices{ 4 });
  EXPECT_EQ(selected("altloc \"\"", t).size(), t.size() - 1);
}

TEST(AtomSelection, WildcardsMatchLikeAShell)
{
  const AtomTable t = small_system();
  EXPECT_EQ(selected("name C*", t), (Indices{ 1, 2, 4, 7, 10 }));
  EXPECT_EQ(selected("name C?", t), (Indices{ 1, 4, 7, 10 }));
  EXPECT_EQ(selected("name [NO]", t), (Indices{ 0, 3, 6 }));
  EXPECT_EQ(selected("resname \"P*\"", t), Indices{ 9 });
}

TEST(AtomSelection, NumbersAndRanges)
{
  const AtomTable t = small_system();
  EXPECT_EQ(selected("resid 2", t), (Indices{ 6, 7 }));
  EXPECT_EQ(selected("resid 2B", t), Indices{ 7 });
  EXPECT_EQ(selected("resid 2-3", t), (Indices{ 6, 7, 8 }));
  EXPECT_EQ(selected("resid 2:3", t), (Indices{ 6, 7, 8 }));
  EXPECT_EQ(selected("resid 2 to 3", t), (Indices{ 6, 7, 8 }));
  EXPECT_EQ(selected("resid -2", t), Indices{ 10 });
  EXPECT_EQ(selected("resid -5--1 4", t), (Indices{ 9, 10 }));
  EXPECT_EQ(selected("resnum 4", t), Indices{ 9 });
  EXPECT_EQ(selected("index 0 10", t), (Indices{ 0, 10 }));
  EXPECT_EQ(selected("bynum 1 11", t), (Indices{ 0, 10 }));
  EXPECT_EQ(selected("serial 102-103", t), (Indices{ 1, 2 }));
  EXPECT_EQ(selected("id 111", t), Indices{ 10 });
  EXPECT_EQ(selected("residue 1", t), (Indices{ 6, 7 }));
  EXPECT_EQ(selected("resindex 2 3", t), (Indices{ 8, 9 }));
  // The peptide is one molecule, the water, lipid and ligand one each.
  EXPECT_EQ(selected("molecule 0", t), (Indices{ 0, 1, 2, 3, 4, 5, 6, 7 }));
  EXPECT_EQ(selected("molecule 3", t), Indices{ 10 });
}

TEST(AtomSelection, ComparisonsOnFieldsAndArrays)
{
  const AtomTable t = small_system();
  EXPECT_EQ(selected("x < 2", t), (Indices{ 0, 1 }));
  EXPECT_EQ(selected("x<=2", t), (Indices{ 0, 1, 2 }));
  EXPECT_EQ(selected("prop x >= 9.5", t), Indices{ 10 });
  EXPECT_EQ(selected("y == 0 and z != 0", t), Indices{});
  EXPECT_EQ(selected("beta > 95", t), (Indices{ 9, 10 }));
  EXPECT_EQ(selected("bfactor = 30", t), Indices{ 2 });
  EXPECT_EQ(selected("mass > 20", t), Indices{ 9 });
  EXPECT_EQ(selected("resid < 0", t), Indices{ 10 });
  EXPECT_EQ(selected("index >= 9", t), (Indices{ 9, 10 }));
  mesolens::SelectionArrays arrays;
  arrays["leaflet"] = { 0, 0, 0, 0, 0, 0, 0, 0, 1, 1, -1 };
  EXPECT_EQ(selected("leaflet > 0", t, arrays), (Indices{ 8, 9 }));
  EXPECT_EQ(selected("prop leaflet < 0 or leaflet == 1", t, arrays), (Indices{ 8, 9, 10 }));
  EXPECT_EQ(AtomSelection("leaflet > 0 and charge < 1 or x > 1e3").array_names(),
            std::vector<std::string>{ "leaflet" });
}

TEST(AtomSelection, BooleanOperatorsAndPrecedence)
{
  const AtomTable t = small_system();
  // and binds tighter than or.
  EXPECT_EQ(selected("chain C or name CA and resid 2", t), (Indices{ 7, 10 }));
  EXPECT_EQ(selected("(chain C or name CA) and resid 2", t), Indices{ 7 });
  EXPECT_EQ(selected("not protein", t), (Indices{ 8, 9, 10 }));
  EXPECT_EQ(selected("not not water", t), Indices{ 8 });
  EXPECT_EQ(selected("protein and not backbone", t), (Indices{ 4, 5 }));
  EXPECT_EQ(selected("not chain A and not water", t), (Indices{ 9, 10 }));
  EXPECT_EQ(selected("((((name P))))", t), Indices{ 9 });
}

TEST(AtomSelection, WithinAndAroundOnALine)
{
  const AtomTable t = small_system(); // atom i at x = i
  EXPECT_EQ(selected("within 2 of index 5", t), (Indices{ 3, 4, 5, 6, 7 }));
  EXPECT_EQ(selected("within 1.99 of index 5", t), (Indices{ 4, 5, 6 }));
  EXPECT_EQ(selected("exwithin 2 of index 5", t), (Indices{ 3, 4, 6, 7 }));
  EXPECT_EQ(selected("around 2 index 5", t), (Indices{ 3, 4, 6, 7 }));
  EXPECT_EQ(selected("within 0 of index 3", t), Indices{ 3 });
  EXPECT_EQ(selected("within 1 of chain C and hetero", t), Indices{ 10 });
  EXPECT_EQ(selected("within 1 of (chain C or water)", t), (Indices{ 7, 8, 9, 10 }));
  EXPECT_EQ(selected("within 3 of none", t), Indices{});
  EXPECT_EQ(selected("within 1e30 of index 0", t).size(), t.size());
}

TEST(AtomSelection, SameGroupAs)
{
  const AtomTable t = small_system();
  EXPECT_EQ(selected("same residue as name CB", t), (Indices{ 0, 1, 2, 3, 4, 5 }));
  EXPECT_EQ(selected("byres index 7", t), (Indices{ 6, 7 }));
  EXPECT_EQ(selected("same chain as index 9", t), (Indices{ 8, 9 }));
  EXPECT_EQ(selected("same molecule as index 7", t), (Indices{ 0, 1, 2, 3, 4, 5, 6, 7 }));
  EXPECT_EQ(selected("same residue as within 1 of index 8", t), (Indices{ 6, 7, 8, 9 }));
}

/// The brute-force answer of `within` on a random cloud, for several distances.
TEST(AtomSelection, WithinMatchesAllPairsOnARandomCloud)
{
  std::mt19937 random(7);
  std::uniform_real_distribution<float> coordinate(-20.0f, 20.0f);
  AtomTable t;
  for (int i = 0; i < 3000; ++i)
  {
    t.append_atom("C", coordinate(random), coordinate(random), coordinate(random));
    t.residue_numbers.back() = i % 17;
  }
  for (double distance : { 0.5, 2.0, 4.5, 11.0 })
  {
    const auto mask = select_atoms(t, "within " + std::to_string(distance) + " of resid 3");
    for (std::size_t i = 0; i < t.size(); ++i)
    {
      bool near = false;
      for (std::size_t j = 0; j < t.size() && !near; ++j)
      {
        if (t.residue_numbers[j] == 3)
        {
          double squared = 0.0;
          for (int d = 0; d < 3; ++d)
          {
            const double delta = double(t.positions[3 * i + d]) - t.positions[3 * j + d];
            squared += delta * delta;
          }
          near = squared <= distance * distance;
        }
      }
      ASSERT_EQ(mask[i] != 0, near) << "atom " << i << " at distance " << distance;
    }
  }
}

TEST(AtomSelection, NonFiniteCoordinatesAreNeverWithin)
{
  AtomTable t = small_system();
  t.positions[3 * 4] = std::nanf("");
  t.positions[3 * 6] = INFINITY;
  EXPECT_EQ(selected("within 3 of index 5", t), (Indices{ 2, 3, 5, 7, 8 }));
  EXPECT_EQ(selected("within 3 of index 4", t), Indices{});
  EXPECT_EQ(selected("x > 5.5", t), (Indices{ 6, 7, 8, 9, 10 }));
}

/// The 0-based character a bad expression's error names.
std::size_t error_position(const std::string& expression, std::string* message = nullptr)
{
  try
  {
    AtomSelection selection(expression);
    (void)selection.evaluate(small_system());
  }
  catch (const SelectionError& error)
  {
    if (message)
    {
      *message = error.what();
    }
    return error.position();
  }
  ADD_FAILURE() << "no error for \"" << expression << "\"";
  return std::string::npos;
}

TEST(AtomSelection, BadExpressionsNameTheirPosition)
{
  std::string message;
  EXPECT_EQ(error_position("name CA and (resid 5", &message), 20u);
  EXPECT_EQ(message, "selection \"name CA and (resid 5\": missing ')' at character 21");
  EXPECT_EQ(error_position(""), 0u);
  EXPECT_EQ(error_position("   "), 3u);
  EXPECT_EQ(error_position("resname"), 7u);
  EXPECT_EQ(error_position("name CA and"), 11u);
  EXPECT_EQ(error_position("nmae CA"), 0u);
  EXPECT_EQ(error_position("name CA resid 5"), 8u);
  EXPECT_EQ(error_position("protein)"), 7u);
  EXPECT_EQ(error_position("resid 10-5"), 6u);
  EXPECT_EQ(error_position("resid 1.5"), 6u);
  EXPECT_EQ(error_position("resid five"), 6u);
  EXPECT_EQ(error_position("index 3B"), 6u);
  EXPECT_EQ(error_position("resid 5 to"), 10u);
  EXPECT_EQ(error_position("element C Qq"), 10u);
  EXPECT_EQ(error_position("within -1 of protein"), 7u);
  EXPECT_EQ(error_position("within nan of protein"), 7u);
  EXPECT_EQ(error_position("within 5 protein"), 9u);
  EXPECT_EQ(error_position("same atom as protein"), 5u);
  EXPECT_EQ(error_position("same residue protein"), 13u);
  EXPECT_EQ(error_position("x << 3"), 2u);
  EXPECT_EQ(error_position("x < three"), 4u);
  EXPECT_EQ(error_position("name \"CA"), 5u);
  EXPECT_EQ(error_position("x < 1e999"), 4u);
  EXPECT_EQ(error_position("protein and charges > 0", &message), 12u);
  EXPECT_EQ(message,
            "selection \"protein and charges > 0\": 'charges' is neither a keyword nor a "
            "per-atom array at character 13");
  EXPECT_EQ(error_position("name CA\nor"), 10u);
  EXPECT_EQ(message.find('\n'), std::string::npos);
}

TEST(AtomSelection, AnArrayOfTheWrongLengthIsRefused)
{
  mesolens::SelectionArrays arrays;
  arrays["leaflet"] = { 1.0, 2.0 };
  EXPECT_THROW(AtomSelection("leaflet > 1").evaluate(small_system(), arrays), SelectionError);
}

TEST(AtomSelection, LongAndDeepExpressionsAreSafe)
{
  const AtomTable t = small_system();
  std::string many = "index 0";
  for (int i = 0; i < 100000; ++i)
  {
    many += " or index 1";
  }
  EXPECT_EQ(selected(many, t), (Indices{ 0, 1 }));
  const std::string nested = std::string(200, '(') + "water" + std::string(200, ')');
  EXPECT_EQ(selected(nested, t), Indices{ 8 });
  std::string negated;
  for (int i = 0; i < 255; ++i)
  {
    negated += "not ";
  }
  EXPECT_EQ(selected(negated + "water", t).size(), t.size() - 1);
  EXPECT_THROW(AtomSelection(std::string(100000, '(') + "water"), SelectionError);
  EXPECT_THROW(AtomSelection(negated + "not not water"), SelectionError);
  EXPECT_THROW(AtomSelection("resid " + std::string(100000, '7')), SelectionError);
}

TEST(AtomSelection, EmptyTablesGiveEmptyMasks)
{
  EXPECT_TRUE(select_atoms(AtomTable{}, "within 5 of protein").empty());
  EXPECT_TRUE(select_atoms(AtomTable{}, "same residue as all").empty());
}

TEST(AtomSelection, InconsistentTablesAreRefused)
{
  AtomTable t = small_system();
  t.residue_names.pop_back();
  EXPECT_THROW(select_atoms(t, "all"), mesolens::InvalidInput);
}

TEST(LipidResidues, ForceFieldNamesAreLipids)
{
  for (const char* lipid : { "DPPC", "POPE", "POPG", "DOPS", "popc", "CHOL", "CHL1", "PSM", "DPSM",
                             "SAPI", "CDL2", "PC", "OL" })
  {
    EXPECT_TRUE(mesolens::is_lipid_residue(lipid)) << lipid;
  }
  for (const char* other : { "ALA", "HOH", "NA", "LA", "PO4", "DPP", "12PC", "LIG", "" })
  {
    EXPECT_FALSE(mesolens::is_lipid_residue(other)) << other;
  }
}

} // namespace
