// SPDX-License-Identifier: GPL-3.0-or-later
// REMARK 350 (biological assemblies) of PDB files.
#include "io/detail/assembly_records.h"
#include "io/detail/text_fields.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <string_view>

namespace mesolens {
namespace detail {

namespace {

bool starts_with(std::string_view text, std::string_view prefix)
{
  return text.substr(0, prefix.size()) == prefix;
}

std::string_view trimmed(std::string_view text)
{
  const std::size_t begin = text.find_first_not_of(" \t\r");
  if (begin == std::string_view::npos)
  {
    return {};
  }
  const std::size_t end = text.find_last_not_of(" \t\r");
  return text.substr(begin, end + 1 - begin);
}

/// The REMARK 350 text (from column 12) of a line, or nothing when it is no REMARK 350 line.
bool remark_350(std::string_view line, std::string_view& content)
{
  if (line.size() < 10 || line.substr(7, 3) != "350")
  {
    return false;
  }
  for (std::size_t i = 0; i < 6; ++i)
  {
    if (std::toupper(static_cast<unsigned char>(line[i])) != "REMARK"[i])
    {
      return false;
    }
  }
  content = trimmed(line.size() > 11 ? line.substr(11) : std::string_view());
  return true;
}

/// Reads REMARK 350 lines one at a time.
class Remark350Reader
{
public:
  void read(std::string_view content, std::size_t line_number)
  {
    this->Line = line_number;
    if (starts_with(content, "BIOMOLECULE:"))
    {
      this->finish_operator();
      this->Assemblies.emplace_back();
      this->Assemblies.back().name = std::string(trimmed(content.substr(12)));
      this->Problems.emplace_back();
    }
    else if (starts_with(content, "APPLY THE FOLLOWING TO CHAINS:"))
    {
      this->finish_operator();
      if (Assembly* assembly = this->current())
      {
        assembly->generators.emplace_back();
        this->add_chains(content.substr(30));
      }
    }
    else if (starts_with(content, "AND CHAINS:"))
    {
      Assembly* assembly = this->current();
      if (assembly &&
          (assembly->generators.empty() || this->PendingRows > 0 ||
           !assembly->generators.back().operators.empty()))
      {
        this->problem("an AND CHAINS line that continues no chain list");
      }
      else if (assembly)
      {
        this->add_chains(content.substr(11));
      }
    }
    else if (starts_with(content, "BIOMT"))
    {
      this->biomt(content);
    }
    else if (starts_with(content, "AUTHOR DETERMINED BIOLOGICAL UNIT:") ||
             starts_with(content, "SOFTWARE DETERMINED QUATERNARY STRUCTURE:"))
    {
      if (!this->Assemblies.empty() &&
          (this->Assemblies.back().details.empty() || content[0] == 'A'))
      {
        this->Assemblies.back().details = std::string(content);
      }
    }
  }

  std::vector<Assembly> finish(std::vector<std::string>& warnings)
  {
    this->finish_operator();
    if (this->Orphans > 0)
    {
      warnings.push_back(std::to_string(this->Orphans) +
                         " REMARK 350 chain or BIOMT lines come before any BIOMOLECULE line; "
                         "they were ignored");
    }
    std::vector<Assembly> kept;
    for (std::size_t a = 0; a < this->Assemblies.size(); ++a)
    {
      if (this->Problems[a].empty())
      {
        kept.push_back(std::move(this->Assemblies[a]));
        continue;
      }
      warnings.push_back("assembly '" + this->Assemblies[a].name + "' (REMARK 350) has " +
                         this->Problems[a] + "; the assembly was left out");
    }
    return kept;
  }

private:
  Assembly* current()
  {
    if (this->Assemblies.empty())
    {
      ++this->Orphans;
      return nullptr;
    }
    return &this->Assemblies.back();
  }

  void problem(const std::string& what)
  {
    if (!this->Problems.empty() && this->Problems.back().empty())
    {
      this->Problems.back() = what + " (line " + std::to_string(this->Line) + ")";
    }
  }

  void add_chains(std::string_view list)
  {
    std::vector<std::string>& chains = this->Assemblies.back().generators.back().chains;
    std::string text(list);
    std::replace(text.begin(), text.end(), ',', ' ');
    for (const std::string_view word : split_words(text))
    {
      if (std::find(chains.begin(), chains.end(), word) == chains.end())
      {
        chains.emplace_back(word);
      }
    }
  }

  /// One BIOMTn line: "BIOMTn serial m1 m2 m3 t" as blank-separated words.
  void biomt(std::string_view content)
  {
    Assembly* assembly = this->current();
    if (!assembly)
    {
      return;
    }
    const int row = content.size() > 5 ? content[5] - '1' : -1;
    // Read for each of thousands of lines in a virus capsid's file: no allocation.
    std::array<std::string_view, 5> words;
    const std::size_t word_count = split_words(
      content.size() > 6 ? content.substr(6) : std::string_view(), words.data(), words.size());
    double values[4];
    long long serial = 0;
    bool numbers = row >= 0 && row < 3 && (content.size() == 6 || content[6] == ' ') &&
      word_count == 5 && parse_integer(words[0], serial);
    for (std::size_t i = 0; numbers && i < 4; ++i)
    {
      numbers = parse_number(words[i + 1], values[i]);
    }
    if (!numbers)
    {
      this->problem("a BIOMT line that is not 'BIOMTn serial m1 m2 m3 t'");
      return;
    }
    if (row != this->PendingRows || (row > 0 && serial != this->PendingSerial))
    {
      this->problem("BIOMT" + std::to_string(row + 1) + " of operator " + std::string(words[0]) +
                    " out of order");
      this->PendingRows = 0;
      return;
    }
    this->PendingSerial = serial;
    std::copy(values, values + 4, this->Pending.matrix.begin() + 4 * row);
    this->PendingRows = row + 1;
    if (row < 2)
    {
      return;
    }
    this->PendingRows = 0;
    if (assembly->generators.empty())
    {
      this->problem("an operator before any APPLY THE FOLLOWING TO CHAINS line");
      return;
    }
    this->Pending.name = std::string(words[0]);
    assembly->generators.back().operators.push_back(this->Pending);
  }

  void finish_operator()
  {
    if (this->PendingRows > 0)
    {
      this->problem("operator " + std::to_string(this->PendingSerial) + " without its BIOMT" +
                    std::to_string(this->PendingRows + 1));
      this->PendingRows = 0;
    }
  }

  std::vector<Assembly> Assemblies;
  std::vector<std::string> Problems; ///< per assembly, its first problem, "" when none
  std::size_t Orphans = 0;
  std::size_t Line = 0;
  int PendingRows = 0; ///< BIOMT rows read of the operator being read
  long long PendingSerial = 0;
  AssemblyOperator Pending;
};

} // namespace

std::vector<Assembly> read_pdb_assemblies(const std::vector<NumberedLine>& remarks,
                                          std::vector<std::string>& warnings)
{
  Remark350Reader reader;
  for (const NumberedLine& line : remarks)
  {
    std::string_view content;
    if (remark_350(line.text, content))
    {
      reader.read(content, line.number);
    }
  }
  std::vector<Assembly> assemblies = reader.finish(warnings);
  check_assemblies(assemblies, warnings);
  return assemblies;
}

} // namespace detail
} // namespace mesolens
