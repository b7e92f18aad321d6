// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/io/gro_topology.h"

#include "io/detail/file_checks.h"
#include "io/detail/gromacs_support.h"
#include "io/detail/trajectory_index.h"
#include "mesolens/molecules/elements.h"
#include "mesolens/common/errors.h"

#include <gromacs/fileio/confio.h>
#include <gromacs/pbcutil/pbc.h>
#include <gromacs/topology/atoms.h>
#include <gromacs/topology/symtab.h>
#include <gromacs/utility/smalloc.h>

#include <cmath>

namespace mesolens {

namespace {
/// Owns what readConfAndAtoms allocates.
struct GroConfiguration
{
  t_symtab symtab{};
  t_atoms atoms{};
  char* title = nullptr;
  rvec* x = nullptr;
  rvec* v = nullptr;
  matrix box{};
  PbcType pbc_type = PbcType::Unset;

  GroConfiguration()
  {
    open_symtab(&this->symtab);
    init_t_atoms(&this->atoms, 0, FALSE);
  }
  ~GroConfiguration()
  {
    done_atom(&this->atoms);
    done_symtab(&this->symtab);
    sfree(this->x);
    sfree(this->v);
    sfree(this->title);
  }
  GroConfiguration(const GroConfiguration&) = delete;
  GroConfiguration& operator=(const GroConfiguration&) = delete;
};

std::string trimmed(const char* text)
{
  std::string out = text ? text : "";
  const auto first = out.find_first_not_of(' ');
  const auto last = out.find_last_not_of(' ');
  return first == std::string::npos ? std::string() : out.substr(first, last - first + 1);
}
} // namespace

AtomTable read_gro_topology(const std::string& path)
{
  detail::require_readable_file(path);
  // GROMACS' reader crashes on some malformed files (no atoms and a bad box: a null
  // dereference) and ends the process on others: the first frame, which it reads, is checked
  // first.
  const detail::FrameIndex frames = detail::index_gro(path, 1);
  if (frames.offsets.empty())
  {
    throw FileError(
      path + ": " +
      (frames.incomplete_tail.empty() ? std::string("no complete frame") : frames.incomplete_tail));
  }
  detail::install_gromacs_error_handler();
  GroConfiguration gro;
  try
  {
    readConfAndAtoms(path.c_str(), &gro.symtab, &gro.title, &gro.atoms, &gro.pbc_type, &gro.x,
                     &gro.v, gro.box);
  }
  catch (const FileError& e)
  {
    throw FileError(path + ": " + e.what());
  }
  const t_atoms& atoms = gro.atoms;
  if (atoms.nr <= 0)
  {
    throw FileError(path + ": the file contains no atoms");
  }
  constexpr float angstrom_per_nm = 10.0f;
  AtomTable table;
  for (int i = 0; i < atoms.nr; ++i)
  {
    const float px = gro.x[i][0] * angstrom_per_nm;
    const float py = gro.x[i][1] * angstrom_per_nm;
    const float pz = gro.x[i][2] * angstrom_per_nm;
    if (!std::isfinite(px) || !std::isfinite(py) || !std::isfinite(pz))
    {
      throw InvalidInput(path + ": atom " + std::to_string(i + 1) + " has a non-finite coordinate");
    }
    table.append_atom(trimmed(*atoms.atomname[i]), px, py, pz);
    const t_resinfo& residue = atoms.resinfo[atoms.atom[i].resind];
    table.residue_names.back() = trimmed(*residue.name);
    table.residue_numbers.back() = residue.nr;
    table.serials.back() = i + 1;
    table.atomic_numbers.back() =
      std::uint8_t(guess_atomic_number(table.atom_names.back(), table.residue_names.back()));
  }
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      table.box.vectors[std::size_t(r)][std::size_t(c)] = double(gro.box[r][c]) * 10.0;
    }
  }
  return table;
}

} // namespace mesolens
