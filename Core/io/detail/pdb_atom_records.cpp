// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/detail/pdb_atom_records.h"

#include "mesolens/common/errors.h"

#include <gemmi/elem.hpp>
#include <gemmi/pdb.hpp>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <unordered_map>

namespace mesolens {
namespace detail {

namespace {

using gemmi::pdb_impl::is_record_type;
using gemmi::pdb_impl::is_record_type3;
using gemmi::pdb_impl::read_charge;
using gemmi::pdb_impl::read_double;
using gemmi::pdb_impl::read_int;
using gemmi::pdb_impl::read_res_id;
using gemmi::pdb_impl::read_string;

/// gemmi reads each line into a buffer of at most 120 characters, newline included, with NUL
/// after it; its field readers rely on that NUL where a record is short.
constexpr std::size_t max_record = 120;
constexpr std::size_t padding = 8;
constexpr std::size_t none = static_cast<std::size_t>(-1);

/// Copies a line as gemmi does, with `nuls` NUL characters after it; returns gemmi's length of
/// it. gemmi reuses one buffer and writes one NUL: a field read past that (the number of a short
/// "MODEL 1" record) sees the end of an earlier, longer line, and its file reads that way.
std::size_t copy_record(const char* line, const char* end, char* out, std::size_t nuls)
{
  const std::size_t available = std::min<std::size_t>(std::size_t(end - line), max_record);
  const auto* newline = static_cast<const char*>(std::memchr(line, '\n', available));
  const std::size_t length = newline ? std::size_t(newline - line) + 1 : available;
  std::memcpy(out, line, length);
  std::memset(out + length, 0, nuls);
  return length;
}

struct ResidueEntry
{
  gemmi::ResidueId id;
  char het_flag = 'A';   ///< 'H' for a residue whose first record is HETATM
  std::size_t chain = 0; ///< index into ModelRecords::chains
  std::size_t atoms = 0;
};

struct AtomRecord
{
  const char* line;
  std::size_t residue; ///< index into ModelRecords::residues
  std::size_t ordinal; ///< 0-based among the file's ATOM/HETATM records
  std::int8_t charge;
};

struct ModelRecords
{
  std::string name;
  std::vector<std::string> chains;
  std::vector<ResidueEntry> residues; ///< in table order: by chain, then first appearance
  std::vector<AtomRecord> records;    ///< in file order
};

/// A fixed-width decimal field as gemmi's read_double reads it. Fields such as "%8.3f" and
/// "%6.2f" writes take a short path: blanks, a sign, at most 15 digits around one point, blanks;
/// their value is the digits as an integer divided by a power of ten, which is exact before one
/// correctly rounded division, so it equals what the general parser returns.
double read_decimal_field(const char* field, int width)
{
  static constexpr double powers_of_ten[] = { 1e0, 1e1, 1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                              1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15 };
  int i = 0;
  while (i < width && field[i] == ' ')
  {
    ++i;
  }
  const bool negative = i < width && field[i] == '-';
  i += negative ? 1 : 0;
  std::int64_t digits = 0;
  int count = 0;
  int before_point = -1; // digits before the point, once it is read
  for (; i < width; ++i)
  {
    const char c = field[i];
    if (c >= '0' && c <= '9')
    {
      digits = digits * 10 + (c - '0');
      ++count;
    }
    else if (c == '.' && before_point < 0)
    {
      before_point = count;
    }
    else
    {
      break;
    }
  }
  while (i < width && field[i] == ' ')
  {
    ++i;
  }
  const int decimals = before_point < 0 ? 0 : count - before_point;
  // Anything else ("+1", ".5", "5.", "1e3", no blanks after) takes the general parser.
  if (i != width || count == 0 || count > 15 || before_point == 0 ||
      (before_point > 0 && decimals == 0))
  {
    return read_double(field, width);
  }
  const double magnitude = double(digits) / powers_of_ten[decimals];
  return negative ? -magnitude : magnitude;
}

gemmi::El element_of(const char* record, std::size_t length)
{
  const auto letter = [](char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0; };
  if (length > 76 && (letter(record[76]) || letter(record[77])))
  {
    return gemmi::find_element(record + 76);
  }
  // As gemmi: "HXXX" names are hydrogens; "1HB " and "1C4A" (old and MD names) and "C210" take
  // the letter beside the digit.
  if (gemmi::alpha_up(record[12]) == 'H' && record[15] != ' ')
  {
    return gemmi::El::H;
  }
  if (gemmi::is_digit(record[12]))
  {
    return gemmi::impl::find_single_letter_element(record[13]);
  }
  if (gemmi::is_digit(record[13]))
  {
    return gemmi::impl::find_single_letter_element(record[12]);
  }
  return gemmi::find_element(record + 12);
}

/// Fills atom `i` of `table` from its record.
void fill_atom(const ModelRecords& model, const AtomRecord& record, const char* end,
               const PdbTextScan& scan, std::size_t i, AtomTable& table)
{
  char text[max_record + padding];
  const std::size_t length = copy_record(record.line, end, text, padding);
  const ResidueEntry& residue = model.residues[record.residue];
  const PdbAtomFields fields =
    record.ordinal < scan.atoms.size() ? scan.atoms[record.ordinal] : PdbAtomFields{};
  table.atom_names[i] = read_string(text + 12, 4);
  table.positions[3 * i] = float(read_decimal_field(text + 30, 8));
  table.positions[3 * i + 1] = float(read_decimal_field(text + 38, 8));
  table.positions[3 * i + 2] = float(read_decimal_field(text + 46, 8));
  const gemmi::El element = element_of(text, length);
  table.atomic_numbers[i] =
    static_cast<std::uint8_t>(element == gemmi::El::D ? gemmi::El::H : element);
  std::string& residue_name = table.residue_names[i];
  residue_name = residue.id.name;
  if (fields.residue_name_end != ' ')
  {
    residue_name += fields.residue_name_end;
  }
  const gemmi::SeqId& seqid = residue.id.seqid;
  table.residue_numbers[i] = fields.residue_number_read ? fields.residue_number
    : seqid.num.has_value()                             ? int(seqid.num)
                                                        : 0;
  table.insertion_codes[i] = seqid.icode == '\0' ? ' ' : seqid.icode;
  table.chain_ids[i] = model.chains[residue.chain];
  table.alt_locs[i] = text[16] == '\0' ? ' ' : text[16];
  table.occupancies[i] = length > 58 ? float(read_decimal_field(text + 54, 6)) : 1.0f;
  table.b_factors[i] = length > 64 ? float(read_decimal_field(text + 60, 6)) : 20.0f;
  table.is_hetero[i] = residue.het_flag == 'H' ? 1 : 0;
  table.serials[i] = fields.serial;
  table.formal_charges[i] = record.charge;
}

/// The table and residue layout of one model: residues in their order, each residue's records
/// in file order.
PdbModelAtoms build_model(const ModelRecords& model, const char* end, const PdbTextScan& scan,
                          const ParallelFor& parallel_for)
{
  PdbModelAtoms atoms;
  std::vector<std::size_t> first_atom(model.residues.size() + 1, 0);
  for (std::size_t r = 0; r < model.residues.size(); ++r)
  {
    first_atom[r + 1] = first_atom[r] + model.residues[r].atoms;
    const ResidueEntry& residue = model.residues[r];
    if (atoms.chains.empty() || model.residues[r - 1].chain != residue.chain)
    {
      atoms.chains.push_back({ model.chains[residue.chain], {} });
    }
    atoms.chains.back().residues.push_back(
      { residue.id.seqid, residue.id.name, residue.id.segment, first_atom[r], first_atom[r + 1] });
  }
  std::vector<std::size_t> order(model.records.size());
  std::vector<std::size_t> next_slot(first_atom.begin(), first_atom.end() - 1);
  for (std::size_t k = 0; k < model.records.size(); ++k)
  {
    order[next_slot[model.records[k].residue]++] = k;
  }
  atoms.table.resize(model.records.size());
  run_parallel(parallel_for, order.size(), [&](std::size_t begin, std::size_t stop) {
    for (std::size_t i = begin; i < stop; ++i)
    {
      fill_atom(model, model.records[order[i]], end, scan, i, atoms.table);
    }
  });
  return atoms;
}

} // namespace

PdbAtomsAndHeader read_pdb_atoms(const char* text, std::size_t size, const PdbTextScan& scan,
                                 const ParallelFor& parallel_for, const std::string& path)
{
  PdbAtomsAndHeader result;
  std::vector<ModelRecords> models;
  std::size_t model = none;   // the open model (gemmi: after MODEL or an atom, until ENDMDL)
  bool chain_open = false;    // gemmi's chain: set by an atom, reset by MODEL and ENDMDL
  std::size_t residue = none; // the residue of the last atom, within the open chain
  std::unordered_map<gemmi::ResidueId, std::size_t> residues_of_chain;
  bool last_atom_has_anisou = false;
  std::size_t ordinal = 0;
  std::size_t line_number = 0;
  char record[max_record + padding] = {};
  const char* const end = text + size;
  for (const char* line = text; line < end;)
  {
    const auto* newline =
      static_cast<const char*>(std::memchr(line, '\n', std::size_t(end - line)));
    const char* next = newline ? newline + 1 : end;
    ++line_number;
    const std::size_t length = copy_record(line, end, record, 1);
    const auto refuse = [&](const std::string& message) {
      throw FileError(path + ": Problem in line " + std::to_string(line_number) + ": " + message);
    };
    if (is_record_type(record, "ATOM") || is_record_type(record, "HETATM"))
    {
      const std::size_t this_ordinal = ordinal++;
      if (length < 55)
      {
        refuse("The line is too short to be correct:\n" + std::string(record));
      }
      std::string chain_name = read_string(record + 20, 2);
      gemmi::ResidueId id = read_res_id(record + 22, record + 17);
      if (!chain_open || chain_name != models[model].chains.back())
      {
        if (model == none)
        {
          // Without MODEL records each ENDMDL ends a model (MD frames) and the next is numbered.
          std::string name = std::to_string(models.size() + 1);
          if (std::any_of(models.begin(), models.end(),
                          [&](const ModelRecords& m) { return m.name == name; }))
          {
            refuse("ATOM/HETATM between models");
          }
          models.push_back({ std::move(name), {}, {}, {} });
          model = models.size() - 1;
        }
        models[model].chains.push_back(std::move(chain_name));
        chain_open = true;
        residues_of_chain.clear();
        residue = none;
      }
      if (length > 72)
      {
        id.segment = read_string(record + 72, 4);
      }
      ModelRecords& current = models[model];
      if (residue == none || !current.residues[residue].id.matches(id))
      {
        const auto found = residues_of_chain.find(id);
        if (found == residues_of_chain.end())
        {
          residue = current.residues.size();
          residues_of_chain.emplace(id, residue);
          current.residues.push_back(
            { std::move(id), gemmi::alpha_up(record[0]), current.chains.size() - 1, 0 });
        }
        else
        {
          residue = found->second;
        }
      }
      ++current.residues[residue].atoms;
      const std::int8_t charge = length > 78 ? read_charge(record[78], record[79]) : 0;
      current.records.push_back({ line, residue, this_ordinal, charge });
      last_atom_has_anisou = false;
    }
    else if (is_record_type(record, "ANISOU"))
    {
      // Not kept, but checked as gemmi checks it.
      if (model == none || !chain_open || residue == none)
      {
        refuse("ANISOU record not directly after ATOM/HETATM.");
      }
      if (last_atom_has_anisou)
      {
        refuse("Duplicated ANISOU record or not directly after ATOM/HETATM.");
      }
      last_atom_has_anisou = read_int(record + 28, 7) * 1e-4f != 0;
    }
    else if (is_record_type(record, "MODEL"))
    {
      if (model != none && chain_open)
      {
        refuse("MODEL without ENDMDL?");
      }
      std::string name = std::to_string(read_int(record + 10, 4));
      const auto found = std::find_if(models.begin(), models.end(),
                                      [&](const ModelRecords& m) { return m.name == name; });
      model = std::size_t(found - models.begin());
      if (found == models.end())
      {
        models.push_back({ name, {}, {}, {} });
      }
      else if (!found->chains.empty())
      {
        refuse("duplicate MODEL number: " + name);
      }
      chain_open = false;
    }
    else if (is_record_type(record, "ENDMDL"))
    {
      model = none;
      chain_open = false;
    }
    else if (is_record_type3(record, "TER"))
    {
      // Only marks entity types in gemmi, which MesoLens does not read from PDB files.
    }
    else if (is_record_type3(record, "END"))
    {
      break;
    }
    else if (is_record_type(record, "REMARK"))
    {
      const std::size_t text_length = std::size_t((newline ? newline : end) - line);
      result.remarks.push_back({ line_number, std::string_view(line, text_length) });
    }
    else if (model == none || !(is_record_type(record, "data") || is_record_type(record, "{\"da")))
    {
      // gemmi takes "data_" before any model for an mmCIF file, and ignores it after.
      result.header.append(line, std::size_t(next - line));
    }
    line = next;
  }
  result.models.reserve(models.size());
  for (const ModelRecords& records : models)
  {
    result.models.push_back(build_model(records, end, scan, parallel_for));
  }
  return result;
}

} // namespace detail
} // namespace mesolens
