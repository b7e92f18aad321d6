// SPDX-License-Identifier: GPL-3.0-or-later
// Reference coordinates come from MDAnalysis (Testing/Tools/reference_values.py).
#include "mesolens/io/trajectory_file.h"

#include "mesolens/common/errors.h"
#include "mesolens/io/gro_topology.h"
#include "mesolens_test_data.h"

#include <gromacs/fileio/oenv.h>
#include <gromacs/fileio/trxio.h>
#include <gromacs/trajectory/trajectoryframe.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace {
using mesolens_test::data_file;

void expect_atom(const mesolens::TrajectoryFrame& frame, std::size_t atom, float x, float y,
                 float z)
{
  EXPECT_NEAR(frame.positions[3 * atom], x, 1e-3) << atom;
  EXPECT_NEAR(frame.positions[3 * atom + 1], y, 1e-3) << atom;
  EXPECT_NEAR(frame.positions[3 * atom + 2], z, 1e-3) << atom;
}

/// Writes the frames of an XTC as a full-precision TRR with GROMACS' own writer; with
/// `poison_atom` >= 0, that atom's x in the last frame is NaN.
std::string trr_copy_of(const std::string& xtc, const std::string& name, int poison_atom = -1)
{
  const std::string path = mesolens_test::output_file(name);
  gmx_output_env_t* oenv = nullptr;
  output_env_init_default(&oenv);
  t_trxstatus* in = nullptr;
  t_trxframe frame;
  clear_trxframe(&frame, TRUE);
  t_trxstatus* out = open_trx(path.c_str(), "w");
  bool more = read_first_frame(oenv, &in, xtc.c_str(), &frame, TRX_NEED_X);
  int written = 0;
  while (more)
  {
    frame.bV = FALSE;
    frame.bF = FALSE;
    if (poison_atom >= 0 && written == 4)
    {
      frame.x[poison_atom][0] = std::numeric_limits<float>::quiet_NaN();
    }
    write_trxframe(out, &frame, nullptr);
    ++written;
    more = read_next_frame(oenv, in, &frame);
  }
  close_trx(out);
  close_trx(in);
  done_frame(&frame);
  output_env_done(oenv);
  return path;
}
} // namespace

TEST(TrajectoryFile, XtcFramesMatchMDAnalysis)
{
  mesolens::TrajectoryFile file(data_file("membranes/yiip_popepopg.xtc"));
  ASSERT_EQ(file.frame_count(), 5u);
  EXPECT_EQ(file.atom_count(), 43480u);
  EXPECT_DOUBLE_EQ(file.frame_times()[4], 80000.0);
  // Random access, out of order.
  const auto frame4 = file.read_frame(4);
  expect_atom(frame4, 0, 23.160002f, 18.140001f, 53.930000f);
  expect_atom(frame4, 1000, 10.279999f, 42.620003f, 48.170006f);
  expect_atom(frame4, 43479, -15.010000f, 62.420002f, 83.229996f);
  const auto frame2 = file.read_frame(2);
  expect_atom(frame2, 0, 22.75f, 14.020000f, 56.940002f);
  expect_atom(frame2, 43479, -9.340000f, 37.360001f, 73.540009f);
  EXPECT_DOUBLE_EQ(frame2.time_ps, 40000.0);
  // Hexagonal box: |a| = 110.216 Å, gamma = 120 degrees.
  EXPECT_NEAR(frame2.box.vectors[0][0], 110.21635, 1e-3);
  EXPECT_NEAR(frame2.box.vectors[1][0], -0.5 * 110.21623, 1e-2);
  const auto frame0 = file.read_frame(0);
  expect_atom(frame0, 0, 21.27f, 11.350001f, 62.890007f);
  EXPECT_THROW(file.read_frame(5), mesolens::InvalidInput);
}

TEST(TrajectoryFile, TriclinicVesicle)
{
  mesolens::TrajectoryFile file(data_file("membranes/martini_dppc_vesicle.xtc"));
  ASSERT_EQ(file.frame_count(), 11u);
  const auto frame = file.read_frame(7);
  EXPECT_DOUBLE_EQ(frame.time_ps, 3500.0);
  expect_atom(frame, 0, 6.22f, 272.31f, 248.27002f);
  expect_atom(frame, 20000, 59.820004f, 321.47003f, 178.59001f);
  expect_atom(frame, 36863, 12.96f, 270.84003f, 194.63f);
  EXPECT_FALSE(frame.box.is_orthorhombic());
}

TEST(TrajectoryFile, TrrWrittenByGromacsReadsTheSameFrames)
{
  const std::string trr = trr_copy_of(data_file("membranes/yiip_popepopg.xtc"), "yiip.trr");
  mesolens::TrajectoryFile file(trr);
  ASSERT_EQ(file.frame_count(), 5u);
  mesolens::TrajectoryFile xtc(data_file("membranes/yiip_popepopg.xtc"));
  for (std::size_t f : { 3u, 1u })
  {
    const auto a = file.read_frame(f);
    const auto b = xtc.read_frame(f);
    ASSERT_EQ(a.positions.size(), b.positions.size());
    for (std::size_t i = 0; i < a.positions.size(); i += 997)
    {
      EXPECT_NEAR(a.positions[i], b.positions[i], 1e-4);
    }
    EXPECT_DOUBLE_EQ(a.time_ps, b.time_ps);
  }
}

TEST(TrajectoryFile, NonFiniteCoordinatesAreAnError)
{
  mesolens::TrajectoryFile file(
    trr_copy_of(data_file("membranes/yiip_popepopg.xtc"), "yiip_nan.trr", 1000));
  EXPECT_NO_THROW(file.read_frame(3));
  try
  {
    file.read_frame(4);
    FAIL() << "a NaN coordinate was accepted";
  }
  catch (const mesolens::FileError& e)
  {
    EXPECT_NE(std::string(e.what()).find("atom 1001"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("non-finite"), std::string::npos) << e.what();
  }
  // GRO topology with "nan" in a coordinate field: GROMACS itself rejects it.
  std::string gro = mesolens_test::read_bytes(data_file("membranes/martini_dppc_chol_bilayer.gro"));
  const std::size_t third_line = gro.find('\n', gro.find('\n') + 1) + 1;
  gro.replace(third_line + 20, 8, "     nan");
  EXPECT_THROW(mesolens::read_gro_topology(mesolens_test::write_bytes("nan.gro", gro)),
               mesolens::FileError);
}

TEST(TrajectoryFile, GroAsTrajectory)
{
  mesolens::TrajectoryFile file(data_file("membranes/martini_dppc_vesicle.gro"));
  ASSERT_EQ(file.frame_count(), 1u);
  const auto frame = file.read_frame(0);
  EXPECT_NEAR(frame.positions[0], 470.89f, 1e-2); // 47.089 nm
  // Two concatenated copies make a two-frame GRO.
  const std::string one =
    mesolens_test::read_bytes(data_file("membranes/martini_dppc_chol_bilayer.gro"));
  mesolens::TrajectoryFile twice(mesolens_test::write_bytes("two_frames.gro", one + one));
  EXPECT_EQ(twice.frame_count(), 2u);
  EXPECT_EQ(twice.read_frame(1).positions, twice.read_frame(0).positions);
}

TEST(TrajectoryFile, TruncatedXtc)
{
  const std::string path = mesolens_test::truncated_copy(data_file("membranes/yiip_popepopg.xtc"),
                                                         500000, "truncated.xtc");
  try
  {
    mesolens::TrajectoryFile file(path);
    FAIL() << "a truncated trajectory was accepted";
  }
  catch (const mesolens::FileError& e)
  {
    EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("frame 3"), std::string::npos) << e.what();
  }
  mesolens::TrajectoryFile lenient(path, mesolens::TrajectoryFile::IncompleteFrames::Skip);
  EXPECT_EQ(lenient.frame_count(), 3u);
  EXPECT_NO_THROW(lenient.read_frame(2));
}

TEST(TrajectoryFile, BadFiles)
{
  using mesolens_test::output_file;
  EXPECT_THROW(mesolens::TrajectoryFile(output_file("missing.xtc")), mesolens::FileError);
  EXPECT_THROW(mesolens::TrajectoryFile(mesolens_test::write_bytes("empty.xtc", "")),
               mesolens::FileError);
  EXPECT_THROW(mesolens::TrajectoryFile(mesolens_test::garbage_file("garbage.xtc")),
               mesolens::FileError);
  EXPECT_THROW(mesolens::TrajectoryFile(mesolens_test::garbage_file("garbage.trr")),
               mesolens::FileError);
  EXPECT_THROW(mesolens::TrajectoryFile(mesolens_test::garbage_file("garbage.gro")),
               mesolens::FileError);
  EXPECT_THROW(mesolens::TrajectoryFile(data_file("membranes/yiip_popepopg.gro") + ".dcd"),
               mesolens::FileError);
  // A header cut inside the first frame.
  EXPECT_THROW(mesolens::TrajectoryFile(mesolens_test::truncated_copy(
                 data_file("membranes/yiip_popepopg.xtc"), 30, "header.xtc")),
               mesolens::FileError);
}

TEST(TrajectoryFile, CorruptCompressedDataIsAnErrorNotACrash)
{
  // Keep the frame headers, scramble the compressed coordinates of frame 1.
  std::string bytes = mesolens_test::read_bytes(data_file("membranes/yiip_popepopg.xtc"));
  for (std::size_t i = 166592 + 200; i < 166592 + 60000; ++i)
  {
    bytes[i] = char(bytes[i] * 31 + 7);
  }
  mesolens::TrajectoryFile file(mesolens_test::write_bytes("scrambled.xtc", bytes));
  ASSERT_EQ(file.frame_count(), 5u);
  try
  {
    const auto frame = file.read_frame(1);
    // Decoding garbage may "succeed"; then the values must at least be finite numbers.
    for (float v : frame.positions)
    {
      ASSERT_TRUE(std::isfinite(v));
    }
  }
  catch (const mesolens::FileError&)
  {
  }
  EXPECT_NO_THROW(file.read_frame(0)); // the reader recovers for the intact frames
}

// Found by fuzz_trajectory (a heap corruption that ASan reported later, in fclose): GROMACS
// reads a frame's compressed bytes into a buffer of 60 ints up to 16 atoms, else of 1.2 ints per
// coordinate, whatever size the frame claims; and it sizes its coordinates by the header's atom
// count but decodes the count repeated before them.
TEST(TrajectoryFile, XtcFramesThatWouldOverrunGromacsBuffersAreRefused)
{
  const auto xtc = [](std::int32_t header_atoms, std::int32_t atoms, std::int32_t bytes) {
    std::string frame;
    const auto put = [&frame](std::int32_t value) {
      for (int shift = 24; shift >= 0; shift -= 8)
      {
        frame.push_back(char((std::uint32_t(value) >> shift) & 0xff));
      }
    };
    put(1995);
    put(header_atoms);
    put(0); // step
    put(0); // time
    for (int k = 0; k < 9; ++k)
    {
      put(k % 4 == 0 ? 0x40a00000 : 0); // a 5 nm cubic box
    }
    put(atoms);
    put(0x447a0000); // precision 1000
    for (int k = 0; k < 3; ++k)
    {
      put(0); // minint
    }
    for (int k = 0; k < 3; ++k)
    {
      put(100); // maxint
    }
    put(10);    // small-coordinate index
    put(bytes); // compressed bytes, all zero
    frame.append(std::size_t((bytes + 3) / 4 * 4), '\0');
    return frame;
  };
  const struct
  {
    std::string bytes;
    const char* problem;
  } cases[] = {
    { xtc(17, 17, 260), "compressed size out of range" },        // 232 bytes fit
    { xtc(13, 13, 224), "compressed size out of range" },        // 228 fit (on GROMACS' stack)
    { xtc(12, 30, 100), "atom counts 12 and 30 in its header" }, // found by the index
    { xtc(3, 9, 0), "atom counts 3 and 9 in its header" },
  };
  for (const auto& c : cases)
  {
    SCOPED_TRACE(c.problem);
    try
    {
      mesolens::TrajectoryFile file(mesolens_test::write_bytes("overrun.xtc", c.bytes));
      file.read_frame(0);
      ADD_FAILURE() << "read";
    }
    catch (const mesolens::FileError& e)
    {
      EXPECT_NE(std::string(e.what()).find(c.problem), std::string::npos) << e.what();
    }
  }
}

// Found by fuzz_trajectory (valgrind named the write): for a coordinate range of 2^30 or more,
// GROMACS' int arithmetic takes 32 bits per coordinate where the check counted 31, so the check
// walked another bit stream than GROMACS decodes, and GROMACS wrote past its integer array.
TEST(TrajectoryFile, CoordinateRangesOf2To30AreWalkedAsGromacsDecodesThem)
{
  mesolens::TrajectoryFile file(
    std::string(MESOLENS_SOURCE_DIR) +
      "/Testing/Data/trajectories/fuzz_xtc_coordinate_range_over_2e30.xtc",
    mesolens::TrajectoryFile::IncompleteFrames::Skip);
  ASSERT_EQ(file.frame_count(), 1u);
  try
  {
    file.read_frame(0);
    ADD_FAILURE() << "read";
  }
  catch (const mesolens::FileError& e)
  {
    EXPECT_NE(std::string(e.what()).find("bit stream ends early"), std::string::npos) << e.what();
  }
}

// Found by fuzz_trajectory: opening GROMACS' decoder decodes the first frame, which was not
// checked when a later frame was read first (a crash in xdr3dfcoord).
TEST(TrajectoryFile, ACorruptFirstFrameIsCaughtWhenALaterOneIsReadFirst)
{
  std::string bytes = mesolens_test::read_bytes(data_file("membranes/yiip_popepopg.xtc"));
  bytes[84] = bytes[85] = bytes[86] = 0; // frame 0's small-coordinate index: 99
  bytes[87] = 99;
  mesolens::TrajectoryFile file(mesolens_test::write_bytes("corrupt_first_frame.xtc", bytes));
  ASSERT_EQ(file.frame_count(), 5u);
  try
  {
    file.read_frame(1);
    ADD_FAILURE() << "frame 1 read";
  }
  catch (const mesolens::FileError& e)
  {
    EXPECT_NE(std::string(e.what()).find("the frame at byte 0 is corrupt"), std::string::npos)
      << e.what();
  }
}

// Found by fuzz_gro: GROMACS' reader dereferences null for a file of no atoms and a bad box
// line, copies a coordinate field as wide as the first line's decimal points are apart into a
// buffer of 256, and ends the process on lines it cannot read. Such files are refused first.
TEST(GroTopology, FilesGromacsCannotReadAreRefusedFirst)
{
  const std::string atom = "    1RES     CA    1   0.000   0.000   0.000\n";
  const std::string wide_fields = "    1RES     CA    1" + std::string(300, ' ') + "1." +
    std::string(298, ' ') + "2." + std::string(298, ' ') + "3.\n";
  const struct
  {
    std::string text;
    const char* problem;
  } cases[] = {
    { "no atoms\n    0\n  10.sting ex000\n", "claims 0 atoms" },
    { "wide\n    1\n" + wide_fields + "   1.0   1.0   1.0\n",
      "decimal points of x, y and z are not evenly spaced" },
    { "short\n    1\n    1RES     CA    1   0.000   0.000\n   1.0   1.0   1.0\n",
      "atom line 1 has 36 characters" },
    { "two numbers\n    1\n    1RES     CA    1   0.000   0.0 0   0.000\n   1 1 1\n",
      "y is not one number in its 8 columns" },
    { "bad box\n    1\n" + atom + "   box\n", "the box line after the atoms" },
    { "cut\n    2\n" + atom, "incomplete" },
  };
  for (const auto& c : cases)
  {
    SCOPED_TRACE(c.text.substr(0, 20));
    try
    {
      mesolens::read_gro_topology(mesolens_test::write_bytes("refused.gro", c.text));
      ADD_FAILURE() << "accepted";
    }
    catch (const mesolens::FileError& e)
    {
      EXPECT_NE(std::string(e.what()).find(c.problem), std::string::npos) << e.what();
    }
  }
  const mesolens::AtomTable one = mesolens::read_gro_topology(
    mesolens_test::write_bytes("one.gro", "one\n    1\n" + atom + "   1.0   1.0   1.0\n"));
  EXPECT_EQ(one.size(), 1u);
}

TEST(GroTopology, AtomsResiduesAndBox)
{
  const auto t = mesolens::read_gro_topology(data_file("membranes/dppc128_slipids_323K.gro"));
  EXPECT_EQ(t.size(), 28160u);
  EXPECT_NEAR(t.box.vectors[0][0], 63.0, 0.1);
  EXPECT_EQ(t.residue_names[0], "DPPC");
  EXPECT_EQ(t.atomic_numbers[0], 7); // N of the choline
  // Awkward but readable: a blank atom name, velocities on only some lines.
  EXPECT_EQ(
    mesolens::read_gro_topology(data_file("proteins/awkward/mdanalysis_missing_atomname.gro"))
      .size(),
    1u);
  EXPECT_EQ(
    mesolens::read_gro_topology(data_file("proteins/awkward/mdanalysis_test_incomplete_vel.gro"))
      .size(),
    5u);
  const auto bad = data_file("proteins/awkward/mdanalysis_empty_atom.gro");
  EXPECT_THROW(mesolens::read_gro_topology(bad), mesolens::FileError);
  EXPECT_THROW(mesolens::read_gro_topology(mesolens_test::output_file("nothing.gro")),
               mesolens::FileError);
  EXPECT_THROW(mesolens::read_gro_topology(mesolens_test::garbage_file("garbage_topology.gro")),
               mesolens::FileError);
  EXPECT_THROW(mesolens::read_gro_topology(mesolens_test::truncated_copy(
                 data_file("membranes/dppc128_slipids_323K.gro"), 5000, "cut.gro")),
               mesolens::FileError);
}
