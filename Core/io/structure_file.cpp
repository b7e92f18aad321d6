// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesolens/io/structure_file.h"

#include "io/detail/assembly_records.h"
#include "io/detail/file_checks.h"
#include "io/detail/pdb_atom_records.h"
#include "io/detail/pdb_text_scan.h"
#include "mesolens/molecules/bond_consensus.h"
#include "mesolens/common/errors.h"
#include "mesolens/molecules/molecule_assignment.h"

#include <gemmi/cif.hpp>
#include <gemmi/gz.hpp>
#include <gemmi/mmcif.hpp>
#include <gemmi/mmread.hpp>
#include <gemmi/pdb.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <unordered_map>

namespace mesolens {

namespace {

bool ends_with(const std::string& text, const std::string& suffix)
{
  return text.size() >= suffix.size() &&
    std::equal(suffix.rbegin(), suffix.rend(), text.rbegin(),
               [](char a, char b) { return std::tolower(a) == std::tolower(b); });
}

SecondaryStructure helix_kind(gemmi::Helix::HelixClass helix_class)
{
  switch (helix_class)
  {
    case gemmi::Helix::RAlpha:
    case gemmi::Helix::UnknownHelix:
      return SecondaryStructure::AlphaHelix;
    case gemmi::Helix::RPi:
      return SecondaryStructure::PiHelix;
    case gemmi::Helix::R310:
      return SecondaryStructure::Helix310;
    default:
      return SecondaryStructure::OtherHelix;
  }
}

using detail::ChainResidues;
using detail::ResidueRange;

/// Finds the residues of HELIX/SHEET spans: per chain, the position of each residue number.
class ResidueLocator
{
public:
  explicit ResidueLocator(const std::vector<ChainResidues>& chains)
    : Chains(chains)
  {
    for (std::size_t c = 0; c < chains.size(); ++c)
    {
      auto& positions = this->Positions[chains[c].name];
      for (std::size_t r = 0; r < chains[c].residues.size(); ++r)
      {
        const gemmi::SeqId& id = chains[c].residues[r].seqid;
        // The first residue of a number wins (microheterogeneity repeats numbers).
        positions.emplace(key(id), std::make_pair(c, r));
      }
    }
  }

  /// Marks residues from `start` to `end` (inclusive, in chain order).
  void mark(AtomTable& table, const gemmi::AtomAddress& start, const gemmi::AtomAddress& end,
            SecondaryStructure kind, int span_id) const
  {
    const auto chain = this->Positions.find(start.chain_name);
    if (chain == this->Positions.end())
    {
      return;
    }
    const auto first = chain->second.find(key(start.res_id.seqid));
    const auto last = chain->second.find(key(end.res_id.seqid));
    if (first == chain->second.end() || last == chain->second.end() ||
        first->second.first != last->second.first)
    {
      return;
    }
    const ChainResidues& residues = this->Chains[first->second.first];
    for (std::size_t r = first->second.second; r <= last->second.second; ++r)
    {
      for (std::size_t i = residues.residues[r].begin; i < residues.residues[r].end; ++i)
      {
        table.secondary_structure[i] = static_cast<std::uint8_t>(kind);
        table.secondary_structure_ids[i] = span_id;
      }
    }
  }

private:
  static std::int64_t key(const gemmi::SeqId& id)
  {
    const int number = id.num.has_value() ? int(id.num) : 0;
    return std::int64_t(number) * 256 + static_cast<unsigned char>(id.icode);
  }
  const std::vector<ChainResidues>& Chains;
  std::unordered_map<std::string,
                     std::unordered_map<std::int64_t, std::pair<std::size_t, std::size_t>>>
    Positions;
};

/// Alternate-location mask: per residue the conformer with the highest summed occupancy; per
/// atom name, that conformer's atom, or the best atom of the group when the conformer lacks it.
void mark_alternate_locations(const AtomTable& table, const ResidueRange& range,
                              std::vector<bool>& keep)
{
  if (std::all_of(table.alt_locs.begin() + long(range.begin),
                  table.alt_locs.begin() + long(range.end), [](char c) { return c == ' '; }))
  {
    return;
  }
  std::map<char, double> occupancy_by_conformer;
  for (std::size_t i = range.begin; i < range.end; ++i)
  {
    if (table.alt_locs[i] != ' ')
    {
      occupancy_by_conformer[table.alt_locs[i]] += table.occupancies[i];
    }
  }
  if (occupancy_by_conformer.empty())
  {
    return;
  }
  char chosen = occupancy_by_conformer.begin()->first;
  for (const auto& entry : occupancy_by_conformer)
  {
    if (entry.second > occupancy_by_conformer[chosen] + 1e-6)
    {
      chosen = entry.first;
    }
  }
  std::map<std::string, std::vector<std::size_t>> groups;
  for (std::size_t i = range.begin; i < range.end; ++i)
  {
    if (table.alt_locs[i] != ' ')
    {
      groups[table.atom_names[i]].push_back(i);
    }
  }
  for (const auto& group : groups)
  {
    std::size_t best = group.second.front();
    for (const std::size_t i : group.second)
    {
      keep[i] = false;
      if (table.alt_locs[i] == chosen)
      {
        best = i;
      }
    }
    if (table.alt_locs[best] != chosen)
    {
      for (const std::size_t i : group.second)
      {
        best = table.occupancies[i] > table.occupancies[best] ? i : best;
      }
    }
    keep[best] = true;
  }
}

/// Converts one model of an mmCIF file; fills `chains` with the residue layout. `label_asym`:
/// the residues' subchains are mmCIF label_asym_ids.
AtomTable convert_model(const gemmi::Model& model, std::vector<ChainResidues>& chains,
                        bool label_asym)
{
  AtomTable table;
  std::size_t atom_count = 0;
  for (const gemmi::Chain& chain : model.chains)
  {
    for (const gemmi::Residue& residue : chain.residues)
    {
      atom_count += residue.atoms.size();
    }
  }
  table.reserve(atom_count);
  for (const gemmi::Chain& chain : model.chains)
  {
    chains.push_back({ chain.name, {} });
    for (const gemmi::Residue& residue : chain.residues)
    {
      const std::size_t begin = table.size();
      for (const gemmi::Atom& atom : residue.atoms)
      {
        table.append_atom(atom.name, float(atom.pos.x), float(atom.pos.y), float(atom.pos.z));
        std::uint8_t z = static_cast<std::uint8_t>(atom.element.elem);
        if (atom.element.elem == gemmi::El::D)
        {
          z = 1;
        }
        table.atomic_numbers.back() = z;
        table.residue_names.back() = residue.name;
        table.residue_numbers.back() = residue.seqid.num.has_value() ? int(residue.seqid.num) : 0;
        table.insertion_codes.back() = residue.seqid.icode == '\0' ? ' ' : residue.seqid.icode;
        table.chain_ids.back() = chain.name;
        if (label_asym)
        {
          table.label_asym_ids.back() = residue.subchain;
        }
        table.alt_locs.back() = atom.altloc == '\0' ? ' ' : atom.altloc;
        table.occupancies.back() = atom.occ;
        table.b_factors.back() = atom.b_iso;
        table.is_hetero.back() = residue.het_flag == 'H' ? 1 : 0;
        table.serials.back() = atom.serial;
        table.formal_charges.back() = atom.charge;
      }
      chains.back().residues.push_back(
        { residue.seqid, residue.name, residue.segment, begin, table.size() });
    }
  }
  return table;
}

/// Table index of each atom serial (the first atom holding it). Files list serials in rising
/// order, so that case searches the serials themselves; others get a sorted copy.
class SerialIndex
{
public:
  static constexpr std::size_t none = std::numeric_limits<std::size_t>::max();

  explicit SerialIndex(const std::vector<int>& serials)
    : Serials(serials)
  {
    if (std::adjacent_find(serials.begin(), serials.end(), std::greater_equal<int>()) ==
        serials.end())
    {
      return;
    }
    this->Sorted.reserve(serials.size());
    for (std::size_t i = 0; i < serials.size(); ++i)
    {
      this->Sorted.emplace_back(serials[i], i);
    }
    std::stable_sort(this->Sorted.begin(), this->Sorted.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
  }

  std::size_t find(int serial) const
  {
    if (this->Sorted.empty())
    {
      const auto at = std::lower_bound(this->Serials.begin(), this->Serials.end(), serial);
      return at != this->Serials.end() && *at == serial ? std::size_t(at - this->Serials.begin())
                                                        : none;
    }
    const auto at = std::lower_bound(
      this->Sorted.begin(), this->Sorted.end(), serial,
      [](const std::pair<int, std::size_t>& entry, int value) { return entry.first < value; });
    return at != this->Sorted.end() && at->first == serial ? at->second : none;
  }

private:
  const std::vector<int>& Serials;
  std::vector<std::pair<int, std::size_t>> Sorted;
};

/// CONECT records and covalent and disulfide links as bonds; warnings for what the text pass
/// found.
std::vector<Bond> explicit_bonds(const std::vector<gemmi::Connection>& connections,
                                 const std::vector<ChainResidues>& chains, const AtomTable& table,
                                 const detail::PdbTextScan& pdb, std::vector<std::string>& warnings)
{
  std::vector<Bond> bonds;
  auto add = [&bonds](std::size_t a, std::size_t b) {
    if (a != b)
    {
      bonds.push_back({ std::uint32_t(std::min(a, b)), std::uint32_t(std::max(a, b)) });
    }
  };
  if (!pdb.conect_pairs.empty())
  {
    const SerialIndex by_serial(table.serials);
    std::size_t unresolved = 0;
    for (const auto& pair : pdb.conect_pairs)
    {
      const std::size_t a = by_serial.find(pair.first);
      const std::size_t b = by_serial.find(pair.second);
      if (a == SerialIndex::none || b == SerialIndex::none)
      {
        ++unresolved;
        continue;
      }
      add(a, b);
    }
    if (unresolved > 0)
    {
      warnings.push_back(
        std::to_string(unresolved) +
        " CONECT entries name atom serials that are not in the file; they were ignored");
    }
  }
  if (pdb.legacy_columns > 0)
  {
    warnings.push_back(
      std::to_string(pdb.legacy_columns) +
      " atom records carry non-standard text in columns 77-80 (pre-remediation PDB format); "
      "their elements were inferred from the atom names");
  }
  if (pdb.unreadable_conect_fields > 0)
  {
    warnings.push_back(std::to_string(pdb.unreadable_conect_fields) +
                       " CONECT fields are not numbers (e.g. ***** serials); they were ignored");
  }
  if (pdb.run_together_conect_records > 0)
  {
    warnings.push_back(std::to_string(pdb.run_together_conect_records) +
                       " CONECT records have serials over 99999 written in full, running into "
                       "each other; they were ignored");
  }
  if (pdb.shifted_records > 0)
  {
    warnings.push_back(std::to_string(pdb.shifted_records) +
                       " atom records have a serial over 99999 or a residue number over 9999 "
                       "written in full, which pushes the later fields right; they were read from "
                       "where their coordinates are");
  }
  if (pdb.continued_serials > 0)
  {
    warnings.push_back(
      "atom serials restart after 99999 (written modulo 100000, as GROMACS does); " +
      std::to_string(pdb.continued_serials) + " atom records were numbered on from 100000");
  }
  if (pdb.continued_residue_numbers > 0)
  {
    warnings.push_back(
      "residue numbers restart after 9999 (written modulo 10000, as GROMACS does); " +
      std::to_string(pdb.continued_residue_numbers) + " atom records were numbered on from 10000");
  }
  for (const gemmi::Connection& connection : connections)
  {
    if (connection.type == gemmi::Connection::Hydrog ||
        connection.type == gemmi::Connection::MetalC)
    {
      continue;
    }
    const ResidueRange* residue_a = detail::find_linked_residue(connection.partner1, chains, true);
    const ResidueRange* residue_b = detail::find_linked_residue(connection.partner2, chains, true);
    if (!residue_a || !residue_b)
    {
      continue;
    }
    const std::size_t a = detail::find_linked_atom(connection.partner1, *residue_a, table);
    const std::size_t b = detail::find_linked_atom(connection.partner2, *residue_b, table);
    if (a != detail::no_atom && b != detail::no_atom)
    {
      add(a, b);
    }
  }
  std::sort(bonds.begin(), bonds.end());
  bonds.erase(std::unique(bonds.begin(), bonds.end()), bonds.end());
  return bonds;
}

void check_finite(const AtomTable& table, const std::string& path)
{
  for (std::size_t i = 0; i < table.size(); ++i)
  {
    for (int d = 0; d < 3; ++d)
    {
      if (!std::isfinite(table.positions[3 * i + std::size_t(d)]))
      {
        throw InvalidInput(path + ": atom " + std::to_string(table.serials[i]) + " (" +
                           table.atom_names[i] + " of " + table.residue_names[i] + " " +
                           std::to_string(table.residue_numbers[i]) +
                           ") has a non-finite coordinate");
      }
    }
  }
}

/// The PDB text as gemmi 0.5 can read it safely, or nothing when it already can:
/// - gemmi reads the reported distance (columns 74-78) of SSBOND and LINK records, and a LINKR
///   record's link id (columns 73-80), whenever a line, its newline included, is longer than 73
///   characters: past the end of a record cut before or inside those columns. PDB columns are
///   fixed and blank when absent, so these records (and CISPEP, read the same way) get blanks up
///   to column 80.
/// - gemmi reads DBREF2's ten-digit sequence numbers into int unchecked (signed overflow for
///   more than 2147483647). MesoLens keeps no database references, so DBREF2 records are left
///   out.
std::optional<std::string> pdb_text_for_gemmi(const char* text, std::size_t size)
{
  constexpr std::size_t record_width = 80;
  std::string padded;
  std::size_t copied = 0;
  bool changed = false;
  for (std::size_t start = 0; start < size;)
  {
    const char* end_of_line =
      static_cast<const char*>(std::memchr(text + start, '\n', size - start));
    std::size_t end = end_of_line ? std::size_t(end_of_line - text) : size;
    const std::size_t next = end_of_line ? end + 1 : size;
    if (end > start && text[end - 1] == '\r')
    {
      --end;
    }
    const std::size_t length = end - start;
    const auto starts_with = [&](const char* name) {
      const std::size_t name_length = std::strlen(name);
      if (length < name_length)
      {
        return false;
      }
      for (std::size_t i = 0; i < name_length; ++i)
      {
        if (std::toupper(static_cast<unsigned char>(text[start + i])) != name[i])
        {
          return false;
        }
      }
      return true;
    };
    // gemmi knows a record by its first four letters, in any case.
    if (length < record_width &&
        (starts_with("SSBO") || starts_with("LINK") || starts_with("CISP")))
    {
      padded.append(text + copied, end - copied);
      padded.append(record_width - length, ' ');
      copied = end;
      changed = true;
    }
    else if (starts_with("DBRE") && length > 5 && text[start + 5] == '2')
    {
      padded.append(text + copied, start - copied);
      copied = next;
      changed = true;
    }
    start = next;
  }
  if (!changed)
  {
    return std::nullopt;
  }
  padded.append(text + copied, size - copied);
  return padded;
}

/// Whether a CIF value starts with an integer (after blanks and a sign) beyond int's range.
bool starts_with_overflowing_int(const std::string& value)
{
  std::size_t i = value.find_first_not_of(" \t");
  if (i == std::string::npos)
  {
    return false;
  }
  if (value[i] == '-' || value[i] == '+')
  {
    ++i;
  }
  i = std::min(value.find_first_not_of('0', i), value.size()); // leading zeros
  std::int64_t magnitude = 0;
  for (; i < value.size() && value[i] >= '0' && value[i] <= '9'; ++i)
  {
    magnitude = 10 * magnitude + (value[i] - '0');
    if (magnitude > std::int64_t(std::numeric_limits<int>::max()))
    {
      return true;
    }
  }
  return false;
}

/// gemmi 0.5 reads mmCIF integers into int without checking for overflow (undefined behaviour,
/// and in practice wrong residue numbers and serials). Throws FileError naming the first
/// integer out of int's range in a category that gemmi's structure reads.
void refuse_overflowing_integers(const gemmi::cif::Document& document, const std::string& path)
{
  static const char* const read_categories[] = {
    "_atom_site.",
    "_atom_site_anisotrop.",
    "_struct_conf.",
    "_struct_sheet_range.",
    "_struct_sheet_order.",
    "_pdbx_struct_sheet_hbond.",
    "_struct_conn.",
    "_pdbx_struct_assembly.",
    "_pdbx_struct_assembly_gen.",
    "_pdbx_struct_assembly_prop.",
    "_pdbx_struct_oper_list.",
    "_pdbx_sifts_xref_db.",
    "_refine.",
    "_exptl.",
    "_exptl_crystal.",
    "_diffrn.",
    "_diffrn_detector.",
    "_diffrn_radiation.",
    "_diffrn_source.",
    "_reflns.",
    "_software.",
    "_struct_ncs_oper.",
    "_entity.",
    "_entity_poly.",
    "_entity_poly_seq.",
    "_struct_ref.",
    "_struct_ref_seq.",
    "_struct_asym.",
    "_struct_mon_prot_cis.",
  };
  const auto is_read = [](const std::string& tag) {
    for (const char* category : read_categories)
    {
      if (gemmi::istarts_with(tag, category))
      {
        return true;
      }
    }
    return false;
  };
  if (document.blocks.empty())
  {
    return;
  }
  for (const gemmi::cif::Item& item : document.blocks.front().items)
  {
    if (item.type == gemmi::cif::ItemType::Pair && is_read(item.pair[0]) &&
        starts_with_overflowing_int(item.pair[1]))
    {
      throw FileError(path + ": line " + std::to_string(item.line_number) + ": " + item.pair[0] +
                      " " + item.pair[1].substr(0, 32) + " is an integer beyond 2147483647");
    }
    if (item.type != gemmi::cif::ItemType::Loop)
    {
      continue;
    }
    const gemmi::cif::Loop& loop = item.loop;
    const std::size_t width = loop.tags.size();
    for (std::size_t column = 0; column < width; ++column)
    {
      if (!is_read(loop.tags[column]))
      {
        continue;
      }
      for (std::size_t v = column; v < loop.values.size(); v += width)
      {
        if (starts_with_overflowing_int(loop.values[v]))
        {
          throw FileError(
            path + ": " + loop.tags[column] + " in row " + std::to_string(v / width + 1) +
            " of its loop: " + loop.values[v].substr(0, 32) + " is an integer beyond 2147483647");
        }
      }
    }
  }
}

/// A control character other than tab, line ends, form feed and escape: below 0x09, or in
/// 0x0e-0x1f but not 0x1b. Written without branches, so that a loop over bytes vectorizes.
bool is_binary_byte(char c)
{
  const auto byte = static_cast<unsigned char>(c);
  return (byte < 0x09) | ((static_cast<unsigned char>(byte - 0x0e) < 0x12) & (byte != 0x1b));
}

/// Offset of the first byte that no text file holds (is_binary_byte), or `size`. The test runs
/// over every byte of every file read: blocks of a fixed size are tested whole, vectorized.
std::size_t first_binary_byte(const char* data, std::size_t size)
{
  constexpr std::size_t block = 64;
  std::size_t start = 0;
  for (; start + block <= size; start += block)
  {
    unsigned char any = 0;
    for (std::size_t i = 0; i < block; ++i)
    {
      any |= static_cast<unsigned char>(is_binary_byte(data[start + i]));
    }
    if (any)
    {
      break;
    }
  }
  for (std::size_t i = start; i < size; ++i)
  {
    if (is_binary_byte(data[i]))
    {
      return i;
    }
  }
  return size;
}

/// Parses the file: an mmCIF file with gemmi; a PDB file's atoms into `pdb_models` and the
/// rest with gemmi. Reads the assemblies (with their warnings) on the way.
gemmi::Structure parse_file(const std::string& path, const ParallelFor& parallel_for,
                            detail::PdbTextScan& pdb,
                            std::vector<detail::PdbModelAtoms>& pdb_models,
                            std::vector<Assembly>& assemblies, std::vector<std::string>& warnings)
{
  detail::require_readable_file(path);
  try
  {
    gemmi::MaybeGzipped input(path);
    gemmi::CharArray buffer = gemmi::read_into_buffer(input);
    if (buffer.size() == 0)
    {
      throw FileError(path + ": the file is empty");
    }
    const std::size_t binary = first_binary_byte(buffer.data(), buffer.size());
    if (binary != buffer.size())
    {
      throw FileError(path + ": binary data at byte " + std::to_string(binary) +
                      "; not a PDB or mmCIF text file");
    }
    gemmi::CoorFormat format = gemmi::coor_format_from_ext(input.basepath());
    if (format == gemmi::CoorFormat::Unknown)
    {
      format = gemmi::coor_format_from_content(buffer.data(), buffer.data() + buffer.size());
    }
    if (format == gemmi::CoorFormat::Pdb)
    {
      pdb = detail::scan_pdb_text(buffer.data(), buffer.size(), path);
      detail::PdbAtomsAndHeader split =
        detail::read_pdb_atoms(buffer.data(), buffer.size(), pdb, parallel_for, path);
      assemblies = detail::read_pdb_assemblies(split.remarks, warnings);
      pdb_models = std::move(split.models);
      const std::string& header = split.header;
      const std::optional<std::string> padded = pdb_text_for_gemmi(header.data(), header.size());
      return padded ? gemmi::read_pdb_from_memory(padded->data(), padded->size(), path)
                    : gemmi::read_pdb_from_memory(header.data(), header.size(), path);
    }
    if (format == gemmi::CoorFormat::Mmcif)
    {
      gemmi::cif::Document document =
        gemmi::cif::read_memory(buffer.data(), buffer.size(), path.c_str());
      refuse_overflowing_integers(document, path);
      if (!document.blocks.empty())
      {
        assemblies = detail::read_mmcif_assemblies(document.blocks.front(), warnings);
      }
      return gemmi::make_structure(document);
    }
    throw FileError(path + ": neither a PDB nor an mmCIF file");
  }
  catch (const Error&)
  {
    throw;
  }
  catch (const std::exception& e)
  {
    throw FileError(path + ": " + e.what());
  }
}

std::vector<bool> selection_mask(const AtomTable& table, const std::vector<ChainResidues>& chains,
                                 const StructureReadParams& params)
{
  std::vector<bool> keep(table.size(), true);
  if (params.alt_locs == AltLocPolicy::HighestOccupancy)
  {
    for (const ChainResidues& chain : chains)
    {
      for (const ResidueRange& range : chain.residues)
      {
        mark_alternate_locations(table, range, keep);
      }
    }
  }
  for (std::size_t i = 0; i < table.size(); ++i)
  {
    if ((params.remove_waters && is_water_residue(table.residue_names[i])) ||
        (params.remove_hydrogens && table.atomic_numbers[i] == 1))
    {
      keep[i] = false;
    }
  }
  return keep;
}

} // namespace

bool build_connectivity(AtomTable& table, const std::vector<Bond>& explicit_bonds,
                        const StructureReadParams& params, bool elements_given)
{
  assign_residues(table);
  assign_molecules(table);
  BondPerceptionInput input;
  input.positions = table.positions;
  input.atomic_numbers = table.atomic_numbers.data();
  input.molecule_ids = table.molecule_ids.data();
  input.alt_locs = table.alt_locs.data();
  BondPerceptionParams bond_params = params.bonds;
  bond_params.coarse_grained = params.force_coarse_grained;
  std::vector<Bond> perceived;
  if (!bond_params.coarse_grained && (params.perceive_bonds || !elements_given))
  {
    bond_params.coarse_grained = false;
    perceived = perceive_bonds(input, bond_params, params.parallel_for);
    bond_params.coarse_grained = !elements_given && looks_coarse_grained(input, perceived);
  }
  if (bond_params.coarse_grained)
  {
    std::fill(table.atomic_numbers.begin(), table.atomic_numbers.end(), std::uint8_t(0));
    perceived.clear();
    if (params.perceive_bonds)
    {
      perceived = consensus_bonds(table, perceive_bonds(input, bond_params, params.parallel_for));
    }
  }
  if (!params.perceive_bonds)
  {
    perceived.clear();
  }
  table.bonds = merge_bonds(perceived, explicit_bonds);
  return bond_params.coarse_grained;
}

StructureFile read_structure(const std::string& path, const StructureReadParams& params,
                             const ProgressCallback& progress)
{
  auto report = [&progress](double fraction) {
    if (progress && !progress(fraction))
    {
      throw FileError("reading was aborted");
    }
  };
  detail::PdbTextScan pdb;
  std::vector<detail::PdbModelAtoms> pdb_models;
  StructureFile file;
  std::vector<std::string> assembly_warnings;
  const gemmi::Structure structure =
    parse_file(path, params.parallel_for, pdb, pdb_models, file.assemblies, assembly_warnings);
  const bool is_pdb = structure.input_format == gemmi::CoorFormat::Pdb;
  std::vector<gemmi::Connection> connections = structure.connections;
  if (is_pdb && !pdb_models.empty())
  {
    // gemmi completes SSBOND partners from the atoms, which it did not read here.
    for (gemmi::Connection& connection : connections)
    {
      if (connection.type == gemmi::Connection::Disulf)
      {
        detail::complete_disulfide_partner(connection.partner1, pdb_models.front().chains,
                                           pdb_models.front().table);
        detail::complete_disulfide_partner(connection.partner2, pdb_models.front().chains,
                                           pdb_models.front().table);
      }
    }
  }
  // mmCIF always names elements (type_symbol); a PDB file does when most records fill 77-78.
  const bool elements_given = !is_pdb || 2 * pdb.element_records > pdb.atoms.size();
  report(0.5);

  file.title = structure.get_info("_struct.title");
  bool emptied_by_selection = false; // a model whose atoms the params all removed
  const std::size_t model_count = is_pdb ? pdb_models.size() : structure.models.size();
  for (std::size_t m = 0; m < model_count; ++m)
  {
    std::vector<ChainResidues> chains;
    AtomTable table;
    if (is_pdb)
    {
      table = std::move(pdb_models[m].table);
      chains = std::move(pdb_models[m].chains);
    }
    else
    {
      table = convert_model(structure.models[m], chains,
                            structure.input_format == gemmi::CoorFormat::Mmcif);
    }
    if (table.size() == 0)
    {
      continue;
    }
    check_finite(table, path);
    if (m == 0)
    {
      detail::warn_missing_chains(file.assemblies, table, assembly_warnings);
    }
    int span_id = 0;
    if (!structure.helices.empty() || !structure.sheets.empty())
    {
      const ResidueLocator locator(chains);
      for (const gemmi::Helix& helix : structure.helices)
      {
        locator.mark(table, helix.start, helix.end, helix_kind(helix.pdb_helix_class), span_id++);
      }
      for (const gemmi::Sheet& sheet : structure.sheets)
      {
        for (const gemmi::Sheet::Strand& strand : sheet.strands)
        {
          locator.mark(table, strand.start, strand.end, SecondaryStructure::Strand, span_id++);
        }
      }
    }
    std::vector<std::string> warnings;
    table.bonds = explicit_bonds(connections, chains, table, pdb, warnings);
    if (m == 0)
    {
      file.warnings = warnings;
    }
    const std::vector<bool> keep = selection_mask(table, chains, params);
    if (std::find(keep.begin(), keep.end(), false) != keep.end())
    {
      table.filter(keep);
      if (table.size() == 0)
      {
        emptied_by_selection = true;
        continue; // nothing of this model is wanted
      }
    }
    const std::vector<Bond> kept_explicit = table.bonds;
    file.coarse_grained = build_connectivity(table, kept_explicit, params, elements_given);
    if (structure.cell.is_crystal())
    {
      table.box =
        PeriodicBox::from_cell(structure.cell.a, structure.cell.b, structure.cell.c,
                               structure.cell.alpha, structure.cell.beta, structure.cell.gamma);
    }
    file.models.push_back(std::move(table));
    report(0.5 + 0.5 * double(m + 1) / double(model_count));
  }
  if (file.models.empty() && emptied_by_selection)
  {
    throw InvalidInput(path + ": no atoms are left once " +
                       (params.remove_waters && params.remove_hydrogens
                          ? "waters and hydrogens are"
                          : (params.remove_waters ? "waters are" : "hydrogens are")) +
                       " removed");
  }
  if (file.models.empty())
  {
    throw FileError(path + ": the file contains no atoms");
  }
  file.warnings.insert(file.warnings.end(), assembly_warnings.begin(), assembly_warnings.end());
  return file;
}

} // namespace mesolens
