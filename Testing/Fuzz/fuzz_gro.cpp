// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: GROMACS .gro files, as the atom reader takes them: the topology
// (mesolens::read_gro_topology) with its bonds and molecules (mesolens::build_connectivity),
// then every frame through mesolens::TrajectoryFile. The first byte chooses: bit 0 no bond
// perception, bit 1 coarse-grained beads forced, bit 2 incomplete frames skipped (else refused);
// the rest is the file. Every input must give atoms or a mesolens::Error.
#include "fuzz_frames.h"
#include "fuzz_input.h"

#include "mesolens/common/errors.h"
#include "mesolens/io/gro_topology.h"
#include "mesolens/io/structure_file.h"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  using mesolens_fuzz::require;
  static const mesolens_fuzz::ScratchFile gro(".gro");
  mesolens_fuzz::FuzzInput input(data, size);
  const std::uint8_t options = input.byte();
  const std::string& path = gro.write(input.rest());

  mesolens::StructureReadParams params;
  params.perceive_bonds = !(options & 1);
  params.force_coarse_grained = options & 2;
  try
  {
    mesolens::AtomTable table = mesolens::read_gro_topology(path);
    mesolens::build_connectivity(table, {}, params, false);
    const std::size_t atoms = table.size();
    require(atoms > 0 && table.positions.size() == 3 * atoms && table.molecule_ids.size() == atoms);
    for (const mesolens::Bond& bond : table.bonds)
    {
      require(bond.first < atoms && bond.second < atoms);
    }
  }
  catch (const mesolens::Error&)
  {
  }
  try
  {
    mesolens_fuzz::read_frames(path, options & 4, 8);
  }
  catch (const mesolens::Error&)
  {
  }
  return 0;
}
