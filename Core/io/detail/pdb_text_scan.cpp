// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/detail/pdb_text_scan.h"

#include "mesolens/molecules/elements.h"
#include "mesolens/common/errors.h"

#include <gemmi/elem.hpp>
#include <gemmi/resinfo.hpp>

#include <algorithm>
#include <cctype>
#include <cstring>

namespace mesolens {
namespace detail {

namespace {

// 0-based columns of the standard ATOM/HETATM record.
constexpr std::size_t serial_column = 6;
constexpr std::size_t serial_width = 5;
constexpr std::size_t name_column = 11; // the blank before the atom name, then name to chain
constexpr std::size_t residue_name_column = 17;
constexpr std::size_t chain_column = 21;
constexpr std::size_t residue_number_column = 22;
constexpr std::size_t residue_number_width = 4;
constexpr std::size_t insertion_code_column = 26;
constexpr std::size_t coordinates_column = 30;
constexpr std::size_t coordinates_end = 54;
/// A 32-bit serial and residue number overflow their fields by at most 5 and 6 characters.
constexpr std::size_t max_shift = 11;

// Hybrid-36 (cci.lbl.gov/hybrid_36): after the largest decimal, A000 (A0000 for serials)
// follows, counting in base 36 through ZZZZ, then a000 through zzzz.
constexpr long pow36_3 = 36L * 36 * 36;
constexpr long pow36_4 = pow36_3 * 36;
constexpr int largest_serial_code = 100000 + int(26 * pow36_4) - 1; // ZZZZZ
constexpr int largest_residue_code = 10000 + int(26 * pow36_3) - 1; // ZZZZ

bool is_digit(char c)
{
  return c >= '0' && c <= '9';
}

bool is_charge_field(char a, char b)
{
  const auto sign = [](char c) { return c == '+' || c == '-'; };
  return (a == ' ' && b == ' ') || (is_digit(a) && sign(b)) || (sign(a) && is_digit(b)) ||
    (a == ' ' && is_digit(b)) || (is_digit(a) && b == ' ');
}

bool is_element_field(char a, char b)
{
  if (a == ' ' && b == ' ')
  {
    return true;
  }
  const char symbol[3] = { a, b, '\0' };
  return gemmi::find_element(symbol) != gemmi::El::X || (a == ' ' && b == 'X') ||
    (a == 'X' && b == ' ');
}

/// True when the fixed-width field holds one decimal number (blanks around it allowed), or
/// "nan"/"inf", which the finiteness check reports later with the atom's name.
bool is_number_field(const char* field, std::size_t width)
{
  std::size_t i = 0;
  while (i < width && field[i] == ' ')
  {
    ++i;
  }
  const std::size_t first = i;
  if (i < width && (field[i] == '-' || field[i] == '+'))
  {
    ++i;
  }
  std::size_t digits = 0;
  bool dot = false;
  for (; i < width && field[i] != ' '; ++i)
  {
    const char c = field[i];
    if (is_digit(c))
    {
      ++digits;
    }
    else if (c == '.' && !dot)
    {
      dot = true;
    }
    else if ((c == 'e' || c == 'E') && digits > 0 && i + 1 < width)
    {
      if (field[i + 1] == '-' || field[i + 1] == '+')
      {
        ++i;
      }
    }
    else
    {
      const std::string word(field + first, std::min<std::size_t>(width - first, 4));
      return word.rfind("nan", 0) == 0 || word.rfind("-nan", 0) == 0 || word.rfind("inf", 0) == 0 ||
        word.rfind("-inf", 0) == 0;
    }
  }
  while (i < width && field[i] == ' ')
  {
    ++i;
  }
  return digits > 0 && i == width;
}

/// A decimal integer filling the field, blanks around it allowed.
bool read_decimal(const char* field, std::size_t width, int& value)
{
  std::size_t i = 0;
  while (i < width && field[i] == ' ')
  {
    ++i;
  }
  const bool negative = i < width && field[i] == '-';
  if (negative || (i < width && field[i] == '+'))
  {
    ++i;
  }
  long number = 0;
  std::size_t digits = 0;
  for (; i < width && is_digit(field[i]); ++i, ++digits)
  {
    number = number * 10 + (field[i] - '0');
  }
  while (i < width && field[i] == ' ')
  {
    ++i;
  }
  if (digits == 0 || digits > 10 || i != width || number > 2147483647L)
  {
    return false;
  }
  value = int(negative ? -number : number);
  return true;
}

/// Reads a fixed-width hybrid-36 number: a decimal integer (blanks around it allowed) or, when
/// it fills the field and starts with a letter, base 36 continuing after the largest decimal
/// (upper case first, then lower case). False when the field holds neither.
bool read_hybrid36(const char* field, std::size_t width, int& value)
{
  if (read_decimal(field, width, value))
  {
    return true;
  }
  const bool upper = field[0] >= 'A' && field[0] <= 'Z';
  const bool lower = field[0] >= 'a' && field[0] <= 'z';
  if ((!upper && !lower) || (width != serial_width && width != residue_number_width))
  {
    return false;
  }
  long code = 0;
  for (std::size_t i = 0; i < width; ++i)
  {
    const char c = field[i];
    int digit = 0;
    if (is_digit(c))
    {
      digit = c - '0';
    }
    else if (upper && c >= 'A' && c <= 'Z')
    {
      digit = c - 'A' + 10;
    }
    else if (lower && c >= 'a' && c <= 'z')
    {
      digit = c - 'a' + 10;
    }
    else
    {
      return false;
    }
    code = code * 36 + digit;
  }
  const long power = width == serial_width ? pow36_4 : pow36_3;
  const long decimal_limit = width == serial_width ? 100000 : 10000;
  value = int(decimal_limit + code - 10 * power + (lower ? 26 * power : 0));
  return true;
}

/// Writes `value` right-justified in `width` characters as hybrid-36 writes it; callers keep it
/// within the decimal and upper-case range.
void write_hybrid36(int value, std::size_t width, char* field)
{
  const long decimal_limit = width == serial_width ? 100000 : 10000;
  if (value >= decimal_limit)
  {
    long code = value - decimal_limit + 10 * (width == serial_width ? pow36_4 : pow36_3);
    for (std::size_t i = width; i-- > 0; code /= 36)
    {
      const int digit = int(code % 36);
      field[i] = char(digit < 10 ? '0' + digit : 'A' + digit - 10);
    }
    return;
  }
  // Right-justified decimal, as "%*d" writes it (negative residue numbers included).
  long magnitude = value < 0 ? -long(value) : long(value);
  std::size_t i = width;
  do
  {
    field[--i] = char('0' + magnitude % 10);
    magnitude /= 10;
  } while (magnitude > 0 && i > 0);
  if (value < 0 && i > 0)
  {
    field[--i] = '-';
  }
  std::memset(field, ' ', i);
}

/// A "%8.3f" field: a number with its decimal point five characters in, where every PDB writer
/// puts it.
bool is_fixed_point_field(const char* field)
{
  return field[4] == '.' && is_number_field(field, 8);
}

bool has_coordinates_at(const char* line, std::size_t length, std::size_t column)
{
  return column + 24 <= length && is_fixed_point_field(line + column) &&
    is_fixed_point_field(line + column + 8) && is_fixed_point_field(line + column + 16);
}

/// Where the fields before the coordinates are: the serial and the residue number take more
/// than their 5 and 4 characters when a printf-based writer overflowed them.
struct AtomRecordLayout
{
  std::size_t serial_extra = 0;
  std::size_t residue_number_extra = 0;
  std::size_t shift() const
  {
    return serial_extra + residue_number_extra;
  }
};

/// The layout of a record whose coordinates sit `shift` columns right of standard: the serial
/// and the residue number together must be exactly that much wider than their fields (a wider
/// one fills its field with digits), and the three blanks before the coordinates must be there.
bool fit_shifted_layout(const char* line, std::size_t shift, AtomRecordLayout& layout)
{
  std::size_t serial_end = serial_column;
  while (serial_end < serial_column + serial_width + shift && is_digit(line[serial_end]))
  {
    ++serial_end;
  }
  layout.serial_extra =
    serial_end > serial_column + serial_width ? serial_end - serial_column - serial_width : 0;
  if ((layout.serial_extra > 0 && line[serial_end] != ' ') || layout.serial_extra > shift)
  {
    return false;
  }
  layout.residue_number_extra = shift - layout.serial_extra;
  const char* residue_number = line + residue_number_column + layout.serial_extra;
  const std::size_t width = residue_number_width + layout.residue_number_extra;
  int value = 0;
  // A number wider than its field fills it: no blanks around it.
  const bool overflowed = layout.residue_number_extra > 0;
  if (overflowed &&
      std::any_of(residue_number, residue_number + width, [](char c) { return c == ' '; }))
  {
    return false;
  }
  if (overflowed ? !read_decimal(residue_number, width, value)
                 : !read_hybrid36(residue_number, width, value))
  {
    return false;
  }
  const char* gap = line + insertion_code_column + shift + 1;
  return gap[0] == ' ' && gap[1] == ' ' && gap[2] == ' ';
}

/// Pre-remediation files (1HPV) keep the entry id and a serial in columns 73-80. Blanks columns
/// 77-80 of such a record, so gemmi infers the element from the atom name instead of failing
/// on the "charge".
bool blank_legacy_columns(char* line, std::size_t length)
{
  if (length < 77)
  {
    return false;
  }
  const char element_a = line[76];
  const char element_b = length > 77 ? line[77] : ' ';
  const char charge_a = length > 78 ? line[78] : ' ';
  const char charge_b = length > 79 ? line[79] : ' ';
  if (is_element_field(element_a, element_b) && is_charge_field(charge_a, charge_b))
  {
    return false;
  }
  for (std::size_t column = 76; column < std::min<std::size_t>(length, 80); ++column)
  {
    line[column] = ' ';
  }
  return true;
}

/// gemmi's test for ATOM/HETATM records: the first four letters, any case.
bool is_atom_record(const char* line, std::size_t length)
{
  if (length < 4)
  {
    return false;
  }
  char word[4];
  for (int i = 0; i < 4; ++i)
  {
    // std::toupper in the "C" locale, without a call per character: this runs on every line.
    const char c = line[i];
    word[i] = c >= 'a' && c <= 'z' ? char(c - 'a' + 'A') : c;
  }
  return std::memcmp(word, "ATOM", 4) == 0 || std::memcmp(word, "HETA", 4) == 0;
}

bool starts_with(const char* line, std::size_t length, const char* record)
{
  const std::size_t size = std::strlen(record);
  return length >= size && std::memcmp(line, record, size) == 0;
}

/// Continues numbers that a writer put down modulo 10^digits (GROMACS: serial % 100000,
/// resSeq % 10000): a drop by more than half the modulus from the previous record is taken as
/// the restart, never as a real jump back.
class NumberContinuation
{
public:
  explicit NumberContinuation(int modulus)
    : Modulus(modulus)
  {
  }

  /// The true number of a value read from the fixed field; `may_restart` false when this record
  /// cannot continue the previous one's count.
  int continue_from_field(int value, bool may_restart)
  {
    int number = value + this->Offset;
    while (may_restart && value >= 0 && this->HavePrevious &&
           number < this->Previous - this->Modulus / 2)
    {
      this->Offset += this->Modulus;
      number += this->Modulus;
    }
    this->remember(number);
    return number;
  }

  /// A number that did not come modulo the field (written in full or in hybrid-36).
  void remember(int number)
  {
    this->Previous = number;
    this->HavePrevious = true;
  }

  bool continued() const
  {
    return this->Offset != 0;
  }

  void reset()
  {
    this->Offset = 0;
    this->HavePrevious = false;
  }

private:
  int Modulus;
  int Offset = 0;
  int Previous = 0;
  bool HavePrevious = false;
};

/// Reads and rewrites the ATOM/HETATM records of one file, in order.
class AtomRecordScanner
{
public:
  AtomRecordScanner(PdbTextScan& scan, const std::string& path)
    : Scan(scan)
    , Path(path)
  {
  }

  void new_model()
  {
    this->Serials.reset();
    this->ResidueNumbers.reset();
    this->AfterTer = false;
  }

  void ter()
  {
    this->AfterTer = true;
  }

  void scan(char* line, std::size_t length, std::size_t line_number)
  {
    const AtomRecordLayout layout = this->find_layout(line, length, line_number);
    PdbAtomFields fields;
    this->read_serial(line, layout, fields);
    const bool charmm_residue_number = this->read_residue_number(line, layout, fields);

    const std::size_t shift = layout.shift();
    if (shift > 0)
    {
      // Back to the standard columns: the atom name to chain fields, which only an overflowing
      // serial moved, then everything from the insertion code on; blanks fill the end.
      std::memmove(line + name_column, line + name_column + layout.serial_extra,
                   residue_number_column - name_column);
      const std::size_t tail = insertion_code_column;
      std::memmove(line + tail, line + tail + shift, length - tail - shift);
      std::memset(line + length - shift, ' ', shift);
      ++this->Scan.shifted_records;
    }
    if (charmm_residue_number)
    {
      line[insertion_code_column] = ' ';
    }
    if (fields.residue_number_read)
    {
      write_hybrid36(residue_number_key(fields.residue_number), residue_number_width,
                     line + residue_number_column);
    }
    const std::size_t ordinal = this->Scan.atoms.size() + 1;
    if (ordinal > std::size_t(largest_serial_code))
    {
      throw FileError(this->Path + ": more than " + std::to_string(largest_serial_code) +
                      " atom records, more than the PDB format can number; use mmCIF");
    }
    // Nothing reads this serial now (read_pdb_atoms keeps the records' order), but a short
    // "MODEL 1" record's number is read past its end, as gemmi reads it, from an earlier line's
    // columns 11-14: rewriting them as before keeps such files' models as they were.
    write_hybrid36(int(ordinal), serial_width, line + serial_column);
    this->read_residue_name_end(line, fields);
    this->Chain = line[chain_column];
    this->AfterTer = false;

    if (blank_legacy_columns(line, length))
    {
      ++this->Scan.legacy_columns;
    }
    if (length > 77 &&
        (std::isalpha(static_cast<unsigned char>(line[76])) ||
         std::isalpha(static_cast<unsigned char>(line[77]))))
    {
      ++this->Scan.element_records;
    }
    this->Scan.atoms.push_back(fields);
  }

  /// Decides the records whose columns 18-21 and 21-22 both read as names: a three-letter
  /// residue with a two-letter chain (gemmi writes those) or a four-letter residue with a
  /// one-letter chain (GROMACS, CHARMM). A standard residue or water read the first way in any
  /// of them means the file uses two-letter chains.
  void finish()
  {
    if (this->TwoLetterChains)
    {
      return;
    }
    for (const auto& candidate : this->FourLetterCandidates)
    {
      char* name_end = candidate.second + residue_name_column + 3;
      this->Scan.atoms[candidate.first].residue_name_end = *name_end;
      *name_end = ' ';
    }
  }

private:
  AtomRecordLayout find_layout(const char* line, std::size_t length, std::size_t line_number) const
  {
    // Built only for an error: this runs once per atom record.
    const auto where = [&] { return this->Path + ": line " + std::to_string(line_number); };
    if (length < coordinates_end)
    {
      throw FileError(where() + " is an " + std::string(line, std::min<std::size_t>(length, 6)) +
                      " record of " + std::to_string(length) +
                      " columns, too short to hold coordinates (54); the file looks truncated");
    }
    AtomRecordLayout layout;
    if (has_coordinates_at(line, length, coordinates_column))
    {
      return layout;
    }
    for (std::size_t shift = 1; shift <= max_shift; ++shift)
    {
      if (has_coordinates_at(line, length, coordinates_column + shift) &&
          fit_shifted_layout(line, shift, layout))
      {
        return layout;
      }
    }
    // Coordinates without the usual three decimals are still read from the standard columns.
    for (std::size_t column = coordinates_column; column < coordinates_end; column += 8)
    {
      if (!is_number_field(line + column, 8))
      {
        throw FileError(where() + " has '" + std::string(line + column, 8) +
                        "' in coordinate columns " + std::to_string(column + 1) + "-" +
                        std::to_string(column + 8) + ", not a number");
      }
    }
    return {};
  }

  void read_serial(const char* line, const AtomRecordLayout& layout, PdbAtomFields& fields)
  {
    const char* field = line + serial_column;
    if (layout.serial_extra > 0)
    {
      read_decimal(field, serial_width + layout.serial_extra, fields.serial);
      this->Serials.remember(fields.serial);
    }
    else if (read_decimal(field, serial_width, fields.serial))
    {
      fields.serial = this->Serials.continue_from_field(fields.serial, true);
      this->Scan.continued_serials += this->Serials.continued() ? 1 : 0;
    }
    else if (read_hybrid36(field, serial_width, fields.serial))
    {
      this->Serials.remember(fields.serial);
    }
    else
    {
      fields.serial = 0; // "*****" and the like: no serial
    }
  }

  /// Returns true for a CHARMM five-digit residue number in columns 23-27.
  bool read_residue_number(const char* line, const AtomRecordLayout& layout, PdbAtomFields& fields)
  {
    const char* field = line + residue_number_column + layout.serial_extra;
    const std::size_t width = residue_number_width + layout.residue_number_extra;
    const bool charmm =
      layout.shift() == 0 && is_digit(field[4]) && std::all_of(field, field + 4, is_digit);
    int value = 0;
    if (charmm || layout.residue_number_extra > 0)
    {
      fields.residue_number_read = read_decimal(field, charmm ? 5 : width, value);
      this->ResidueNumbers.remember(value);
    }
    else if (read_decimal(field, width, value))
    {
      const bool same_chain = line[chain_column + layout.serial_extra] == this->Chain;
      value = this->ResidueNumbers.continue_from_field(value, same_chain && !this->AfterTer);
      fields.residue_number_read = true;
      this->Scan.continued_residue_numbers += this->ResidueNumbers.continued() ? 1 : 0;
    }
    else if (read_hybrid36(field, width, value))
    {
      fields.residue_number_read = true;
      this->ResidueNumbers.remember(value);
    }
    fields.residue_number = value;
    return charmm;
  }

  /// Atoms are grouped into residues (as gemmi groups them) by the residue number field:
  /// hybrid-36 keeps the true numbers apart up to its largest code, and far beyond it only residues
  /// 1213056 apart could share one (the fields of each atom still come from the scan).
  static int residue_number_key(int number)
  {
    if (number < -999)
    {
      return -999;
    }
    if (number > largest_residue_code)
    {
      return 10000 + (number - 10000) % int(26 * pow36_3);
    }
    return number;
  }

  /// Residue names are columns 18-20 and, when a program writes four letters, 21; gemmi reads
  /// three, and column 21 as the first of a two-letter chain.
  void read_residue_name_end(char* line, PdbAtomFields& fields)
  {
    const char* name = line + residue_name_column;
    if (name[3] == ' ' || name[0] == ' ' || name[1] == ' ' || name[2] == ' ')
    {
      return;
    }
    if (line[chain_column] == ' ')
    {
      fields.residue_name_end = name[3];
      line[residue_name_column + 3] = ' ';
      return;
    }
    const gemmi::ResidueInfo info = gemmi::find_tabulated_residue(std::string(name, 3));
    this->TwoLetterChains = this->TwoLetterChains || info.is_standard() || info.is_water();
    this->FourLetterCandidates.emplace_back(this->Scan.atoms.size(), line);
  }

  PdbTextScan& Scan;
  const std::string& Path;
  NumberContinuation Serials{ 100000 };
  NumberContinuation ResidueNumbers{ 10000 };
  char Chain = '\0';
  bool AfterTer = false;
  bool TwoLetterChains = false;
  std::vector<std::pair<std::size_t, char*>> FourLetterCandidates;
};

/// The serials of one CONECT record (columns 7-11, then four or more 5-wide fields).
void read_conect(const char* line, std::size_t length, PdbTextScan& scan)
{
  std::size_t end = length;
  while (end > 6 && line[end - 1] == ' ')
  {
    --end;
  }
  // Serials over 99999 written in full run into each other ("CONECT100000100001"), and no split
  // of them is certain. Right-justified fields end the record on a field boundary and never
  // start with a zero digit, which such a record breaks.
  const bool touching = std::search_n(line + 6, line + end, 6, ' ',
                                      [](char c, char) { return c != ' '; }) != line + end;
  bool run_together = touching && (end - 6) % 5 != 0;
  for (std::size_t column = 6; touching && column + 1 < end && !run_together; column += 5)
  {
    run_together = line[column] == '0' && is_digit(line[column + 1]);
  }
  if (run_together)
  {
    ++scan.run_together_conect_records;
    return;
  }
  auto field = [&](std::size_t column) -> int {
    if (column + 5 > length)
    {
      return 0;
    }
    int value = 0;
    if (read_hybrid36(line + column, 5, value))
    {
      return value;
    }
    if (std::any_of(line + column, line + column + 5, [](char c) { return c != ' '; }))
    {
      ++scan.unreadable_conect_fields;
    }
    return 0;
  };
  const int from = field(6);
  for (std::size_t column = 11; column <= 26 && from > 0; column += 5)
  {
    const int to = field(column);
    if (to > 0)
    {
      scan.conect_pairs.emplace_back(from, to);
    }
  }
}

} // namespace

PdbTextScan scan_pdb_text(char* data, std::size_t size, const std::string& path)
{
  PdbTextScan scan;
  AtomRecordScanner atoms(scan, path);
  std::size_t line_number = 0;
  char* line = data;
  char* end = data + size;
  while (line < end)
  {
    char* newline = static_cast<char*>(std::memchr(line, '\n', std::size_t(end - line)));
    const char* line_end = newline ? newline : end;
    std::size_t length = std::size_t(line_end - line);
    if (length > 0 && line[length - 1] == '\r')
    {
      --length;
    }
    ++line_number;
    if (is_atom_record(line, length))
    {
      atoms.scan(line, length, line_number);
    }
    else if (starts_with(line, length, "MODEL") || starts_with(line, length, "ENDMDL"))
    {
      atoms.new_model();
    }
    else if (starts_with(line, length, "TER"))
    {
      atoms.ter();
    }
    else if (length >= 11 && starts_with(line, length, "CONECT"))
    {
      read_conect(line, length, scan);
    }
    line = newline ? newline + 1 : end;
  }
  atoms.finish();
  return scan;
}

} // namespace detail
} // namespace mesolens
