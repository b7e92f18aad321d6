// SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: the structure reader (mesolens::read_structure) on PDB, PDBx/mmCIF and
// gzipped input, with the options that change its code path. The first byte chooses:
//   bits 0-1  the file: .pdb, .cif, no extension (format from the content), gzipped (.pdb.gz,
//             or .cif.gz when bit 7 is set)
//   bit 2     every alternate location kept (else the most occupied)
//   bit 3     waters removed          bit 4  hydrogens removed
//   bit 5     no bond perception      bit 6  coarse-grained beads forced
// The rest is the file. Every input must give a structure or a mesolens::Error. The file's
// assemblies are counted and given as instances, and expanded when small: each of these gives
// a consistent result or a mesolens::Error.
#include "fuzz_input.h"

#include "mesolens/common/errors.h"
#include "mesolens/io/structure_file.h"
#include "mesolens/protein/assembly.h"

#include <zlib.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

namespace {

void check_model(const mesolens::AtomTable& table)
{
  using mesolens_fuzz::require;
  const std::size_t atoms = table.size();
  require(atoms > 0);
  require(table.positions.size() == 3 * atoms);
  require(table.residue_names.size() == atoms && table.residue_indices.size() == atoms &&
          table.molecule_ids.size() == atoms && table.secondary_structure.size() == atoms);
  for (const float coordinate : table.positions)
  {
    require(std::isfinite(coordinate));
  }
  for (const mesolens::Bond& bond : table.bonds)
  {
    require(std::size_t(bond.first) < atoms && std::size_t(bond.second) < atoms &&
            bond.first != bond.second);
  }
}

/// Every assembly: within the copy limit, as many instances as copies, and (when small) the
/// expansion as many atoms as counted, consistent, finite and numbered by copy.
void check_assemblies(const mesolens::StructureFile& structure)
{
  using mesolens_fuzz::require;
  const mesolens::AtomTable& unit = structure.models.front();
  std::size_t copies = 0;
  for (const mesolens::Assembly& assembly : structure.assemblies)
  {
    copies += assembly.copy_count();
    require(assembly.copy_count() > 0 && copies <= mesolens::max_assembly_copies);
    std::size_t atoms = 0;
    mesolens::AssemblyExpansion expanded;
    try // an operator may move atoms beyond float's range: InvalidInput
    {
      atoms = mesolens::assembly_atom_count(unit, assembly);
      const mesolens::AssemblyInstances instances = mesolens::assembly_instances(unit, assembly);
      require(instances.instances.size() == assembly.copy_count());
      if (atoms == 0 || atoms > 100000)
      {
        continue;
      }
      expanded = mesolens::expand_assembly(unit, assembly);
    }
    catch (const mesolens::InvalidInput&)
    {
      continue;
    }
    require(expanded.atoms.size() == atoms && expanded.copy_of_atom.size() == atoms);
    require(expanded.atoms.label_asym_ids.size() == atoms);
    check_model(expanded.atoms);
    require(std::size_t(expanded.copy_of_atom.back()) < assembly.copy_count());
  }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  static const mesolens_fuzz::ScratchFile pdb(".pdb"), cif(".cif"), bare(""), pdb_gz(".pdb.gz"),
    cif_gz(".cif.gz");
  mesolens_fuzz::FuzzInput input(data, size);
  const std::uint8_t options = input.byte();
  mesolens::StructureReadParams params;
  params.alt_locs =
    (options & 4) ? mesolens::AltLocPolicy::KeepAll : mesolens::AltLocPolicy::HighestOccupancy;
  params.remove_waters = options & 8;
  params.remove_hydrogens = options & 16;
  params.perceive_bonds = !(options & 32);
  params.force_coarse_grained = options & 64;
  const std::string bytes = input.rest();

  std::string path;
  switch (options & 3)
  {
    case 0:
      path = pdb.write(bytes);
      break;
    case 1:
      path = cif.write(bytes);
      break;
    case 2:
      path = bare.write(bytes);
      break;
    default: {
      const mesolens_fuzz::ScratchFile& file = (options & 128) ? cif_gz : pdb_gz;
      path = file.write("");
      if (gzFile out = gzopen(path.c_str(), "wb"))
      {
        gzwrite(out, bytes.data(), unsigned(bytes.size()));
        gzclose(out);
      }
    }
  }
  try
  {
    const mesolens::StructureFile structure = mesolens::read_structure(path, params);
    mesolens_fuzz::require(!structure.models.empty());
    for (const mesolens::AtomTable& model : structure.models)
    {
      check_model(model);
    }
    check_assemblies(structure);
  }
  catch (const mesolens::Error&)
  {
  }
  return 0;
}
