// SPDX-License-Identifier: GPL-3.0-or-later
// Reference numbers come from independent tools (python3-gemmi, python3-mdanalysis); see
// Testing/Tools/reference_values.py.
#include "mesolens/structure_file.h"

#include "mesolens/errors.h"
#include "mesolens_test_data.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <dirent.h>
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
