// SPDX-License-Identifier: GPL-3.0-or-later
// Writes small XTC and TRR files, cut from a real trajectory with GROMACS' own writers, as seeds
// for the trajectory fuzz target (make_fuzz_seeds.py puts its option byte in front): the first
// FRAMES frames of the first ATOMS atoms. XTC compresses only frames of 10 atoms or more, so
// the seeds come in two sizes, 3 and 40 atoms, to reach both code paths.
//
// Built on request only (target write_trajectory_seeds, not part of `all`, not a test):
//   write_trajectory_seeds Data/membranes/yiip_popepopg.xtc OUTPUT_DIR
#include <gromacs/fileio/oenv.h>
#include <gromacs/fileio/trxio.h>
#include <gromacs/trajectory/trajectoryframe.h>

#include <cstdio>
#include <string>

namespace {

void write_cut(const char* input, const std::string& output, int atoms, int frames)
{
  gmx_output_env_t* oenv = nullptr;
  output_env_init_default(&oenv);
  t_trxstatus* in = nullptr;
  t_trxframe frame;
  clear_trxframe(&frame, TRUE);
  t_trxstatus* out = open_trx(output.c_str(), "w");
  bool more = read_first_frame(oenv, &in, input, &frame, TRX_NEED_X);
  for (int written = 0; more && written < frames; ++written)
  {
    const int all_atoms = frame.natoms;
    frame.natoms = atoms < all_atoms ? atoms : all_atoms;
    frame.bV = FALSE;
    frame.bF = FALSE;
    write_trxframe(out, &frame, nullptr);
    frame.natoms = all_atoms;
    more = read_next_frame(oenv, in, &frame);
  }
  close_trx(out);
  close_trx(in);
  done_frame(&frame);
  output_env_done(oenv);
}

} // namespace

int main(int argc, char** argv)
{
  if (argc != 3)
  {
    std::fprintf(stderr, "usage: write_trajectory_seeds INPUT.xtc OUTPUT_DIR\n");
    return 2;
  }
  const std::string directory = argv[2];
  for (const int atoms : { 3, 40 })
  {
    for (const char* format : { "xtc", "trr" })
    {
      write_cut(argv[1], directory + "/seed_" + std::to_string(atoms) + "_atoms." + format, atoms,
                2);
    }
  }
  return 0;
}
