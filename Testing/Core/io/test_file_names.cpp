// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/io/file_names.h"

#include "mesolens_test_data.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace {
/// An empty folder of its own under the test output, with `files` (empty) in it.
fs::path folder_with(const std::string& name, std::initializer_list<const char*> files)
{
  const fs::path folder = fs::path(mesolens_test::output_file(name));
  fs::remove_all(folder);
  fs::create_directories(folder);
  for (const char* file : files)
  {
    std::ofstream(folder / file) << "";
  }
  return folder;
}
} // namespace

TEST(FileNames, ExtensionsInLowerCaseThroughCompression)
{
  EXPECT_EQ(mesolens::file_extension("cell/mito.OBJ"), "obj");
  EXPECT_EQ(mesolens::file_extension("1abc.pdb.gz"), "gz");
  EXPECT_EQ(mesolens::file_extension("1abc.pdb.gz", true), "pdb");
  EXPECT_EQ(mesolens::file_extension("folder.d/README"), "");
}

TEST(FileNames, TheTopologyOfTheSameNameComesFirst)
{
  const fs::path run =
    folder_with("beside_same_name", { "md.xtc", "md.gro", "md.pdb", "conf.gro" });
  EXPECT_EQ(mesolens::topology_beside((run / "md.xtc").string()), (run / "md.gro").string());
  const fs::path pdb = folder_with("beside_pdb", { "md.trr", "md.pdb.gz", "other.cif" });
  EXPECT_EQ(mesolens::topology_beside((pdb / "md.trr").string()), (pdb / "md.pdb.gz").string());
}

TEST(FileNames, OtherwiseTheOnlyTopologyInTheFolder)
{
  const fs::path one = folder_with("beside_only", { "traj.xtc", "conf.gro", "notes.txt" });
  EXPECT_EQ(mesolens::topology_beside((one / "traj.xtc").string()), (one / "conf.gro").string());
  // Two candidates and none of the trajectory's name: no guess.
  const fs::path two = folder_with("beside_two", { "traj.xtc", "a.gro", "b.pdb" });
  EXPECT_EQ(mesolens::topology_beside((two / "traj.xtc").string()), "");
  const fs::path none = folder_with("beside_none", { "traj.xtc" });
  EXPECT_EQ(mesolens::topology_beside((none / "traj.xtc").string()), "");
  EXPECT_EQ(mesolens::topology_beside((none / "missing" / "traj.xtc").string()), "");
  // A multi-frame .gro is not its own topology by the folder rule.
  const fs::path gro = folder_with("beside_gro", { "frames.gro" });
  EXPECT_EQ(mesolens::topology_beside((gro / "frames.gro").string()), "");
}
