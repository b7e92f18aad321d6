// SPDX-License-Identifier: GPL-3.0-or-later
// Reference numbers come from independent tools (python3-gemmi, python3-mdanalysis); see
// Testing/Tools/reference_values.py.
#include "mesolens/io/structure_file.h"

#include "mesolens/common/errors.h"
#include "mesolens_test_data.h"

#include <gemmi/pdb.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <dirent.h>
#include <functional>
#include <numeric>
#include <set>
#include <tuple>
#include <zlib.h>

namespace {
using mesolens_test::data_file;

struct Expected
{
  const char* file;
  std::size_t models;
  std::size_t atoms;
  int residues;
  std::size_t chains;
  std::size_t hydrogens;
  std::size_t secondary_structure_spans;
  long bonds; // -1: not checked
};

// gemmi: models, atoms (one conformer), residues, chains, H, unique HELIX/strand spans;
// MDAnalysis: bonds (distance guess per molecule with covalent radii + 0.45 Å, plus CONECT).
const Expected expected_counts[] = {
  { "proteins/1crn.pdb", 1, 327, 46, 1, 0, 4, 337 },
  { "proteins/1crn.cif", 1, 327, 46, 1, 0, 4, -1 },
  { "proteins/1ubq.pdb", 1, 660, 134, 1, 0, 7, 608 },
  { "proteins/1ubq.cif", 1, 660, 134, 1, 0, 7, -1 },
  { "proteins/1l2y.pdb", 38, 304, 20, 1, 150, 2, -1 },
  { "proteins/1aki.pdb", 1, 1079, 207, 1, 0, 10, 1025 },
  { "proteins/1hpv.pdb", 1, 1631, 279, 3, 0, 21, -1 },
  { "proteins/4we2.pdb", 1, 2200, 549, 1, 0, 20, -1 },
  { "proteins/1dix.pdb", 1, 1748, 344, 1, 0, 16, -1 },
  { "proteins/1dix.cif", 1, 1748, 344, 1, 0, 16, -1 },
  { "proteins/3o5r.pdb", 1, 1326, 416, 1, 0, 11, -1 },
  { "proteins/3o5r.cif", 1, 1326, 416, 1, 0, 11, -1 },
  { "proteins/1bna.pdb", 1, 566, 104, 2, 0, 0, 544 },
  { "proteins/4gxy.pdb", 1, 3685, 175, 1, 0, 0, 4107 },
  { "proteins/1tii.pdb", 1, 5684, 927, 8, 0, 63, 5575 },
  { "proteins/1d3z.pdb", 10, 1231, 76, 1, 629, 8, -1 },
};

class StructureCounts : public ::testing::TestWithParam<Expected>
{
};

std::size_t count_spans(const mesolens::AtomTable& t)
{
  std::set<int> spans(t.secondary_structure_ids.begin(), t.secondary_structure_ids.end());
  spans.erase(-1);
  return spans.size();
}

std::string gzip_copy(const std::string& source, const std::string& name)
{
  const std::string bytes = mesolens_test::read_bytes(source);
  const std::string path = mesolens_test::output_file(name);
  gzFile out = gzopen(path.c_str(), "wb");
  gzwrite(out, bytes.data(), unsigned(bytes.size()));
  gzclose(out);
  return path;
}

/// Copy of 1crn.pdb with the x field of its fifth ATOM record replaced.
std::string crambin_with_x_field(const std::string& field, const std::string& name)
{
  std::string text = mesolens_test::read_bytes(data_file("proteins/1crn.pdb"));
  std::size_t position = 0;
  for (int atom = 0; atom < 5; ++atom)
  {
    position = text.find("\nATOM  ", position + 1);
  }
  text.replace(position + 1 + 30, 8, field);
  return mesolens_test::write_bytes(name, text);
}
} // namespace

TEST_P(StructureCounts, MatchIndependentReaders)
{
  const Expected& e = GetParam();
  const mesolens::StructureFile file = mesolens::read_structure(data_file(e.file));
  ASSERT_EQ(file.models.size(), e.models);
  const mesolens::AtomTable& t = file.models.front();
  EXPECT_NO_THROW(t.check_consistent());
  EXPECT_EQ(t.size(), e.atoms);
  EXPECT_EQ(t.residue_indices.back() + 1, e.residues);
  EXPECT_EQ(std::set<std::string>(t.chain_ids.begin(), t.chain_ids.end()).size(), e.chains);
  EXPECT_EQ(std::size_t(std::count(t.atomic_numbers.begin(), t.atomic_numbers.end(), 1)),
            e.hydrogens);
  EXPECT_EQ(count_spans(t), e.secondary_structure_spans);
  if (e.bonds >= 0)
  {
    EXPECT_EQ(long(t.bonds.size()), e.bonds);
  }
  EXPECT_FALSE(file.coarse_grained);
  EXPECT_TRUE(std::none_of(t.atomic_numbers.begin(), t.atomic_numbers.end(),
                           [](std::uint8_t z) { return z == 0; }));
}

INSTANTIATE_TEST_SUITE_P(RealFiles, StructureCounts, ::testing::ValuesIn(expected_counts),
                         [](const ::testing::TestParamInfo<Expected>& info) {
                           std::string name =
                             std::string(info.param.file).substr(sizeof("proteins/") - 1);
                           std::replace(name.begin(), name.end(), '.', '_');
                           return name;
                         });

TEST(StructureFile, HelixAndSheetSpansFollowRecords)
{
  // 1CRN: HELIX ILE A 7 - PRO A 19 (class 1), GLU A 23 - THR A 30 (class 1); SHEET THR A 1 - CYS
  // A 4, CYS A 32 - ILE A 35.
  const auto t = mesolens::read_structure(data_file("proteins/1crn.pdb")).models.front();
  for (std::size_t i = 0; i < t.size(); ++i)
  {
    const int r = t.residue_numbers[i];
    const auto kind = static_cast<mesolens::SecondaryStructure>(t.secondary_structure[i]);
    if ((r >= 7 && r <= 19) || (r >= 23 && r <= 30))
    {
      EXPECT_EQ(kind, mesolens::SecondaryStructure::AlphaHelix) << r;
    }
    else if ((r >= 1 && r <= 4) || (r >= 32 && r <= 35))
    {
      EXPECT_EQ(kind, mesolens::SecondaryStructure::Strand) << r;
    }
    else
    {
      EXPECT_EQ(kind, mesolens::SecondaryStructure::Coil) << r;
    }
  }
}

TEST(StructureFile, AlternateLocationsKeepHighestOccupancy)
{
  // 3O5R MET 48: conformer A has occupancy 0.25, B 0.75.
  const auto t = mesolens::read_structure(data_file("proteins/3o5r.pdb")).models.front();
  std::size_t met48 = 0;
  for (std::size_t i = 0; i < t.size(); ++i)
  {
    if (t.residue_numbers[i] == 48 && t.residue_names[i] == "MET")
    {
      ++met48;
      EXPECT_EQ(t.alt_locs[i], 'B');
    }
  }
  EXPECT_EQ(met48, 8u);
  mesolens::StructureReadParams keep_all;
  keep_all.alt_locs = mesolens::AltLocPolicy::KeepAll;
  EXPECT_EQ(mesolens::read_structure(data_file("proteins/3o5r.pdb"), keep_all).models[0].size(),
            1470u);
  EXPECT_EQ(mesolens::read_structure(data_file("proteins/4we2.pdb"), keep_all).models[0].size(),
            2238u);
}

TEST(StructureFile, InsertionCodesAndHetatm)
{
  const auto t = mesolens::read_structure(data_file("proteins/1dix.pdb")).models.front();
  EXPECT_EQ(std::count_if(t.insertion_codes.begin(), t.insertion_codes.end(),
                          [](char c) { return c != ' '; }),
            21);
  const auto ubq = mesolens::read_structure(data_file("proteins/1ubq.pdb")).models.front();
  EXPECT_EQ(std::count(ubq.is_hetero.begin(), ubq.is_hetero.end(), 1), 58); // waters
}

TEST(StructureFile, RemoveWatersAndHydrogens)
{
  mesolens::StructureReadParams params;
  params.remove_waters = true;
  EXPECT_EQ(mesolens::read_structure(data_file("proteins/1ubq.pdb"), params).models[0].size(),
            602u);
  params = {};
  params.remove_hydrogens = true;
  EXPECT_EQ(mesolens::read_structure(data_file("proteins/1l2y.pdb"), params).models[0].size(),
            154u);
}

// Found by fuzz_structure: gemmi 0.5 read DBREF2's ten-digit sequence numbers into int unchecked
// (signed overflow under UBSan). MesoLens keeps no database references: the record is skipped.
TEST(StructureFile, DbrefNumbersBeyondIntAreSkipped)
{
  const std::string path = mesolens_test::write_bytes(
    "dbref2_overflow.pdb",
    "DBREF1 1ABC A    1    10  UNP                  PROT_HUMAN\n"
    "DBREF2 1ABC A     P12345                          4444444444  9999999999\n"
    "ATOM      1  N   GLY A   1       0.000   0.000   0.000  1.00  0.00           N\n"
    "ATOM      2  CA  GLY A   1       1.458   0.000   0.000  1.00  0.00           C\n");
  const auto file = mesolens::read_structure(path);
  ASSERT_EQ(file.models.size(), 1u);
  EXPECT_EQ(file.models.front().size(), 2u);
  EXPECT_EQ(file.models.front().bonds.size(), 1u);
}

TEST(StructureFile, NothingLeftAfterRemovalIsAnError)
{
  // Found by fuzz_structure: a file of hydrogens read without hydrogens gave a model of no atoms.
  const std::string hydrogens = mesolens_test::write_bytes(
    "hydrogens_only.pdb",
    "ATOM      1  H1  HOH A   1       0.000   0.000   0.000  1.00  0.00           H\n"
    "ATOM      2  H2  HOH A   1       0.800   0.600   0.000  1.00  0.00           H\n");
  const struct
  {
    bool waters, hydrogens;
    const char* message;
  } cases[] = {
    { false, true, "no atoms are left once hydrogens are removed" },
    { true, false, "no atoms are left once waters are removed" },
    { true, true, "no atoms are left once waters and hydrogens are removed" },
  };
  for (const auto& c : cases)
  {
    mesolens::StructureReadParams params;
    params.remove_waters = c.waters;
    params.remove_hydrogens = c.hydrogens;
    try
    {
      mesolens::read_structure(hydrogens, params);
      ADD_FAILURE() << "no error: " << c.message;
    }
    catch (const mesolens::InvalidInput& e)
    {
      EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(mesolens::read_structure(hydrogens).models.front().size(), 2u);
}

TEST(StructureFile, MmcifIntegersBeyondIntAreRefused)
{
  // Found by fuzz_structure: gemmi 0.5 reads mmCIF integers into int unchecked (signed
  // overflow: undefined behaviour, in practice wrong residue numbers).
  const auto cif = [](const std::string& residue_number) {
    return "data_test\nloop_\n_atom_site.group_PDB\n_atom_site.id\n_atom_site.type_symbol\n"
           "_atom_site.label_atom_id\n_atom_site.label_alt_id\n_atom_site.label_comp_id\n"
           "_atom_site.label_asym_id\n_atom_site.label_seq_id\n_atom_site.Cartn_x\n"
           "_atom_site.Cartn_y\n_atom_site.Cartn_z\n_atom_site.occupancy\n"
           "_atom_site.B_iso_or_equiv\n_atom_site.auth_seq_id\n_atom_site.auth_comp_id\n"
           "_atom_site.auth_asym_id\n_atom_site.auth_atom_id\n_atom_site.pdbx_PDB_model_num\n"
           "ATOM 1 N N . GLY A 1 1.0 2.0 3.0 1.0 0.0 " +
      residue_number + " GLY A N 1\n";
  };
  const auto good =
    mesolens::read_structure(mesolens_test::write_bytes("int_ok.cif", cif("-2147483647")));
  EXPECT_EQ(good.models.front().residue_numbers.front(), -2147483647);
  for (const char* number : { "7777777777", "-2147483649", "00000000002147483648" })
  {
    try
    {
      mesolens::read_structure(mesolens_test::write_bytes("int_overflow.cif", cif(number)));
      ADD_FAILURE() << number << " accepted";
    }
    catch (const mesolens::FileError& e)
    {
      EXPECT_NE(std::string(e.what()).find("_atom_site.auth_seq_id in row 1 of its loop: " +
                                           std::string(number) + " is an integer beyond"),
                std::string::npos)
        << e.what();
    }
  }
}

TEST(StructureFile, ExplicitBondsWithoutPerception)
{
  mesolens::StructureReadParams params;
  params.perceive_bonds = false;
  // CONECT pairs (MDAnalysis): 3 disulfides in 1CRN, 242 unique pairs in 4GXY.
  EXPECT_EQ(mesolens::read_structure(data_file("proteins/1crn.pdb"), params).models[0].bonds.size(),
            3u);
  EXPECT_EQ(mesolens::read_structure(data_file("proteins/4gxy.pdb"), params).models[0].bonds.size(),
            242u);
}

TEST(StructureFile, ModelsDifferInCoordinates)
{
  const auto file = mesolens::read_structure(data_file("proteins/1l2y.pdb"));
  ASSERT_EQ(file.models.size(), 38u);
  EXPECT_NE(file.models[0].positions[0], file.models[1].positions[0]);
  EXPECT_EQ(file.models[0].atom_names, file.models[37].atom_names);
}

TEST(StructureFile, GzippedFile)
{
  const auto t = mesolens::read_structure(gzip_copy(data_file("proteins/1crn.pdb"), "1crn.pdb.gz"));
  EXPECT_EQ(t.models[0].size(), 327u);
  EXPECT_EQ(t.models[0].bonds.size(), 337u);
}

TEST(StructureFile, LegacyColumnsGiveElementsFromNames)
{
  const auto file = mesolens::read_structure(data_file("proteins/1hpv.pdb"));
  const auto& t = file.models[0];
  EXPECT_EQ(t.atomic_numbers[0], 7); // N of PRO 1
  ASSERT_FALSE(file.warnings.empty());
  EXPECT_NE(file.warnings[0].find("columns 77-80"), std::string::npos);
}

TEST(StructureFile, BadInputsThrowFileError)
{
  using mesolens_test::output_file;
  EXPECT_THROW(mesolens::read_structure(output_file("does_not_exist.pdb")), mesolens::FileError);
  EXPECT_THROW(mesolens::read_structure(mesolens_test::write_bytes("empty.pdb", "")),
               mesolens::FileError);
  EXPECT_THROW(mesolens::read_structure(mesolens_test::garbage_file("garbage.pdb")),
               mesolens::FileError);
  EXPECT_THROW(mesolens::read_structure(mesolens_test::garbage_file("garbage.cif")),
               mesolens::FileError);
  // Cut in the middle of an ATOM record.
  const std::string text = mesolens_test::read_bytes(data_file("proteins/1crn.pdb"));
  const std::size_t cut = text.find("ATOM    100") + 40;
  EXPECT_THROW(
    mesolens::read_structure(mesolens_test::write_bytes("truncated.pdb", text.substr(0, cut))),
    mesolens::FileError);
  const std::string cif = mesolens_test::read_bytes(data_file("proteins/1crn.cif"));
  EXPECT_THROW(mesolens::read_structure(mesolens_test::write_bytes(
                 "truncated.cif", cif.substr(0, cif.find("ATOM   100") + 30))),
               mesolens::FileError);
  EXPECT_THROW(mesolens::read_structure(crambin_with_x_field("     nan", "nan.pdb")),
               mesolens::InvalidInput);
  EXPECT_THROW(mesolens::read_structure(crambin_with_x_field("   12.3x", "letters.pdb")),
               mesolens::FileError);
  EXPECT_THROW(mesolens::read_structure(mesolens_test::data_file("proteins")), mesolens::FileError);
}

TEST(StructureFile, ProgressCanAbort)
{
  std::vector<double> reported;
  mesolens::read_structure(data_file("proteins/1l2y.pdb"), {}, [&](double f) {
    reported.push_back(f);
    return true;
  });
  ASSERT_FALSE(reported.empty());
  EXPECT_DOUBLE_EQ(reported.back(), 1.0);
  EXPECT_TRUE(std::is_sorted(reported.begin(), reported.end()));
  EXPECT_THROW(
    mesolens::read_structure(data_file("proteins/1l2y.pdb"), {}, [](double) { return false; }),
    mesolens::FileError);
}

// Every malformed file of other parsers' test suites either reads or fails with FileError.
TEST(StructureFile, AwkwardFilesReadOrFailCleanly)
{
  const std::string folder = data_file("proteins/awkward");
  DIR* directory = opendir(folder.c_str());
  ASSERT_NE(directory, nullptr);
  std::vector<std::string> names;
  while (const dirent* entry = readdir(directory))
  {
    const std::string name = entry->d_name;
    if (name.size() > 4 &&
        (name.substr(name.size() - 4) == ".pdb" || name.substr(name.size() - 4) == ".cif"))
    {
      names.push_back(name);
    }
  }
  closedir(directory);
  ASSERT_GE(names.size(), 30u);
  const std::set<std::string> must_fail = { "freesasa_empty.pdb",     "freesasa_empty_model.pdb",
                                            "biopython_header.pdb",   "gemmi_5moo_header.pdb",
                                            "biopython_4Q9R_min.cif", "biopython_1MOM_min.cif" };
  for (const std::string& name : names)
  {
    SCOPED_TRACE(name);
    if (must_fail.count(name))
    {
      EXPECT_THROW(mesolens::read_structure(folder + "/" + name), mesolens::FileError);
      continue;
    }
    try
    {
      const auto file = mesolens::read_structure(folder + "/" + name);
      EXPECT_GT(file.models.front().size(), 0u);
      EXPECT_NO_THROW(file.models.front().check_consistent());
    }
    catch (const mesolens::FileError& e)
    {
      ADD_FAILURE() << "unexpected failure: " << e.what();
    }
  }
}

TEST(StructureFile, AwkwardElementsAndNames)
{
  const std::string folder = data_file("proteins/awkward/");
  auto ions = mesolens::read_structure(folder + "biopython_ions.pdb").models[0];
  ASSERT_EQ(ions.size(), 2u);
  EXPECT_EQ(ions.atomic_numbers[0], 12);
  EXPECT_EQ(ions.atomic_numbers[1], 12);
  // Without an element column, ' CA ' (name aligned from column 14) is a C-alpha and 'CA  '
  // (from column 13) is calcium.
  auto odd = mesolens::read_structure(folder + "pymol_odd01.pdb").models[0];
  int checked = 0;
  for (std::size_t i = 0; i < odd.size(); ++i)
  {
    if (odd.serials[i] == 500 || odd.serials[i] == 501)
    {
      EXPECT_EQ(odd.atomic_numbers[i], odd.serials[i] == 500 ? 6 : 20);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 2);
  auto conect = mesolens::read_structure(folder + "mdanalysis_conect_error.pdb");
  ASSERT_FALSE(conect.warnings.empty());
  EXPECT_NE(conect.warnings[0].find("CONECT"), std::string::npos);
}

namespace {
/// One ATOM/HETATM record in GROMACS' gmx_fprintf_pdb_atomline format, without the modulo that
/// GROMACS applies first: a serial over 99999 or a residue number over 9999 takes more than its
/// field and pushes the rest of the record right.
std::string printf_atom_record(const char* record, int serial, const char* name, char alt_loc,
                               const char* residue, char chain, int residue_number,
                               char insertion_code, double x, double y, double z, double occupancy,
                               double b_factor, const char* element)
{
  char line[128];
  std::snprintf(line, sizeof(line),
                "%-6s%5d %-4.4s%c%4.4s%c%4d%c   %8.3f%8.3f%8.3f%6.2f%6.2f          %2s\n", record,
                serial, name, alt_loc, residue, chain, residue_number, insertion_code, x, y, z,
                occupancy, b_factor, element);
  return line;
}

std::size_t index_of_serial(const mesolens::AtomTable& t, int serial)
{
  const auto found = std::find(t.serials.begin(), t.serials.end(), serial);
  return found == t.serials.end() ? t.size() : std::size_t(found - t.serials.begin());
}
} // namespace

// Written by GROMACS 2022's own PDB writer (Testing/Tools/write_gromacs_pdb_fixture.cpp): one
// DPPC and 50 waters numbered 9990..10040, atoms 99811..100090. GROMACS writes residue numbers
// modulo 10000 and serials modulo 100000 in the standard columns ("ATOM      0  H2  SOL A  10"),
// and four-letter residue names run into the chain column ("DPPCA9990").
TEST(StructureFile, GromacsNumbersContinueWhereTheyRestart)
{
  const auto file =
    mesolens::read_structure(data_file("proteins/awkward/gromacs_wrapped_numbers.pdb"));
  ASSERT_EQ(file.models.size(), 1u);
  const mesolens::AtomTable& t = file.models[0];
  ASSERT_EQ(t.size(), 280u);
  std::vector<int> serials, residue_numbers;
  std::vector<std::string> residue_names;
  for (int i = 0; i < 280; ++i)
  {
    serials.push_back(99811 + i);
    residue_numbers.push_back(i < 130 ? 9990 : 9991 + (i - 130) / 3);
    residue_names.push_back(i < 130 ? "DPPC" : "SOL");
  }
  EXPECT_EQ(t.serials, serials);
  EXPECT_EQ(t.residue_numbers, residue_numbers);
  EXPECT_EQ(t.residue_names, residue_names);
  EXPECT_EQ(t.chain_ids, std::vector<std::string>(280, "A"));
  EXPECT_EQ(t.insertion_codes, std::vector<char>(280, ' '));
  EXPECT_EQ(t.occupancies, std::vector<float>(280, 1.0f));
  EXPECT_EQ(t.b_factors, std::vector<float>(280, 0.0f));
  EXPECT_EQ(t.residue_indices.back() + 1, 51);

  struct Atom
  {
    std::size_t index;
    const char* name;
    int atomic_number;
    float x, y, z;
  };
  const Atom atoms[] = {
    { 0, "N", 7, 19.680f, 34.850f, 55.850f },      // ATOM  99811  N   DPPCA9990
    { 125, "H15Y", 1, 23.430f, 32.110f, 40.480f }, // ATOM  99936 H15Y DPPCA9990
    { 157, "OH2", 8, 3.780f, 50.140f, 51.870f },   // ATOM  99968  OH2 SOL A   0 (10000)
    { 189, "H2", 1, 1.760f, 4.140f, 55.370f },     // ATOM      0  H2  SOL A  10 (100000)
    { 279, "H2", 1, 24.570f, 55.060f, 59.660f },   // ATOM     90  H2  SOL A  40
  };
  for (const Atom& atom : atoms)
  {
    SCOPED_TRACE(atom.index);
    EXPECT_EQ(t.atom_names[atom.index], atom.name);
    EXPECT_EQ(t.atomic_numbers[atom.index], atom.atomic_number);
    EXPECT_NEAR(t.positions[3 * atom.index], atom.x, 1e-4);
    EXPECT_NEAR(t.positions[3 * atom.index + 1], atom.y, 1e-4);
    EXPECT_NEAR(t.positions[3 * atom.index + 2], atom.z, 1e-4);
  }
  EXPECT_EQ(t.residue_numbers[157], 10000);
  EXPECT_EQ(t.serials[189], 100000);
  const std::string warnings = std::accumulate(file.warnings.begin(), file.warnings.end(),
                                               std::string(), std::plus<std::string>());
  EXPECT_NE(warnings.find("restart after 9999 "), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("restart after 99999 "), std::string::npos) << warnings;
}

// Serials and residue numbers written in full push the record right by one column each.
TEST(StructureFile, OverflowingNumbersShiftTheRecord)
{
  // Open Babel 3's PDB writer: its own format, no modulo either.
  char open_babel_record[128];
  std::snprintf(open_babel_record, sizeof(open_babel_record),
                "%s%5d %-4s %-3s %c%4d    %8.3f%8.3f%8.3f  1.00  0.00          %2s%2s\n", "HETATM",
                100006, " O", "HOH", 'W', 10003, 13.0, 14.0, -15.0, "O", "");
  const std::string text =
    std::string("CRYST1  100.000  100.000  100.000  90.00  90.00  90.00 P 1           1\n") +
    printf_atom_record("ATOM", 99998, " N", ' ', "LYS ", 'C', 9999, ' ', 1.5, -2.25, 3.125, 1.0,
                       0.0, "N") +
    printf_atom_record("ATOM", 99999, " CA", ' ', "LYS ", 'C', 9999, ' ', 2.5, -2.25, 3.125, 1.0,
                       0.0, "C") +
    printf_atom_record("ATOM", 100000, " C", ' ', "LYS ", 'C', 9999, ' ', 3.0, -1.0, 3.125, 1.0,
                       0.0, "C") +
    printf_atom_record("ATOM", 100001, " O", ' ', "LYS ", 'C', 9999, ' ', 3.5, -0.5, 3.125, 0.5,
                       12.34, "O") +
    printf_atom_record("ATOM", 100002, " N", 'A', "GLY ", 'C', 10000, ' ', -123.456, 999.999,
                       -0.001, 1.0, 0.0, "N") +
    printf_atom_record("ATOM", 100003, " N", ' ', "GLY ", 'C', 10001, 'B', 4.0, 5.0, 6.0, 1.0, 0.0,
                       "N") +
    printf_atom_record("HETATM", 100004, "CL", ' ', " CL ", 'C', 10002, ' ', 7.0, 8.0, 9.0, 1.0,
                       0.0, "CL") +
    printf_atom_record("ATOM", 100005, " P", ' ', "POPC", ' ', 123456, ' ', 10.0, 11.0, 12.0, 1.0,
                       0.0, "P") +
    open_babel_record + "CONECT100000100001\nEND\n";
  mesolens::StructureReadParams params;
  params.perceive_bonds = false;
  const auto file =
    mesolens::read_structure(mesolens_test::write_bytes("shifted.pdb", text), params);
  const mesolens::AtomTable& t = file.models.at(0);
  ASSERT_EQ(t.size(), 9u);
  EXPECT_EQ(
    t.serials,
    (std::vector<int>{ 99998, 99999, 100000, 100001, 100002, 100003, 100004, 100005, 100006 }));
  EXPECT_EQ(t.residue_numbers,
            (std::vector<int>{ 9999, 9999, 9999, 9999, 10000, 10001, 10002, 123456, 10003 }));
  EXPECT_EQ(t.atom_names,
            (std::vector<std::string>{ "N", "CA", "C", "O", "N", "N", "CL", "P", "O" }));
  EXPECT_EQ(
    t.residue_names,
    (std::vector<std::string>{ "LYS", "LYS", "LYS", "LYS", "GLY", "GLY", "CL", "POPC", "HOH" }));
  EXPECT_EQ(t.chain_ids, (std::vector<std::string>{ "C", "C", "C", "C", "C", "C", "C", "", "W" }));
  EXPECT_EQ(t.alt_locs, (std::vector<char>{ ' ', ' ', ' ', ' ', 'A', ' ', ' ', ' ', ' ' }));
  EXPECT_EQ(t.insertion_codes, (std::vector<char>{ ' ', ' ', ' ', ' ', ' ', 'B', ' ', ' ', ' ' }));
  EXPECT_EQ(t.atomic_numbers, (std::vector<std::uint8_t>{ 7, 6, 6, 8, 7, 7, 17, 15, 8 }));
  EXPECT_EQ(t.is_hetero, (std::vector<std::uint8_t>{ 0, 0, 0, 0, 0, 0, 1, 0, 1 }));
  EXPECT_FLOAT_EQ(t.occupancies[3], 0.5f);
  EXPECT_FLOAT_EQ(t.b_factors[3], 12.34f);
  const struct
  {
    std::size_t index;
    float x, y, z;
  } positions[] = { { 0, 1.5f, -2.25f, 3.125f },
                    { 4, -123.456f, 999.999f, -0.001f },
                    { 7, 10.0f, 11.0f, 12.0f },
                    { 8, 13.0f, 14.0f, -15.0f } };
  for (const auto& p : positions)
  {
    SCOPED_TRACE(p.index);
    EXPECT_FLOAT_EQ(t.positions[3 * p.index], p.x);
    EXPECT_FLOAT_EQ(t.positions[3 * p.index + 1], p.y);
    EXPECT_FLOAT_EQ(t.positions[3 * p.index + 2], p.z);
  }
  EXPECT_EQ(t.residue_indices.back() + 1, 6);
  // Serials over 99999 in CONECT run into each other: no split is certain, so no bond.
  EXPECT_TRUE(t.bonds.empty());
  const std::string warnings = std::accumulate(file.warnings.begin(), file.warnings.end(),
                                               std::string(), std::plus<std::string>());
  EXPECT_NE(warnings.find("running into each other"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("7 atom records have a serial over 99999"), std::string::npos)
    << warnings;
}

// Hybrid-36 (cci.lbl.gov/hybrid_36): A0000 = 100000 and A000 = 10000 in base 36 on from there,
// a0000 after ZZZZZ; in ATOM/HETATM and in CONECT records.
TEST(StructureFile, Hybrid36SerialsAndResidueNumbers)
{
  const std::string text =
    "ATOM  99998  N   GLY B9999      10.000  20.000  30.000  1.00 10.00           N\n"
    "ATOM  99999  CA  GLY B9999      11.450  20.000  30.000  1.00 10.00           C\n"
    "ATOM  A0000  C   GLY B9999      12.000  21.400  30.000  1.00 10.00           C\n"
    "ATOM  A0001  O   GLY B9999      11.300  22.400  30.000  1.00 10.00           O\n"
    "ATOM  A0002  N   ALA BA000      13.330  21.500  30.000  1.00 10.00           N\n"
    "ATOM  A000Z  CA  ALA BA000      14.000  22.800  30.000  1.00 10.00           C\n"
    "HETATM0a000 ZN    ZN BA001      20.000  20.000  20.000  1.00 10.00          ZN\n"
    "HETATMa0000 ZN    ZN Ba000      25.000  20.000  20.000  1.00 10.00          ZN\n"
    "CONECT9999899999\n"
    "CONECT99999A0000\n"
    "CONECTA0000A0001A0002\n"
    "CONECTA0002A000Z\n"
    "CONECTa0000A000Z\n"
    "END\n";
  mesolens::StructureReadParams params;
  params.perceive_bonds = false;
  const auto file =
    mesolens::read_structure(mesolens_test::write_bytes("hybrid36.pdb", text), params);
  const mesolens::AtomTable& t = file.models.at(0);
  ASSERT_EQ(t.size(), 8u);
  // 0a000 is no number (hybrid-36 codes fill their field): no serial, as for "*****".
  EXPECT_EQ(t.serials,
            (std::vector<int>{ 99998, 99999, 100000, 100001, 100002, 100035, 0, 43770016 }));
  EXPECT_EQ(t.residue_numbers,
            (std::vector<int>{ 9999, 9999, 9999, 9999, 10000, 10000, 10001, 1223056 }));
  EXPECT_EQ(t.atom_names, (std::vector<std::string>{ "N", "CA", "C", "O", "N", "CA", "ZN", "ZN" }));
  EXPECT_EQ(t.residue_names,
            (std::vector<std::string>{ "GLY", "GLY", "GLY", "GLY", "ALA", "ALA", "ZN", "ZN" }));
  EXPECT_EQ(t.atomic_numbers, (std::vector<std::uint8_t>{ 7, 6, 6, 8, 7, 6, 30, 30 }));
  EXPECT_FLOAT_EQ(t.positions[3 * 5], 14.0f);
  std::set<std::pair<int, int>> bonded_serials;
  for (const mesolens::Bond& bond : t.bonds)
  {
    bonded_serials.emplace(t.serials[bond.first], t.serials[bond.second]);
  }
  const std::set<std::pair<int, int>> expected = { { 99998, 99999 },   { 99999, 100000 },
                                                   { 100000, 100001 }, { 100000, 100002 },
                                                   { 100002, 100035 }, { 100035, 43770016 } };
  EXPECT_EQ(bonded_serials, expected);
  EXPECT_EQ(index_of_serial(t, 43770016), 7u);
}

// CHARMM writes a five-digit residue number in columns 23-27, where the insertion code would be.
TEST(StructureFile, CharmmFiveDigitResidueNumbers)
{
  const auto t =
    mesolens::read_structure(data_file("proteins/awkward/mdanalysis_5digitResid.pdb")).models.at(0);
  EXPECT_EQ(t.residue_numbers, (std::vector<int>{ 1, 10, 100, 1000, 10000 }));
  EXPECT_EQ(t.insertion_codes, std::vector<char>(5, ' '));
  EXPECT_EQ(t.residue_names, std::vector<std::string>(5, "TIP3"));
  EXPECT_EQ(t.serials, (std::vector<int>{ 1, 2, 3, 4, 5 }));
  EXPECT_NEAR(t.positions[3 * 4], -50.081f, 1e-4);
}

// A record pushed right by an overflowing number and then cut short or garbled is still an
// error naming the line, not a record read from the wrong columns.
TEST(StructureFile, DamagedShiftedRecordsThrow)
{
  const std::string good = printf_atom_record("ATOM", 100002, " N", ' ', "GLY ", 'C', 10000, ' ',
                                              11.104, 6.012, -3.456, 1.0, 0.0, "N");
  const std::string first = printf_atom_record("ATOM", 99999, " CA", ' ', "LYS ", 'C', 9999, ' ',
                                               2.5, -2.25, 3.125, 1.0, 0.0, "C");
  const struct
  {
    const char* name;
    std::string record;
    const char* problem;
  } cases[] = {
    { "shifted_truncated.pdb", good.substr(0, 46) + "\n", "too short" },
    { "shifted_garbled.pdb", good.substr(0, 38) + "1.1x4" + good.substr(43), "not a number" },
    { "shifted_unexplained.pdb", good.substr(0, 12) + "X" + good.substr(13), "not a number" },
  };
  for (const auto& c : cases)
  {
    SCOPED_TRACE(c.name);
    try
    {
      mesolens::read_structure(mesolens_test::write_bytes(c.name, first + c.record + "END\n"));
      ADD_FAILURE() << "no error";
    }
    catch (const mesolens::FileError& e)
    {
      EXPECT_NE(std::string(e.what()).find("line 2"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(c.problem), std::string::npos) << e.what();
    }
  }
}

// Found by fuzz_structure: gemmi 0.5 read the distance columns (74-78) of an SSBOND or LINK
// record cut at column 73 past the end of the line (a heap overflow under AddressSanitizer), and
// of records known by their first four letters in any case ("ssbo", "LINKR").
// The record is read as if blank-padded: the disulfide becomes a bond.
TEST(StructureFile, ConnectionRecordsCutInTheirDistanceColumns)
{
  mesolens::StructureReadParams params;
  params.perceive_bonds = false; // the bond can come from the SSBOND record only
  const auto file =
    mesolens::read_structure(std::string(MESOLENS_SOURCE_DIR) +
                               "/Testing/Data/proteins/fuzz_ssbond_cut_in_distance_columns.pdb",
                             params);
  ASSERT_EQ(file.models.size(), 1u);
  const mesolens::AtomTable& atoms = file.models.front();
  ASSERT_EQ(atoms.size(), 2u);
  ASSERT_EQ(atoms.bonds.size(), 1u);
  EXPECT_EQ(atoms.bonds.front().first, 0u);
  EXPECT_EQ(atoms.bonds.front().second, 1u);
}

namespace {
/// Every atom of every model as plain gemmi reads the file, in its order, against ours (all
/// alternate locations kept): the reader parses PDB atom records itself and must group, order
/// and read them as gemmi does.
void expect_atoms_as_gemmi_reads_them(const std::string& path)
{
  SCOPED_TRACE(path);
  const gemmi::Structure reference = gemmi::read_pdb_file(path);
  mesolens::StructureReadParams params;
  params.alt_locs = mesolens::AltLocPolicy::KeepAll;
  params.perceive_bonds = false;
  const mesolens::StructureFile file = mesolens::read_structure(path, params);
  std::size_t model_index = 0;
  for (const gemmi::Model& model : reference.models)
  {
    if (model.chains.empty())
    {
      continue;
    }
    ASSERT_LT(model_index, file.models.size());
    const mesolens::AtomTable& t = file.models[model_index++];
    std::size_t i = 0;
    for (const gemmi::Chain& chain : model.chains)
    {
      for (const gemmi::Residue& residue : chain.residues)
      {
        for (const gemmi::Atom& atom : residue.atoms)
        {
          ASSERT_LT(i, t.size());
          EXPECT_EQ(t.atom_names[i], atom.name);
          EXPECT_EQ(t.atomic_numbers[i],
                    atom.element.elem == gemmi::El::D ? 1 : static_cast<int>(atom.element.elem));
          EXPECT_EQ(t.positions[3 * i], float(atom.pos.x));
          EXPECT_EQ(t.positions[3 * i + 1], float(atom.pos.y));
          EXPECT_EQ(t.positions[3 * i + 2], float(atom.pos.z));
          EXPECT_EQ(t.occupancies[i], atom.occ);
          EXPECT_EQ(t.b_factors[i], atom.b_iso);
          EXPECT_EQ(t.alt_locs[i], atom.altloc ? atom.altloc : ' ');
          EXPECT_EQ(t.formal_charges[i], atom.charge);
          EXPECT_EQ(t.residue_names[i].substr(0, 3), residue.name);
          EXPECT_EQ(t.residue_numbers[i], int(residue.seqid.num));
          EXPECT_EQ(t.chain_ids[i], chain.name);
          EXPECT_EQ(t.is_hetero[i], residue.het_flag == 'H' ? 1 : 0);
          ++i;
        }
      }
    }
    EXPECT_EQ(i, t.size());
  }
  EXPECT_EQ(model_index, file.models.size());
}
} // namespace

TEST(StructureFile, PdbAtomsAreReadAsGemmiReadsThem)
{
  for (const char* name : { "1crn.pdb", "1ubq.pdb", "1l2y.pdb", "1aki.pdb", "4we2.pdb", "1dix.pdb",
                            "3o5r.pdb", "1bna.pdb", "4gxy.pdb", "1tii.pdb", "1d3z.pdb" })
  {
    expect_atoms_as_gemmi_reads_them(data_file(std::string("proteins/") + name));
  }
  // Records out of order: residue 1 of chain A comes back after residue 2 (its atoms join it),
  // chain A comes back after chain B (a third run), a record too short for occupancy and B
  // (1 and 20, as gemmi), names without an element column ("1HB", "C210", "HG21").
  const std::string text =
    "ATOM      1  N   ALA A   1      10.000  10.000  10.000  1.00 15.00           N\n"
    "ATOM      2  CA  ALA A   1      11.000  10.000  10.000  1.00 15.00           C\n"
    "ATOM      3  N   GLY A   2      12.000  10.000  10.000  1.00 15.00           N\n"
    "ATOM      4  C   ALA A   1      11.500  11.000  10.000  0.50 16.00           C\n"
    "ATOM      5 1HB  ALA A   1      11.500  11.000  11.000\n"
    "HETATM    6 C210 LIG B   1      20.000  20.000  20.000  1.00 30.00\n"
    "ATOM      7 HG21 THR A   3      -1.250   0.005  -0.000  1.00  5.00\n"
    "ATOM      8  FE  HEM A   4       0.000   0.000   3.000  1.00  5.00          FE2+\n"
    "END\n"
    "ATOM      9  N   ALA A   9      10.000  10.000  10.000  1.00 15.00           N\n";
  const std::string path = mesolens_test::write_bytes("records_out_of_order.pdb", text);
  expect_atoms_as_gemmi_reads_them(path);
  mesolens::StructureReadParams params;
  params.perceive_bonds = false;
  const mesolens::AtomTable t = mesolens::read_structure(path, params).models.at(0);
  ASSERT_EQ(t.size(), 8u); // nothing after END
  EXPECT_EQ(t.serials, (std::vector<int>{ 1, 2, 4, 5, 3, 6, 7, 8 }));
  EXPECT_EQ(t.chain_ids, (std::vector<std::string>{ "A", "A", "A", "A", "A", "B", "A", "A" }));
  EXPECT_EQ(t.b_factors[3], 20.0f);
  EXPECT_EQ(t.occupancies[3], 1.0f);
  EXPECT_EQ(t.atomic_numbers[3], 1);  // 1HB
  EXPECT_EQ(t.atomic_numbers[5], 6);  // C210
  EXPECT_EQ(t.atomic_numbers[6], 1);  // HG21
  EXPECT_EQ(t.atomic_numbers[7], 26); // FE
  EXPECT_EQ(t.formal_charges[7], 2);
}

TEST(StructureFile, PdbModelRecordsAsGemmiChecksThem)
{
  const std::string atom =
    "ATOM      1  CA  ALA A   1      10.000  10.000  10.000  1.00 15.00           C\n";
  // Atoms after ENDMDL start the next model, numbered on; that number being taken is an error.
  EXPECT_EQ(
    mesolens::read_structure(
      mesolens_test::write_bytes("implicit_models.pdb", atom + "ENDMDL\n" + atom + "ENDMDL\n"))
      .models.size(),
    2u);
  EXPECT_THROW(mesolens::read_structure(mesolens_test::write_bytes(
                 "atoms_between_models.pdb",
                 "MODEL        2\n" + atom + "ENDMDL\n" + atom + "ENDMDL\n" + atom)),
               mesolens::FileError);
  EXPECT_THROW(
    mesolens::read_structure(mesolens_test::write_bytes(
      "model_without_endmdl.pdb", "MODEL        1\n" + atom + "MODEL        2\n" + atom)),
    mesolens::FileError);
  EXPECT_THROW(mesolens::read_structure(mesolens_test::write_bytes(
                 "repeated_model.pdb",
                 "MODEL        1\n" + atom + "ENDMDL\nMODEL        1\n" + atom + "ENDMDL\n")),
               mesolens::FileError);
  EXPECT_THROW(
    mesolens::read_structure(mesolens_test::write_bytes(
      "anisou_first.pdb",
      "ANISOU    1  CA  ALA A   1      100    200    300      0      0      0       C\n" + atom)),
    mesolens::FileError);
}

TEST(StructureFile, DisulfideRecordsFindTheSulfurOfTheirResidues)
{
  // SSBOND names residues only: SG, or the residue's first sulfur when it has no SG (here SD).
  const std::string text =
    "SSBOND   1 MET A    1    CYS A    2                          1555   1555  2.04\n"
    "ATOM      1  CA  MET A   1       0.000   0.000   0.000  1.00 10.00           C\n"
    "ATOM      2  SD  MET A   1       1.000   0.000   0.000  1.00 10.00           S\n"
    "ATOM      3  CA  CYS A   2      10.000   0.000   0.000  1.00 10.00           C\n"
    "ATOM      4  SG  CYS A   2       3.000   0.000   0.000  1.00 10.00           S\n";
  mesolens::StructureReadParams params;
  params.perceive_bonds = false;
  const mesolens::AtomTable t =
    mesolens::read_structure(mesolens_test::write_bytes("ssbond_sd.pdb", text), params)
      .models.at(0);
  ASSERT_EQ(t.bonds.size(), 1u);
  EXPECT_EQ(t.bonds[0].first, 1u);
  EXPECT_EQ(t.bonds[0].second, 3u);
}
